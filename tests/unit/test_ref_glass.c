/* The reference tracer's smooth dielectric (glass: KHR_materials_transmission 1 + KHR_materials_ior)
 * against closed forms: Fresnel at normal incidence ((n-1)/(n+1))^2 from both sides, total internal
 * reflection beyond the critical angle, Snell's law for the refracted direction, and the energy
 * that crosses a plane-parallel slab, (1-F)^2 c^2 / (1-F^2) transmitted and the rest reflected,
 * found by a random walk of photons through gk_bsdf_sample_dir between the slab's two faces. The
 * material goes through gk_surface_init, as the tracer's does. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ref/materials.h"

/* A one-triangle scene holding one glass material; the triangle's front face (by winding) is +z
   when up, -z when flipped, so a slab's top and bottom faces both face outwards. */
typedef struct glass_fixture {
    gk_material mat;
    gk_ref_scene rs;
    gk_ref_tri tri;
} glass_fixture;

static void glass_init(glass_fixture *g, float ior, float tint, bool up)
{
    memset(g, 0, sizeof *g);
    gk_material *m = &g->mat;
    m->base_color[0] = m->base_color[1] = m->base_color[2] = tint;
    m->base_color[3] = 1;
    m->base_color_tex = m->metallic_roughness_tex = m->specular_tex = m->specular_color_tex = -1;
    m->emissive_tex = m->normal_tex = m->occlusion_tex = -1;
    m->metallic = 0;
    m->roughness = 0;
    m->transmission = 1;
    m->ior = ior;
    m->specular = 1;
    m->specular_color[0] = m->specular_color[1] = m->specular_color[2] = 1;
    g->rs.materials = m;
    g->rs.n_materials = 1;
    vec3 n = v3(0, 0, up ? 1.0f : -1.0f);
    g->tri.ng = n;
    for (int k = 0; k < 3; k++) {
        g->tri.n[k] = n;
        for (int c = 0; c < 4; c++)
            g->tri.color[k][c] = 1.0f; /* no COLOR_0: white */
    }
    g->tri.material = 0;
}

static gk_surface surface_of(const glass_fixture *g)
{
    gk_surface sf;
    gk_surface_init(&sf, &g->rs, &g->tri, 0.3f, 0.3f);
    return sf;
}

static void fresnel_at_normal_incidence(void **state)
{
    (void)state;
    const float iors[] = {1.0f, 1.33f, 1.5f, 2.4f};
    for (size_t i = 0; i < sizeof iors / sizeof iors[0]; i++) {
        float n = iors[i], r0 = (n - 1) / (n + 1);
        assert_float_equal(gk_fresnel_dielectric(1.0f, n), r0 * r0, 1e-6f);
        assert_float_equal(gk_fresnel_dielectric(1.0f, 1.0f / n), r0 * r0, 1e-6f); /* from inside */
    }
    /* The sampler reflects with that probability: 400k photons straight down onto n = 1.5 glass.
       Binomial sigma sqrt(0.04 0.96 / 4e5) = 3.1e-4; the bound is 5 sigma. */
    glass_fixture g;
    glass_init(&g, 1.5f, 1.0f, true);
    gk_surface sf = surface_of(&g);
    gk_rng rng;
    gk_rng_seed(&rng, 7, 1, 2, 3);
    const int n = 400000;
    int reflected = 0;
    for (int i = 0; i < n; i++) {
        gk_bsdf_sample s;
        assert_true(gk_bsdf_sample_dir(&sf, v3(0, 0, 1), false, &rng, &s));
        assert_true(s.delta);
        if (s.wi.z > 0)
            reflected++;
        else
            assert_float_equal(s.wi.z, -1.0f, 1e-6f); /* straight through */
    }
    double f = (double)reflected / n;
    printf("# n = 1.5, normal incidence: sampled reflectance %.5f, closed form 0.04\n", f);
    assert_true(fabs(f - 0.04) < 5 * sqrt(0.04 * 0.96 / n));
}

/* Inside glass of n = 1.5 the critical angle is asin(1/1.5) = 41.81 deg: at 45 deg every photon
   comes back (mirror direction), at 40 deg some leave along Snell's direction. */
