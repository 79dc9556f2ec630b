/* The reference tracer's BRDF (app/ref/materials.c, brdf_spec.md: glTF 2.0 Appendix B with
 * KHR_materials_specular) against closed forms, by numeric integration of its own gk_bsdf_eval:
 *   - pointwise equal to the spec's normative form mix(dielectric, metal, metallic), transcribed
 *     independently in tests/unit/test_ref_scenes.h (ts_brdf_gltf);
 *   - directional albedo exactly the base colour with specularFactor 0 (pure Lambert), and every
 *     importance-sampled weight then equals the base colour;
 *   - directional albedo <= 1 for a white base where Appendix B conserves energy (Lambert, metal),
 *     and the measured excess of its dielectric mix at grazing views pinned (see albedo_bounds);
 *   - the importance sampler's mean weight equals the integral (its pdf matches its lobes);
 *   - the diffuse lobe's albedo against the fit the GI methods use for gathered light
 *     (gk_brdf_diffuse_gathered in shaders_gles/common/brdf.glsl).
 * Quadrature: cosine-weighted midpoint grid, A(wo) = pi / N^2 sum f(wo, wi(u1, u2)). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ref/materials.h"
#include "test_ref_scenes.h"

#define QN 512 /* quadrature grid per axis */

typedef struct one_surface {
    gk_material mat;
    gk_ref_tri tri;
    gk_ref_scene rs;
    gk_surface sf;
} one_surface;

/* A surface at the origin with normal +z and the given material parameters (no textures). */
static void make_surface(one_surface *o, vec3 base, float metallic, float roughness, float w, vec3 spec_color)
{
    memset(o, 0, sizeof *o);
    gk_material *m = &o->mat;
    m->base_color[0] = base.x, m->base_color[1] = base.y, m->base_color[2] = base.z, m->base_color[3] = 1;
    m->base_color_tex = m->metallic_roughness_tex = m->specular_tex = m->specular_color_tex = m->emissive_tex = m->normal_tex = m->occlusion_tex = -1;
    m->metallic = metallic;
    m->roughness = roughness;
    m->ior = 1.5f;
    m->specular = w;
    m->specular_color[0] = spec_color.x, m->specular_color[1] = spec_color.y, m->specular_color[2] = spec_color.z;
    for (int k = 0; k < 3; k++) {
        o->tri.n[k] = v3(0, 0, 1);
        for (int c = 0; c < 4; c++)
            o->tri.color[k][c] = 1.0f; /* no COLOR_0: white */
    }
    o->tri.ng = v3(0, 0, 1);
    o->tri.p[1] = v3(1, 0, 0), o->tri.p[2] = v3(0, 1, 0);
    o->rs.materials = m;
    o->rs.n_materials = 1;
    gk_surface_init(&o->sf, &o->rs, &o->tri, 1.0f / 3.0f, 1.0f / 3.0f);
}

static vec3 view_dir(float cos_v) { return v3(sqrtf(fmaxf(0.0f, 1.0f - cos_v * cos_v)), 0.0f, cos_v); }

static vec3 albedo(const gk_surface *sf, vec3 wo)
{
    double s[3] = {0, 0, 0};
    for (int i = 0; i < QN; i++) {
        float u1 = (i + 0.5f) / QN, r = sqrtf(u1), z = sqrtf(1.0f - u1);
        for (int j = 0; j < QN; j++) {
            float phi = 2.0f * (float)GK_PI * (j + 0.5f) / QN;
            float pdf;
            vec3 f = gk_bsdf_eval(sf, wo, v3(r * cosf(phi), r * sinf(phi), z), &pdf);
            s[0] += f.x, s[1] += f.y, s[2] += f.z;
        }
    }
    double k = GK_PI / ((double)QN * QN);
    return v3((float)(s[0] * k), (float)(s[1] * k), (float)(s[2] * k));
}

static float max3(vec3 v) { return fmaxf(v.x, fmaxf(v.y, v.z)); }

