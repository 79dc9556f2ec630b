// Joint bilateral upsampling of the splatted caustic irradiance (seed 000 pass 13, §3.3.2.4) and its
// composition: L += f_d · E_caustic with f_d the BRDF's diffuse part (fresnel_mix, brdf_spec.md), added to the
// HDR image. Each full-resolution pixel takes the 3×3 low-resolution texels around it, weighted
//   w = bilinear · max(n·n', 0)^k · 1/(1 + |d − d'|)   (d = distance to the camera, metres),
// the low-resolution normal and distance being the G-buffer's at the texel's pixel (the splat read
// the same pixel); w = 0 gives 0.
// UPSAMPLE_COUNT_FETCHES: the bench's counting variant (#21, app/gi/ispm/ispm_work.c), the splat
// texels read, one atomic add per pixel (fragment-stage storage buffers capability-checked by the
// caller). Never in the kiosk's frames.
// @variant -
// @variant UPSAMPLE_COUNT_FETCHES
precision highp float;
#ifdef UPSAMPLE_COUNT_FETCHES
layout(std430, binding = 6) buffer UpsampleFetches { highp uint texels; } upsample_counted;
#endif
#include "common/gbuffer.glsl"
uniform highp sampler2D u_low;
uniform float u_to_low;        // splat pixels per full pixel (≤ 1)
uniform float u_k;
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 P = ivec2(gl_FragCoord.xy);
    gk_surface s = gk_read_surface(P);
    if (s.unlit)
        discard;
    float di = length(s.p - u_eye);
    ivec2 lsize = textureSize(u_low, 0);
    vec2 lp = (vec2(P) + 0.5) * u_to_low - 0.5;
    ivec2 c = ivec2(floor(lp + 0.5));
    vec3 acc = vec3(0.0);
    float wsum = 0.0;
#ifdef UPSAMPLE_COUNT_FETCHES
    highp uint fetched = 0u;
#endif
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(c + ivec2(dx, dy), ivec2(0), lsize - 1);
            vec2 f = abs(lp - vec2(q));
            float wx = max(0.0, 1.0 - f.x) * max(0.0, 1.0 - f.y);
            if (wx <= 0.0)
                continue;
            ivec2 pq = min(ivec2(floor((vec2(q) + 0.5) / u_to_low)), ivec2(u_viewport) - 1);
            float dq = gb_depth(pq);
            if (gb_background(dq))
                continue;
            float wn = pow(max(dot(s.n, gb_normal(pq)), 0.0), u_k);
            float wd = 1.0 / (1.0 + abs(di - length(gb_world_at((vec2(pq) + 0.5) / u_viewport, dq) - u_eye)));
            float w = wx * wn * wd;
            acc += w * texelFetch(u_low, q, 0).rgb;
            wsum += w;
#ifdef UPSAMPLE_COUNT_FETCHES
            fetched++;
#endif
        }
#ifdef UPSAMPLE_COUNT_FETCHES
    if (fetched > 0u)
        atomicAdd(upsample_counted.texels, fetched);
#endif
    vec3 E = wsum > 0.0 ? acc / wsum : vec3(0.0);
    // the diffuse part of the glTF BRDF lit by the caustic's irradiance, as vpl's compose does it
    o_color = vec4(gk_brdf_diffuse_gathered(s.m, dot(s.n, s.v)) * E, 0.0);
}