static void total_internal_reflection(void **state)
{
    (void)state;
    glass_fixture g;
    glass_init(&g, 1.5f, 1.0f, true);
    gk_surface sf = surface_of(&g);
    float crit = asinf(1.0f / 1.5f);
    assert_float_equal(gk_fresnel_dielectric(cosf(crit + 1e-3f), 1.0f / 1.5f), 1.0f, 0);
    assert_true(gk_fresnel_dielectric(cosf(crit - 0.01f), 1.0f / 1.5f) < 1.0f);
    gk_rng rng;
    gk_rng_seed(&rng, 9, 1, 2, 3);
    float a = 45.0f * (float)M_PI / 180.0f;
    vec3 wo = v3(sinf(a), 0, -cosf(a)); /* below the surface: the photon travels up inside the glass */
    for (int i = 0; i < 20000; i++) {
        gk_bsdf_sample s;
        assert_true(gk_bsdf_sample_dir(&sf, wo, false, &rng, &s));
        assert_float_equal(s.wi.x, -wo.x, 1e-6f);
        assert_float_equal(s.wi.z, wo.z, 1e-6f);
        assert_float_equal(s.weight.x, 1.0f, 0);
    }
    float b = 40.0f * (float)M_PI / 180.0f;
    wo = v3(sinf(b), 0, -cosf(b));
    int out = 0;
    for (int i = 0; i < 20000; i++) {
        gk_bsdf_sample s;
        assert_true(gk_bsdf_sample_dir(&sf, wo, false, &rng, &s));
        if (s.wi.z > 0) { /* refracted out: Snell, n sin 40 = sin t */
            out++;
            assert_float_equal(s.wi.x, -1.5f * sinf(b), 1e-5f);
        }
    }
    assert_true(out > 0);
}

/* Photons cross a slab between z = 1 (top face, front +z) and z = 0 (bottom face, front -z),
   arriving from above at angle theta; returns the fractions of flux leaving below and above. */
static void slab_walk(float ior, float tint, float theta, int n, double *down, double *up)
{
    glass_fixture top, bottom;
    glass_init(&top, ior, tint, true);
    glass_init(&bottom, ior, tint, false);
    gk_surface st = surface_of(&top), sb = surface_of(&bottom);
    gk_rng rng;
    gk_rng_seed(&rng, 11, 1, 2, 3);
    double fd = 0, fu = 0;
    for (int i = 0; i < n; i++) {
        vec3 dir = v3(sinf(theta), 0, -cosf(theta)); /* travel direction */
        bool at_top = true;
        double w = 1;
        for (int bounce = 0; bounce < 1000; bounce++) {
            gk_bsdf_sample s;
            assert_true(gk_bsdf_sample_dir(at_top ? &st : &sb, v3_scale(dir, -1), false, &rng, &s));
            w *= s.weight.x;
            dir = s.wi;
            bool inside = at_top ? dir.z < 0 : dir.z > 0;
            if (!inside) {
                if (dir.z > 0)
                    fu += w;
                else
                    fd += w;
                break;
            }
            at_top = !at_top;
        }
    }
    *down = fd / n;
    *up = fu / n;
}

/* Bounds: 5 binomial sigmas of the transmitted fraction over n photons (the tint only scales). */
static void energy_through_a_slab(void **state)
{
    (void)state;
    const float thetas[] = {0.0f, 0.7f, 1.3f};
    const int n = 200000;
    for (size_t i = 0; i < sizeof thetas / sizeof thetas[0]; i++) {
        float F = gk_fresnel_dielectric(cosf(thetas[i]), 1.5f);
        double t = (1 - F) / (1 + F); /* (1-F)^2 / (1-F^2): white glass */
        double down, up;
        slab_walk(1.5f, 1.0f, thetas[i], n, &down, &up);
        printf("# slab n = 1.5 at %.2f rad: transmitted %.5f (closed form %.5f), reflected %.5f, sum %.6f\n",
               thetas[i], down, t, up, down + up);
        double sigma = sqrt(t * (1 - t) / n);
        assert_true(fabs(down - t) < 5 * sigma);
        assert_float_equal(down + up, 1.0, 1e-9); /* clear glass loses nothing */
        /* Tinted glass (c = 0.8): each refraction multiplies by c, reflections do not. */
        double ct = 0.64 * (1 - F) * (1 - F) / (1 - F * F), tdown, tup;
        slab_walk(1.5f, 0.8f, thetas[i], n, &tdown, &tup);
        assert_true(fabs(tdown - ct) < 5 * sigma);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fresnel_at_normal_incidence),
        cmocka_unit_test(total_internal_reflection),
        cmocka_unit_test(energy_through_a_slab),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
