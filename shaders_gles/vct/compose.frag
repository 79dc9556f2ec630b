// Joint bilateral upsampling (thesis §3.4 after Kopf et al. 2007) of the sparse cone-traced light
// @variant FAITHFUL_COMPOSE=0
// @variant FAITHFUL_COMPOSE=1
// @variant FAITHFUL_COMPOSE=0 VCT_COMPOSE_COUNT_FETCHES
// @variant FAITHFUL_COMPOSE=1 VCT_COMPOSE_COUNT_FETCHES
// and its composition into the renderer's HDR image, drawn with glBlendFunc(GL_ONE, GL_SRC_ALPHA):
//     hdr' = hdr * a + rgb
// Calibrated (default):  rgb = rho_d * D + F0 * L_spec,  a = 1, i.e.
//     hdr' = direct + rho_d / pi * sum_k W_k L_k + F0 L_spec,
//     rho_d = pi x the BRDF's diffuse part for gathered light (brdf_spec.md: albedo (1 - metallic)
//     for a Lambertian surface, times (1 - w max(Fd)) with KHR_materials_specular's weight w),
//     F0 = mix(w c0, albedo, metallic) (0.04 for the default dielectric).
// FAITHFUL_COMPOSE (thesis code): out = albedo (direct + 0.75 GI) * min(0.5 + AO, 1); the renderer's
//     direct image is already multiplied by albedo, so rgb = 0.75 albedo D f + L_spec f, a = f =
//     min(0.5 + AO, 1).
// Upsampling: 3x3 low-resolution taps around the pixel, weight = spatial Gaussian on the distance to
// the tap's traced full-resolution pixel x normal similarity exp(-|dN|^2 / 0.14) (thesis code) x
// plane distance similarity exp(-(dot(N, x_tap - x) / voxel)^2 / 0.14).
// VCT_COMPOSE_COUNT_FETCHES: the bench's counting variant (#21, app/gi/vct/vct_work.c), in its
// untimed frame only: [0] the low-resolution texels read (diffuse and specular, 2 a tap used),
// [1] the G-buffer depth reads of the background tests (the pixel's, then each tap's).
precision highp float;
precision highp int;
#ifdef VCT_COMPOSE_COUNT_FETCHES
layout(std430, binding = 6) buffer VctComposeFetches { highp uint lo_texels; highp uint depth_reads; } compose_counted;
#define COUNT_LO(n) atomicAdd(compose_counted.lo_texels, uint(n))
#define COUNT_DEPTH() atomicAdd(compose_counted.depth_reads, 1u)
#else
#define COUNT_LO(n)
#define COUNT_DEPTH()
#endif
#include "vct/sparse.glsl"
uniform highp sampler2D u_diffuse_lo;
uniform highp sampler2D u_spec_lo;
uniform ivec2 u_low_size;
uniform int u_block;
uniform float u_voxel_world;
uniform float u_spec_enabled;
layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    COUNT_DEPTH();
    if (gb_background(gb_depth(px))) { o_color = vec4(0.0, 0.0, 0.0, 1.0); return; }
    ivec2 full_size = ivec2(u_viewport);
    vec3 N = gb_normal(px);
    vec3 X = vct_world_position(px);
    vec4 dif; vec3 spec;
    if (u_block <= 1) {
        dif = texelFetch(u_diffuse_lo, px, 0);
        spec = texelFetch(u_spec_lo, px, 0).rgb;
        COUNT_LO(2);
    } else {
        ivec2 qc = px / u_block;
        vec4 sd = vec4(0.0); vec3 ss = vec3(0.0); float sw = 0.0;
        vec4 nd = vec4(0.0); vec3 ns = vec3(0.0); float best = 1e30;
        float sigma = float(u_block);
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                ivec2 q = clamp(qc + ivec2(dx, dy), ivec2(0), u_low_size - 1);
                ivec2 tp = sparse_pixel(q, u_block, full_size);
                COUNT_DEPTH();
                if (gb_background(gb_depth(tp))) continue;
                vec3 Nq = gb_normal(tp);
                vec3 Xq = vct_world_position(tp);
                vec2 dp = vec2(tp - px);
                float f = exp(-dot(dp, dp) / (2.0 * sigma * sigma));
                vec3 dn = N - Nq;
                float gn = exp(-dot(dn, dn) / 0.14);
                float pd = dot(N, Xq - X) / u_voxel_world;
                float gd = exp(-pd * pd / 0.14);
                float w = f * gn * gd;
                vec4 d = texelFetch(u_diffuse_lo, q, 0);
                vec3 s = texelFetch(u_spec_lo, q, 0).rgb;
                COUNT_LO(2);
                sd += w * d; ss += w * s; sw += w;
                float dist = dot(dp, dp) + 1e4 * (1.0 - gn * gd);
                if (dist < best) { best = dist; nd = d; ns = s; }
            }
        if (sw > 1e-4) { dif = sd / sw; spec = ss / sw; }
        else { dif = nd; spec = ns; }                  // no similar tap: nearest plausible one
    }
    gk_brdf_material mat = gb_material(px);
    vec3 albedo = mat.base;
    spec *= u_spec_enabled;
#if FAITHFUL_COMPOSE
    float f = min(0.5 + dif.a, 1.0);
    o_color = vec4((0.75 * albedo * dif.rgb + spec) * f, f);
#else
    vec3 rho_d = GK_PI * gk_brdf_diffuse_gathered(mat, dot(N, normalize(u_eye - X)));
    vec3 F0 = mix(mat.spec_weight * mat.c0, albedo, mat.metallic);
    o_color = vec4(rho_d * dif.rgb + F0 * spec, 1.0);
#endif
}
