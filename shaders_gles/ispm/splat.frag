// A disk's irradiance at the surface seen in this splat pixel (point-sampled from the full G-buffer:
// the seed's low-resolution G-buffer), if that surface is the disk's ("same surface": within
// u_plane_tol·h of the disk's plane and normals within acos(u_normal_cos)):
//   ΔE = Φ · κ(x/h) · u_kernel_norm / h²,  κ Gaussian exp(−x²/(2δ)) or cone max(0, 1 − x).
// u_kernel_norm = 1/(π·∫κ) deposits Φ (errata A.7 item 3); 1/π is the seed's 1/(πh²), which keeps
// only 43% (Gaussian δ = 0.25) or 33% (cone) of it.
precision highp float;
#include "common/gbuffer.glsl"
flat in vec3 v_c;
flat in vec3 v_n;
flat in float v_h;
flat in vec3 v_pow;
uniform float u_to_full;       // full-resolution pixels per splat pixel
uniform float u_plane_tol, u_normal_cos, u_kernel_norm, u_delta;
uniform int u_cone;
layout(location = 0) out vec4 o_e;
void main()
{
    ivec2 p = ivec2(floor(gl_FragCoord.xy * u_to_full));
    float depth = gb_depth(p);
    if (gb_background(depth))
        discard;
    // at the splat pixel's own centre (the full pixel's centre is a quarter splat pixel away at
    // 1/2 scale; the disk's coverage is decided at this centre, so its kernel must be too: the
    // offset lost 2% of small disks' energy)
    vec3 x = gb_world_at(gl_FragCoord.xy * u_to_full / u_viewport, depth);
    vec3 v = x - v_c;
    float dp = dot(v, v_n);
    if (abs(dp) > u_plane_tol * v_h || dot(gb_normal(p), v_n) < u_normal_cos)
        discard;
    float r = length(v - dp * v_n) / v_h;
    if (r >= 1.0)
        discard;
    float k = u_cone == 1 ? 1.0 - r : exp(-r * r / (2.0 * u_delta));
    o_e = vec4(v_pow * (k * u_kernel_norm / (v_h * v_h)), 1.0);
}