static void eval_matches_the_spec_mix_form(void **state)
{
    (void)state;
    const float ms[] = {0.0f, 0.3f, 1.0f}, ws[] = {0.0f, 0.5f, 1.0f}, cs[] = {0.5f, 1.0f, 3.0f};
    double worst = 0.0;
    gk_rng rng;
    gk_rng_seed(&rng, 7, 1, 2, 3);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            for (int c = 0; c < 3; c++) {
                one_surface o;
                make_surface(&o, v3(0.6f, 0.6f, 0.6f), ms[a], 0.5f, ws[b], v3(cs[c], cs[c], cs[c]));
                float c0 = fminf(0.04f * cs[c], 1.0f);
                for (int k = 0; k < 200; k++) {
                    vec3 wo = gk_sample_cosine_hemisphere(gk_rng_float(&rng), gk_rng_float(&rng));
                    vec3 wi = gk_sample_cosine_hemisphere(gk_rng_float(&rng), gk_rng_float(&rng));
                    float pdf;
                    float got = gk_bsdf_eval(&o.sf, wo, wi, &pdf).x;
                    float want = ts_brdf_gltf(0.6f, ms[a], 0.5f, ws[b], c0, v3(0, 0, 1), wo, wi);
                    worst = fmax(worst, fabs(got - want) / fmax(want, 1e-3));
                }
            }
    printf("# f vs the spec's mix form: worst relative difference %.2e over 5400 pairs\n", worst);
    assert_true(worst < 1e-4); /* float rounding only (measured ~1e-6) */
}

static void lambert_when_specular_factor_is_zero(void **state)
{
    (void)state;
    const vec3 base = v3(0.3f, 0.5f, 0.8f);
    const float cosines[] = {1.0f, 0.7f, 0.3f, 0.05f}, roughness[] = {0.0f, 0.3f, 1.0f};
    double worst = 0.0, worst_weight = 0.0;
    gk_rng rng;
    gk_rng_seed(&rng, 11, 1, 2, 3);
    for (int r = 0; r < 3; r++) {
        one_surface o;
        make_surface(&o, base, 0.0f, roughness[r], 0.0f, v3(1, 1, 1));
        for (int c = 0; c < 4; c++) {
            vec3 wo = view_dir(cosines[c]);
            vec3 a = albedo(&o.sf, wo);
            worst = fmax(worst, fmax(fabs(a.x - base.x), fmax(fabs(a.y - base.y), fabs(a.z - base.z))));
            for (int k = 0; k < 2000; k++) {
                gk_bsdf_sample bs;
                assert_true(gk_bsdf_sample_dir(&o.sf, wo, true, &rng, &bs));
                worst_weight = fmax(worst_weight, fabs(bs.weight.y - base.y));
            }
        }
    }
    printf("# specularFactor 0: worst |albedo - base| %.2e, worst |sample weight - base| %.2e\n", worst,
           worst_weight);
    assert_true(worst < 1e-4);        /* a constant integrand: float summation only (measured ~1e-6) */
    assert_true(worst_weight < 1e-5); /* no GGX lobe is mixed in: f cos / pdf = base exactly */
}

/* Directional albedo of a white base. Where Appendix B guarantees energy conservation it must hold:
 * pure Lambert (specularFactor 0) and pure metal (GGX single scattering) stay <= 1. A dielectric
 * with a specular lobe does not: fresnel_mix weights the diffuse lobe by 1 - F(v.h) per light
 * direction, while the GGX lobe's reflection at grazing views is mostly Fresnel-brightened, so the
 * sum exceeds 1 there (the spec names albedo scaling as the energy-conserving coupling; it is not
 * built). Measured here on the 512^2 grid: worst 1.283 at n.v 0.1, roughness 0.3, weight 1 (the
 * importance sampler gives 1.284 for the same case); 1.025 at n.v 0.5; <= 1.001 at n.v 1. The
 * bound pins that measurement (1.283 + 0.007 for the quadrature) so a change of the mix shows. */
static void albedo_bounds(void **state)
{
    (void)state;
    const float ms[] = {0.0f, 0.5f, 1.0f}, ws[] = {0.0f, 0.5f, 1.0f}, rs[] = {0.3f, 0.6f, 1.0f};
    const float cosines[] = {1.0f, 0.5f, 0.1f};
    const vec3 colours[] = {v3(1, 1, 1), v3(25, 5, 0)}; /* default; F0 colour clipped to 1 in red */
    float worst_conserving = 0.0f, worst_dielectric = 0.0f, dielectric_normal = 0.0f, white_min = 1.0f;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 2; c++) {
                    one_surface o;
                    make_surface(&o, v3(1, 1, 1), ms[a], rs[r], ws[b], colours[c]);
                    bool conserving = ws[b] == 0.0f || ms[a] == 1.0f;
                    for (int k = 0; k < 3; k++) {
                        float m = max3(albedo(&o.sf, view_dir(cosines[k])));
                        if (conserving)
                            worst_conserving = fmaxf(worst_conserving, m);
                        else
                            worst_dielectric = fmaxf(worst_dielectric, m);
                        if (!conserving && cosines[k] == 1.0f)
                            dielectric_normal = fmaxf(dielectric_normal, m);
                        if (ms[a] == 0.0f && c == 0 && cosines[k] >= 0.5f)
                            white_min = fminf(white_min, m);
                    }
                }
    printf("# white base: Lambert or metal at most %.5f; with a dielectric specular lobe at most %.5f "
           "(%.5f at normal view); white dielectric (n.v >= 0.5) at least %.4f\n",
           worst_conserving, worst_dielectric, dielectric_normal, white_min);
    assert_true(worst_conserving <= 1.0f + 1e-3f); /* the quadrature's error is ~1e-4 */
    assert_true(dielectric_normal <= 1.0f + 2e-3f);
    assert_true(worst_dielectric <= 1.29f);
    /* not passed by losing light: GGX single scattering loses a few percent at roughness 1; a
       missing lobe would lose far more */
    assert_true(white_min > 0.9f);
}

