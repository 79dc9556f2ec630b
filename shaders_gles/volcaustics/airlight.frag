// volcaustics term (A), airlight and volumetric shadows (research §6.1, §6.3 pass 6: "simplest
// substitute: low-res shadowed ray march"): at the march resolution, the view ray from the eye to
// the surface (G-buffer depth) or out of the medium, in u_steps steps with a per-pixel offset
// (interleaved gradient noise: banding traded for noise), adds at each step
//   T(v, x) sigma_s p(cos) I_spot(x) / |x - light|^2 T(light, x) V(x) Delta t
// for each point/spot light (V from the renderer's GI light map, gk_gi_light.shadow_depth_tex), and
// T(v, x) sigma_s p(cos) E T(box, x) V(x) Delta t for a directional light.
// AIRLIGHT_COUNT_FETCHES: the bench's counting variant (app/gi/volcaustics/vc_work.c): the depth
// texels each fragment read (the G-buffer's and the shadow maps'), added to AirFetches once.
// Never in the kiosk's frames.
// @variant -
// @variant AIRLIGHT_COUNT_FETCHES
precision highp float;
precision highp int;
#include "volcaustics/medium.glsl"
#define VC_MAX_LIGHTS 4
#ifdef AIRLIGHT_COUNT_FETCHES
layout(std430, binding = 6) buffer AirFetches { highp uint fetches; } air_counted;
highp uint g_air_fetches = 0u;
#endif
uniform highp sampler2D u_depth;       // the G-buffer depth (full resolution)
uniform highp sampler2D u_shadow0;
uniform highp sampler2D u_shadow1;
uniform highp sampler2D u_shadow2;
uniform highp sampler2D u_shadow3;
uniform int u_n_lights;
uniform int u_light_kind[VC_MAX_LIGHTS];      // 0 point, 1 spot, 2 directional
uniform vec3 u_light_pos[VC_MAX_LIGHTS];
uniform vec3 u_light_dir[VC_MAX_LIGHTS];      // emission axis / travel direction
uniform vec3 u_light_radiant[VC_MAX_LIGHTS];  // cd or lux
uniform vec2 u_light_cone[VC_MAX_LIGHTS];     // cos(outer), cos(inner)
uniform int u_light_shadow[VC_MAX_LIGHTS];    // 1: a shadow map is bound
uniform mat4 u_shadow_vp[VC_MAX_LIGHTS];
uniform mat4 u_inv_view_proj;
uniform vec3 u_eye;
uniform vec2 u_full_size;                     // G-buffer pixels
uniform vec2 u_size;                          // march target pixels
uniform int u_steps;
layout(location = 0) out vec4 o_rad;

float shadow_depth(int i, vec2 uv)
{
#ifdef AIRLIGHT_COUNT_FETCHES
    g_air_fetches++;
#endif
    if (i == 0) return texture(u_shadow0, uv).r;
    if (i == 1) return texture(u_shadow1, uv).r;
    if (i == 2) return texture(u_shadow2, uv).r;
    return texture(u_shadow3, uv).r;
}

float visible(int i, vec3 x)
{
    if (u_light_shadow[i] == 0)
        return 1.0;
    vec4 c = u_shadow_vp[i] * vec4(x, 1.0);
    if (c.w <= 0.0)
        return 1.0;
    vec3 ndc = c.xyz / c.w;
    if (any(greaterThan(abs(ndc.xy), vec2(1.0))))
        return 1.0;
    return ndc.z * 0.5 + 0.5 <= shadow_depth(i, ndc.xy * 0.5 + 0.5) + 2e-4 ? 1.0 : 0.0;
}

void main()
{
    vec2 uv = gl_FragCoord.xy / u_size;
    vec4 cf = u_inv_view_proj * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
    vec3 dv = normalize(cf.xyz / cf.w - u_eye);
    ivec2 fq = clamp(ivec2(uv * u_full_size), ivec2(0), ivec2(u_full_size) - 1);
    float depth = texelFetch(u_depth, fq, 0).r;
#ifdef AIRLIGHT_COUNT_FETCHES
    atomicAdd(air_counted.fetches, 1u); // the march's shadow reads are added at its end
#endif
    float t_surf = 1e6;
    if (depth < 1.0) {
        vec4 cs = u_inv_view_proj * vec4(vec3(uv, depth) * 2.0 - 1.0, 1.0);
        t_surf = distance(cs.xyz / cs.w, u_eye);
    }
    vec2 seg = vc_clip(u_eye, dv, t_surf);
    if (seg.y <= seg.x) {
        o_rad = vec4(0.0);
        return;
    }
    float dt = (seg.y - seg.x) / float(u_steps);
    float jitter = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    vec3 acc = vec3(0.0);
    for (int s = 0; s < u_steps; s++) {
        float t = seg.x + (float(s) + jitter) * dt;
        vec3 x = u_eye + dv * t;
        vec3 tv = exp(-u_sigma_t * (t - seg.x));
        for (int i = 0; i < u_n_lights && i < VC_MAX_LIGHTS; i++) {
            vec3 li;
            vec3 wl;   // direction the light travels at x
            if (u_light_kind[i] == 2) {
                wl = u_light_dir[i];
                vec2 back = vc_clip(x, -wl, 1e6);
                li = u_light_radiant[i] * exp(-u_sigma_t * max(back.y - back.x, 0.0));
            } else {
                vec3 to_x = x - u_light_pos[i];
                float d2 = max(dot(to_x, to_x), 1e-8);
                wl = to_x * inversesqrt(d2);
                float spot = 1.0;
                if (u_light_kind[i] == 1) {
                    float k = clamp((dot(wl, u_light_dir[i]) - u_light_cone[i].x) /
                                    max(u_light_cone[i].y - u_light_cone[i].x, 1e-4), 0.0, 1.0);
                    spot = k * k;
                }
                if (spot <= 0.0)
                    continue;
                li = u_light_radiant[i] * spot / d2 * vc_transmittance(u_light_pos[i], x);
            }
            acc += tv * li * (vc_phase(dot(wl, -dv)) * visible(i, x));
        }
    }
    o_rad = vec4(acc * u_sigma_s * dt, 0.0);
#ifdef AIRLIGHT_COUNT_FETCHES
    atomicAdd(air_counted.fetches, g_air_fetches);
#endif
}
