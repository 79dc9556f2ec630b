// SSLGV injection (seed 002 §4.3; research B.2.7): each caustic photon is projected to its pixel
// of the screen grid (u_size, a reduced resolution of the camera's view) and accepted when the
// G-buffer surface there (at the photon's own screen position) lies within h of it,
// h = C0 sqrt(A / (p N)) (p = 1: the density factor's clamp [P_min, P_max] is not given;
// lgv_internal.h), or within the photon's own position uncertainty (pos.w, the map texel's
// footprint at the hit, trace.comp) where that is larger. Its intensity is added as an SH vector
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
    // x_p: the G-buffer's surface at the photon's own screen position (the plane of the G-buffer
    // pixel it projects into, met by the view ray through the photon), so that the test measures
    // how far the photon is from the visible surface and not how far it is from a pixel's centre
    // (a 160-wide G-buffer pixel spans several h at 0.26M photons: most photons were refused).
    ivec2 gsize = textureSize(u_gb_depth, 0);
    ivec2 gp = min(ivec2(uv * vec2(gsize)), gsize - 1);
    float depth = texelFetch(u_gb_depth, gp, 0).r;
    if (depth >= 1.0)
        return;
    vec2 guv = (vec2(gp) + 0.5) / vec2(gsize);
    vec4 w = u_inv_viewproj * vec4(vec3(guv, depth) * 2.0 - 1.0, 1.0);
    vec3 xc = w.xyz / w.w;
    vec3 n = normalize(texelFetch(u_gb_normal, gp, 0).xyz);
    vec4 near = u_inv_viewproj * vec4(uv * 2.0 - 1.0, -1.0, 1.0);
    vec3 o = near.xyz / near.w, ray = normalize(c.pos.xyz - o);
    float dn = dot(ray, n);
    vec3 xp = abs(dn) > 1e-4 ? o + ray * (dot(xc - o, n) / dn) : xc;
    if (distance(xp, c.pos.xyz) >= max(u_h, c.pos.w))
        return; // hidden or another surface
    float cg = max(dot(c.dir.xyz, n), 0.05);
    vec3 inten = c.power.rgb / (4.0 * (0.0795775 + 0.2387324 * cg));
    vec4 y = lgv_sh(-c.dir.xyz);
    int b = 12 * (px.y * u_size.x + px.x);
    for (int ch = 0; ch < 3; ch++)
        for (int k = 0; k < 4; k++)
            atomicAdd(grid[b + 4 * ch + k], int(round(inten[ch] * y[k] * u_fixed)));
    atomicAdd(st[4], 1u);
}
