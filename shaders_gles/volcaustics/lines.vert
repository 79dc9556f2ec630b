// volcaustics pass 3, line construction without a geometry shader (research §6.3): drawn as
// glDrawArrays(GL_LINES, 0, 2 R^2); vertex gl_VertexID >> 1 is the caustic-buffer texel, its low bit
// the end (p1 or p2). The segment is clipped to the medium's box (light outside the medium
// scatters nothing); an invalid texel or an empty segment goes outside the clip volume.
precision highp float;
precision highp int;
#include "volcaustics/medium.glsl"
uniform highp sampler2D u_p1;
uniform highp sampler2D u_p2;
uniform highp sampler2D u_flux;
uniform int u_res;
uniform mat4 u_view_proj;
flat out vec3 v_p1;      // the reflection point (attenuation starts there)
flat out vec3 v_a;       // the clipped segment's ends
flat out vec3 v_b;
flat out vec3 v_flux;
void main()
{
    int idx = gl_VertexID >> 1;
    ivec2 q = ivec2(idx % u_res, idx / u_res);
    vec4 p1 = texelFetch(u_p1, q, 0);
    vec3 p2 = texelFetch(u_p2, q, 0).xyz;
    vec3 d = p2 - p1.xyz;
    float len = length(d);
    vec2 c = len > 0.0 ? vc_clip(p1.xyz, d / len, len) : vec2(0.0);
    v_p1 = p1.xyz;
    v_flux = texelFetch(u_flux, q, 0).rgb;
    if (p1.w < 0.5 || c.y <= c.x) {
        v_a = v_b = vec3(0.0);
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);   // outside the clip volume: no fragment
        return;
    }
    v_a = p1.xyz + d / len * c.x;
    v_b = p1.xyz + d / len * c.y;
    gl_Position = u_view_proj * vec4((gl_VertexID & 1) == 0 ? v_a : v_b, 1.0);
}
