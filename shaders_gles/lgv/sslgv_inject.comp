// SSLGV injection (seed 002 §4.3; research B.2.7): each caustic photon is projected to its pixel
// of the screen grid (u_size, a reduced resolution of the camera's view) and accepted when the
// G-buffer surface there lies within h of it, h = C0 sqrt(A / (p N)) (p = 1: the density factor's
// clamp [P_min, P_max] is not given; lgv_internal.h). Its intensity is added as an SH vector
// I y(-Theta) by fixed-point atomics. I is chosen so that the photon's own pixel shows
// f_r Phi / A(p) through the lookup (lookup.frag: 4 (c . y(-n))+ / A(p)): a density estimate whose
// total over the screen is the photons' reflected flux, I = f_r Phi / (4 (y0^2 + a^2 cos g)),
// cos g = (Theta, n) at the receiver (the seed leaves I for the SSLGV unspecified).
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
#include "lgv/common.glsl"
struct Caustic { highp vec4 pos; highp vec4 dir; highp vec4 power; };
layout(std430, binding = 2) readonly buffer Caustics { highp uint n_caustic; highp uint overflow; highp uint pad0;
                                                       highp uint pad1; Caustic caustic[]; };
layout(std430, binding = 8) buffer Screen { highp int grid[]; };
layout(std430, binding = 3) buffer Stats { highp uint st[]; };
uniform highp sampler2D u_gb_depth;
uniform highp sampler2D u_gb_normal;
uniform mat4 u_viewproj;
uniform mat4 u_inv_viewproj;
uniform ivec2 u_size;
uniform float u_h;
uniform float u_fixed;
uniform int u_cap;
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= int(min(n_caustic, uint(u_cap))))
        return;
    Caustic c = caustic[i];
    vec4 clip = u_viewproj * vec4(c.pos.xyz, 1.0);
    if (clip.w <= 0.0)
        return;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0))))
        return; // off screen: lost (research B.5 item 11)
    ivec2 px = ivec2(uv * vec2(u_size));
    vec2 puv = (vec2(px) + 0.5) / vec2(u_size);
    float depth = texture(u_gb_depth, puv).r;
    if (depth >= 1.0)
        return;
    vec4 w = u_inv_viewproj * vec4(vec3(puv, depth) * 2.0 - 1.0, 1.0);
    if (distance(w.xyz / w.w, c.pos.xyz) >= u_h)
        return; // hidden or another surface
    vec3 n = normalize(texture(u_gb_normal, puv).xyz);
    float cg = max(dot(c.dir.xyz, n), 0.05);
    vec3 inten = c.power.rgb / (4.0 * (0.0795775 + 0.2387324 * cg));
    vec4 y = lgv_sh(-c.dir.xyz);
    int b = 12 * (px.y * u_size.x + px.x);
    for (int ch = 0; ch < 3; ch++)
        for (int k = 0; k < 4; k++)
            atomicAdd(grid[b + 4 * ch + k], int(round(inten[ch] * y[k] * u_fixed)));
    atomicAdd(st[4], 1u);
}
