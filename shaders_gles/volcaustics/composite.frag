// volcaustics composite (research §6.3 pass 8), two full-screen draws over the HDR image:
// VC_ATTENUATE (blend ZERO, SRC_COLOR: multiplies) gives term (C), the renderer's surfaces seen
// through the medium, C x T(v, p) T(s, p), with s the first local light (exact for one light; with
// several, their light paths are attenuated as the first one's); without it (blend ONE, ONE: adds)
// the airlight term (A, bilinear from its reduced resolution), the volume caustics (B) and the
// surface caustics of (C) (vc_surface.c: irradiance E from the light rays' ends, whose flux already
// carries the light-side attenuation): (diffuse albedo / pi) E T(v, p), the diffuse albedo being the
// G-buffer's base colour x (1 - metallic).
// u_terms selects what is shown (vc_output: all, airlight, vcaustics, surfaces), so each term can be
// measured against its reference term.
// COMPOSITE_COUNT_FETCHES: the bench's counting variant (#21, app/gi/volcaustics/vc_work.c): per
// pixel the depth texels, the airlight image's bilinear lookups and the unfiltered caustic images'
// texels it reads (the G-buffer albedo's are not counted), in the bench's untimed frame only.
// @variant VC_ATTENUATE
// @variant VC_ADD
// @variant VC_ATTENUATE COMPOSITE_COUNT_FETCHES
// @variant VC_ADD COMPOSITE_COUNT_FETCHES
precision highp float;
precision highp int;
#ifdef COMPOSITE_COUNT_FETCHES
layout(std430, binding = 6) buffer CompositeFetches { highp uint depth; highp uint airlight; highp uint caustic; }
    composite_counted;
#define COMPOSITE_COUNT(which) atomicAdd(composite_counted.which, 1u)
#else
#define COMPOSITE_COUNT(which)
#endif
#include "volcaustics/medium.glsl"
in vec2 v_uv;
uniform highp sampler2D u_depth;
uniform highp sampler2D u_airlight;
uniform highp sampler2D u_caustics;
uniform mat4 u_inv_view_proj;
uniform vec3 u_eye;
uniform vec3 u_light_pos;
uniform int u_has_light;
uniform int u_terms;          // bits: 1 airlight, 2 volume caustics, 4 surfaces
uniform highp sampler2D u_surface;   // surface caustics' irradiance E (vc_surface.c)
uniform highp sampler2D u_albedo;    // G-buffer: base colour, a = metallic
uniform int u_has_surface;
layout(location = 0) out vec4 o_col;
void main()
{
#ifdef VC_ATTENUATE
    if ((u_terms & 4) == 0) {
        o_col = vec4(0.0);    // surfaces not shown: the HDR image is cleared to the other terms
        return;
    }
    float depth = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
    COMPOSITE_COUNT(depth);
    vec4 c = u_inv_view_proj * vec4(vec3(v_uv, depth < 1.0 ? depth : 1.0) * 2.0 - 1.0, 1.0);
    vec3 p = c.xyz / c.w;
    vec3 t = vc_transmittance(u_eye, p);
    if (u_has_light == 1 && depth < 1.0)
        t *= vc_transmittance(u_light_pos, p);
    o_col = vec4(t, 1.0);
#else
    vec3 sum = vec3(0.0);
    if ((u_terms & 1) != 0) {
        sum += texture(u_airlight, v_uv).rgb;
        COMPOSITE_COUNT(airlight);
    }
    if ((u_terms & 2) != 0) {
        sum += texelFetch(u_caustics, ivec2(gl_FragCoord.xy), 0).rgb;
        COMPOSITE_COUNT(caustic);
    }
    if ((u_terms & 4) != 0 && u_has_surface == 1) {
        float depth = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
        COMPOSITE_COUNT(depth);
        if (depth < 1.0) {
            COMPOSITE_COUNT(caustic); // the surface caustics' irradiance, below
            vec4 c = u_inv_view_proj * vec4(vec3(v_uv, depth) * 2.0 - 1.0, 1.0);
            vec4 alb = texelFetch(u_albedo, ivec2(gl_FragCoord.xy), 0);
            vec3 e = texelFetch(u_surface, ivec2(gl_FragCoord.xy), 0).rgb;
            sum += alb.rgb * (1.0 - alb.a) * (1.0 / 3.14159265) * e * vc_transmittance(u_eye, c.xyz / c.w);
        }
    }
    o_col = vec4(sum, 0.0);
#endif
}