static void sampling_mean_equals_the_integral(void **state)
{
    (void)state;
    struct { float m, r, w; } cases[] = {{0.0f, 0.5f, 1.0f}, {0.5f, 0.3f, 0.5f}, {1.0f, 0.6f, 1.0f}};
    gk_rng rng;
    gk_rng_seed(&rng, 5, 1, 2, 3);
    for (int c = 0; c < 3; c++) {
        one_surface o;
        make_surface(&o, v3(0.7f, 0.4f, 0.2f), cases[c].m, cases[c].r, cases[c].w, v3(1, 1, 1));
        vec3 wo = view_dir(0.6f);
        float want = albedo(&o.sf, wo).x;
        enum { NS = 400000 };
        double s = 0, s2 = 0;
        for (int k = 0; k < NS; k++) {
            gk_bsdf_sample bs;
            double x = gk_bsdf_sample_dir(&o.sf, wo, true, &rng, &bs) ? bs.weight.x : 0.0;
            s += x, s2 += x * x;
        }
        double mean = s / NS, sigma = sqrt(fmax(s2 / NS - mean * mean, 0.0) / NS);
        printf("# sampling case %d: mean weight %.5f, integral %.5f, sigma %.5f\n", c, mean, want, sigma);
        assert_true(fabs(mean - want) < 5.0 * sigma + 1e-4);
    }
}

/* The GI methods' diffuse weight for gathered light: for a dielectric the GGX part does not depend
 * on the base colour, so A(base 1) - A(base 0) is the diffuse lobe's albedo, 1 - w (c0 + (1 - c0) X)
 * with X the cosine-weighted mean of (1 - v.h)^5, fitted as 0.028 (1 - n.v)^2.6. */
static void gathered_diffuse_fit(void **state)
{
    (void)state;
    const float cosines[] = {1.0f, 0.8f, 0.5f, 0.3f, 0.1f, 0.02f};
    double worst = 0.0, worst_nv = 0.0;
    for (int k = 0; k < 6; k++) {
        one_surface white, black;
        make_surface(&white, v3(1, 1, 1), 0.0f, 0.5f, 1.0f, v3(1, 1, 1));
        make_surface(&black, v3(0, 0, 0), 0.0f, 0.5f, 1.0f, v3(1, 1, 1));
        vec3 wo = view_dir(cosines[k]);
        double diffuse = albedo(&white.sf, wo).x - albedo(&black.sf, wo).x;
        double mu = cosines[k];
        double fit = 1.0 - (0.04 + 0.96 * 0.028 * pow(1.0 - mu, 2.6));
        double at_nv = 1.0 - (0.04 + 0.96 * pow(1.0 - mu, 5.0)); /* v.h = n.v: the rejected choice */
        printf("# n.v %.2f: diffuse albedo %.5f, fit %.5f, v.h = n.v would give %.5f\n", mu, diffuse, fit, at_nv);
        worst = fmax(worst, fabs(diffuse - fit));
        worst_nv = fmax(worst_nv, fabs(diffuse - at_nv));
    }
    printf("# gathered-light fit: worst |error| %.2e (v.h = n.v: %.2e)\n", worst, worst_nv);
    assert_true(worst < 1e-3); /* the fit's error (6e-4 in X) plus quadrature */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(eval_matches_the_spec_mix_form),
        cmocka_unit_test(lambert_when_specular_factor_is_zero),
        cmocka_unit_test(albedo_bounds),
        cmocka_unit_test(sampling_mean_equals_the_integral),
        cmocka_unit_test(gathered_diffuse_fit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
