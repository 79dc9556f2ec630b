// A splat's irradiance at the surface seen in this splat pixel (point-sampled from the full G-buffer:
// the seed's low-resolution G-buffer), if that surface is the splat's ("same surface": within
// u_plane_tol·h of the splat's plane and normals within acos(u_normal_cos)):
//   ΔE = Φ · κ(r) · u_kernel_norm / (a1·a2),  κ Gaussian exp(−r²/(2δ)) or cone max(0, 1 − r),
// r the point's distance from the centre in semi-axes (a disk: a1 = a2 = h, r = |x|/h; an ellipse
// of ispm_radius=footprint: r² = (x·e1/a1)² + (x·e2/a2)², h = the larger semi-axis).
// u_kernel_norm = 1/(π·∫κ) deposits Φ (errata A.7 item 3); 1/π is the seed's 1/(πh²), which keeps
// only 43% (Gaussian δ = 0.25) or 33% (cone) of it.
// With u_samples > 1 (ispm_radius=footprint) κ is averaged over u_samples² points of the splat pixel,
// each where its view ray meets the splat's plane: the pixel's integral of the kernel rather than its
// value at the centre, so an ellipse narrower than a pixel (a caustic line's width) still deposits
// its Φ and keeps its peak, where a point-sampled one would alias or need widening to a pixel.
// SPLAT_COUNT_FRAGMENTS: the bench's counting variant (#21, app/gi/ispm/ispm_work.c), one atomic
// add per fragment shaded, discarded or not (fragment-stage storage buffers capability-checked by
// the caller). Never in the kiosk's frames.
// SPLAT_ONE_SAMPLE (ispm_splat.c, where u_samples is 1: ispm_radius seed or density): the kernel at
// the pixel centre's point alone, without the loop, whose second unprojection and plane hit llvmpipe
// ran for every fragment although their results were not used (it runs both sides of a `?:`).
// @variant -
// @variant SPLAT_COUNT_FRAGMENTS
// @variant SPLAT_ONE_SAMPLE
// @variant SPLAT_ONE_SAMPLE SPLAT_COUNT_FRAGMENTS
precision highp float;
#include "common/gbuffer.glsl"
#ifdef SPLAT_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer SplatFragments { highp uint fragments; } splat_counted;
#endif
flat in vec3 v_c;
flat in vec3 v_n;
flat in vec4 v_e1;
flat in vec4 v_e2;
flat in vec3 v_pow;
uniform float u_to_full;       // full-resolution pixels per splat pixel
uniform float u_plane_tol, u_normal_cos, u_kernel_norm, u_delta;
uniform int u_cone;
uniform highp int u_samples;   // kernel samples per splat pixel side (highp: the vertex stage shares it)
layout(location = 0) out vec4 o_e;
void main()
{
#ifdef SPLAT_COUNT_FRAGMENTS
    atomicAdd(splat_counted.fragments, 1u);
#endif
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
    if (abs(dp) > u_plane_tol * max(v_e1.w, v_e2.w) || dot(gb_normal(p), v_n) < u_normal_cos)
        discard;
    // the kernel averaged over the splat pixel: u_samples² view rays through it, each met with the
    // splat's plane (1: the pixel centre's point alone)
    float k = 0.0;
#ifdef SPLAT_ONE_SAMPLE
    vec3 vy = x - v_c;
    float r = length(vec2(dot(vy, v_e1.xyz), dot(vy, v_e2.xyz)));
    if (r < 1.0)
        k += u_cone == 1 ? 1.0 - r : exp(-r * r / (2.0 * u_delta));
#else
    float ns = float(u_samples);
    for (int sy = 0; sy < u_samples; sy++)
        for (int sx = 0; sx < u_samples; sx++) {
            vec2 sub = floor(gl_FragCoord.xy) + (vec2(float(sx), float(sy)) + 0.5) / ns;
            vec3 w = u_samples == 1 ? x : gb_world_at(sub * u_to_full / u_viewport, depth);
            vec3 dir = w - u_eye;
            float den = dot(dir, v_n);
            vec3 y = u_samples == 1 || abs(den) < 1e-9 ? w : u_eye + dir * (dot(v_c - u_eye, v_n) / den);
            vec3 vy = y - v_c;
            float r = length(vec2(dot(vy, v_e1.xyz), dot(vy, v_e2.xyz)));
            if (r < 1.0)
                k += u_cone == 1 ? 1.0 - r : exp(-r * r / (2.0 * u_delta));
        }
    k /= ns * ns;
#endif
    if (k <= 0.0)
        discard;
    o_e = vec4(v_pow * (k * u_kernel_norm / (v_e1.w * v_e2.w)), 1.0);
}
