/* Oracle tests of the reference tracer's participating medium (app/ref/medium.h) against closed
 * forms, on in-memory scenes:
 *   - the Henyey-Greenstein phase function integrates to 1 (the 1/4pi the seed's Eq. 2.22 loses) and
 *     its samples have mean cosine g;
 *   - transmittance through a slab: an emitter of radiance Le seen through a box of medium of width
 *     w shows Le exp(-sigma_t w) in its surfaces term (and, for a pure absorber, in the full image);
 *   - the airlight integral of a collimated beam: a directional light of E lux entering a box of
 *     medium at its top, seen along a camera ray:
 *       L = int_{t0}^{t1} exp(-sigma_t (t - t0)) sigma_s p(cos) E exp(-sigma_t (h - y(t))) dt,
 *     in closed form since y(t) is linear in t;
 *   - volume caustics of a plane mirror (light tracing, L S+ V E) equal the airlight of the
 *     mirror-image light without the mirror;
 *   - the terms partition the paths: airlight + vcaustics + surfaces + multiple = all, sample by
 *     sample. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ref/medium.h"
#include "ref/render.h"
#include "ref/trace.h"
#include "test_ref_scenes.h"

static void set_medium(test_scene *t, vec3 sigma_s, vec3 sigma_a, float g)
{
    gk_medium *m = &t->s.medium;
    m->present = true;
    m->sigma_s[0] = sigma_s.x, m->sigma_s[1] = sigma_s.y, m->sigma_s[2] = sigma_s.z;
    m->sigma_a[0] = sigma_a.x, m->sigma_a[1] = sigma_a.y, m->sigma_a[2] = sigma_a.z;
    m->g = g;
}

static void set_bounds(test_scene *t, vec3 lo, vec3 hi)
{
    t->s.medium.bounded = true;
    t->s.medium.box_min = lo;
    t->s.medium.box_max = hi;
}

static void render(const gk_ref_scene *rs, int spp, unsigned terms, uint64_t seed, gk_ref_result *r)
{
    gk_ref_options o;
    gk_ref_options_default(&o);
    o.spp = spp;
    o.terms = terms;
    o.seed = seed;
    o.threads = 2;
    gk_err e = {0};
    assert_int_equal(gk_ref_render(rs, &o, r, &e), 0);
}

/* The p_HG integral over the sphere by the midpoint rule in cos (2 pi int p dcos), and the mean
 * cosine of 200k samples: sigma of the mean is sqrt((1 - g^2)/3 / 2e5) < 1.3e-3, so 5e-3 is ~4 sigma. */
static void phase_is_normalised_and_sampled(void **state)
{
    (void)state;
    const float gs[] = {-0.7f, 0.0f, 0.3f, 0.7f};
    for (size_t k = 0; k < sizeof gs / sizeof gs[0]; k++) {
        float g = gs[k];
        double integral = 0.0;
        const int n = 200000;
        for (int i = 0; i < n; i++) {
            double c = -1.0 + (i + 0.5) * 2.0 / n;
            integral += 2.0 * M_PI * gk_phase_hg(g, (float)c) * 2.0 / n;
        }
        assert_true(fabs(integral - 1.0) < 1e-3);
        gk_rng rng;
        gk_rng_seed(&rng, 7, k, 0, 0);
        vec3 d = v3_norm(v3(0.3f, -0.5f, 0.8f));
        double mean_cos = 0.0;
        for (int i = 0; i < n; i++) {
            float u1 = gk_rng_float(&rng), u2 = gk_rng_float(&rng);
            vec3 w = gk_phase_hg_sample(g, d, u1, u2);
            assert_true(fabsf(v3_len(w) - 1.0f) < 1e-4f);
            mean_cos += v3_dot(w, d);
        }
        mean_cos /= n;
        printf("# HG g=%.1f: integral %.6f, sampled mean cos %.4f\n", (double)g, integral, mean_cos);
        assert_true(fabs(mean_cos - g) < 5e-3);
    }
}

/* An emitter (Le = 1, facing the camera) 4 m away behind a slab of medium 2 m thick. */
static void build_slab(test_scene *t, gk_ref_scene *rs, vec3 sigma_s, vec3 sigma_a)
{
    ts_init(t);
    int m = ts_material(t, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f);
    t->mats[m].emissive[0] = t->mats[m].emissive[1] = t->mats[m].emissive[2] = 1.0f;
    ts_quad(t, v3(-5, -5, -4), v3(10, 0, 0), v3(0, 10, 0), m); /* faces +z, towards the eye */
    set_medium(t, sigma_s, sigma_a, 0.0f);
    set_bounds(t, v3(-10, -10, -3), v3(10, 10, -1));
    t->eye = v3(0, 0, 0);
    t->target = v3(0, 0, -1);
    t->yfov = 0.2f;
    assert_int_equal(ts_build(t, rs, 16, 16), 0);
}

/* The image mean of each channel against Le exp(-sigma_t w) for the ray through each pixel (the
 * slab is crossed obliquely off axis: w / cos). Binomial noise (pass or not) of 16x16x1024 paths:
 * sigma of the mean sqrt((1 - T) / (T N)) = 0.26% at T = e^-1, so 1% is ~4 sigma. */
static void slab_transmittance(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    const vec3 ss = v3(0.3f, 0.3f, 0.3f), sa[2] = {v3(0.2f, 0.2f, 0.2f), v3(0.1f, 0.25f, 0.4f)};
    for (int colour = 0; colour < 2; colour++) {
        build_slab(&t, &rs, ss, sa[colour]);
        gk_ref_result r;
        render(&rs, 1024, GK_TERM_SURFACES, 11, &r);
        vec3 st = v3_add(ss, sa[colour]);
        double got[3] = {0, 0, 0}, want[3] = {0, 0, 0};
        for (int y = 0; y < 16; y++)
            for (int x = 0; x < 16; x++) {
                vec3 d = gk_ref_camera_dir(&rs, x + 0.5f, y + 0.5f);
                float len = 2.0f / fabsf(d.z);
                const float *px = &r.rgb[3 * (y * 16 + x)];
                got[0] += px[0], got[1] += px[1], got[2] += px[2];
                want[0] += exp(-st.x * len), want[1] += exp(-st.y * len), want[2] += exp(-st.z * len);
            }
        for (int c = 0; c < 3; c++) {
            printf("# slab (%s) channel %d: mean %.5f, closed form %.5f (%.2f%%)\n", colour ? "coloured" : "grey", c,
                   got[c] / 256, want[c] / 256, 100.0 * (got[c] / want[c] - 1.0));
            assert_true(fabs(got[c] / want[c] - 1.0) < 0.01);
        }
        gk_ref_result_free(&r);
        gk_ref_scene_free(&rs);
    }
    /* A pure absorber scatters nothing: the full image is the surfaces term. */
    build_slab(&t, &rs, v3(0, 0, 0), v3(0.5f, 0.5f, 0.5f));
    gk_ref_result r;
    render(&rs, 1024, GK_TERM_ALL, 12, &r);
    double got = 0.0, want = 0.0;
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            vec3 d = gk_ref_camera_dir(&rs, x + 0.5f, y + 0.5f);
            got += r.rgb[3 * (y * 16 + x)];
            want += exp(-0.5 * 2.0 / fabs(d.z));
        }
    printf("# slab (absorber, all terms): %.5f vs %.5f\n", got / 256, want / 256);
    assert_true(fabs(got / want - 1.0) < 0.01);
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
}

/* The box [lo, hi] along o + t d: [t0, t1], false if missed (an independent slab test). */
static bool box_clip(vec3 o, vec3 d, vec3 lo, vec3 hi, double *t0, double *t1)
{
    double a = 0.0, b = 1e30;
    const double os[3] = {o.x, o.y, o.z}, ds[3] = {d.x, d.y, d.z}, l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
    for (int k = 0; k < 3; k++) {
        if (ds[k] == 0.0) {
            if (os[k] < l[k] || os[k] > h[k])
                return false;
            continue;
        }
        double ta = (l[k] - os[k]) / ds[k], tb = (h[k] - os[k]) / ds[k];
        a = fmax(a, fmin(ta, tb));
        b = fmin(b, fmax(ta, tb));
    }
    *t0 = a, *t1 = b;
    return b > a;
}

/* Airlight of a collimated beam: light of E = 2 lux travelling along -y into the box
 * x in [-1, 1], y in [0, 1.5], z in [-1, 1]; the camera 4 m away on the x axis at y = 0.6 looks
 * across it; behind the box only a black wall. The airlight term per pixel against the closed form
 * (header), compared as the image mean over the pixels that see the box (the closed form is
 * evaluated per pixel): measured noise of the mean ~0.15%, so 1% is a wide margin; g = 0.5 so the
 * phase angle matters. */
static void collimated_beam_airlight(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    ts_init(&t);
    int black = ts_material(&t, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f);
    ts_quad(&t, v3(6, -10, 10), v3(0, 20, 0), v3(0, 0, -20), black); /* faces -x */
    ts_light(&t, GK_LIGHT_DIRECTIONAL, v3(0, 5, 0), v3(0, -1, 0), v3(1, 0, 0), 2.0f);
    const vec3 ss = v3(0.4f, 0.4f, 0.4f), sa = v3(0.2f, 0.2f, 0.2f);
    const float g = 0.5f, E = 2.0f, h = 1.5f;
    const vec3 lo = v3(-1, 0, -1), hi = v3(1, h, 1);
    set_medium(&t, ss, sa, g);
    set_bounds(&t, lo, hi);
    t.eye = v3(-4, 0.6f, 0);
    t.target = v3(0, 0.6f, 0);
    t.yfov = 0.4f;
    assert_int_equal(ts_build(&t, &rs, 16, 16), 0);
    gk_ref_result r;
    render(&rs, 512, GK_TERM_AIRLIGHT, 13, &r);
    double got = 0.0, want = 0.0, st = ss.x + sa.x;
    int n = 0;
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            vec3 d = gk_ref_camera_dir(&rs, x + 0.5f, y + 0.5f);
            double t0, t1;
            if (!box_clip(t.eye, d, lo, hi, &t0, &t1))
                continue;
            /* exponent -st (t - t0) - st (h - y0 - dy t) = -st (h - y0 - t0) - st (1 - dy) t */
            double y0 = t.eye.y, dy = d.y, k = st * (1.0 - dy);
            double p = (1.0 - g * g) / (4.0 * M_PI * pow(1.0 + g * g - 2.0 * g * dy, 1.5)); /* cos = dot(-y, -d) */
            double integral = (exp(-k * t0) - exp(-k * t1)) / k;
            want += ss.x * p * E * exp(-st * (h - y0 - t0)) * integral;
            got += r.rgb[3 * (y * 16 + x)];
            n++;
        }
    printf("# collimated beam airlight: %d pixels, mean %.6f, closed form %.6f (%.2f%%)\n", n, got / n, want / n,
           100.0 * (got / want - 1.0));
    assert_true(n > 100);
    assert_true(fabs(got / want - 1.0) < 0.01);
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
}

/* The airlight integral of a point light (Sun et al. 2005's single-scattering integral), which has
 * no elementary closed form: evaluated per pixel by the midpoint rule with 20000 steps (converged
 * to < 1e-5 relative: the integrand is smooth, the light 0.5 m off every ray) and compared with the
 * tracer's airlight term as the image mean. An unbounded medium, g = -0.4, a black wall ending the
 * rays at z = -4. Measured noise of the mean ~0.1%; 1% bound. */
static void point_light_airlight_integral(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    ts_init(&t);
    int black = ts_material(&t, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f);
    ts_quad(&t, v3(-10, -10, -4), v3(20, 0, 0), v3(0, 20, 0), black); /* faces +z */
    const vec3 P = v3(0.5f, 0.3f, -2.0f);
    const float I = 5.0f, g = -0.4f, ss = 0.3f, sa = 0.1f, st = ss + sa;
    ts_light(&t, GK_LIGHT_POINT, P, v3(0, -1, 0), v3(1, 0, 0), I);
    set_medium(&t, v3(ss, ss, ss), v3(sa, sa, sa), g);
    t.eye = v3(0, 0, 0);
    t.target = v3(0, 0, -1);
    t.yfov = 0.5f;
    assert_int_equal(ts_build(&t, &rs, 16, 16), 0);
    gk_ref_result r;
    render(&rs, 512, GK_TERM_AIRLIGHT, 17, &r);
    double got = 0.0, want = 0.0;
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            vec3 d = gk_ref_camera_dir(&rs, x + 0.5f, y + 0.5f);
            double tend = 4.0 / -d.z, sum = 0.0;
            const int n = 20000;
            for (int i = 0; i < n; i++) {
                double tt = (i + 0.5) * tend / n;
                double px = d.x * tt - P.x, py = d.y * tt - P.y, pz = d.z * tt - P.z;
                double r2 = px * px + py * py + pz * pz, rr = sqrt(r2);
                /* light travels from P to the point (direction p/rr), then towards the eye (-d) */
                double c = -(px * d.x + py * d.y + pz * d.z) / rr;
                double ph = (1.0 - g * g) / (4.0 * M_PI * pow(1.0 + g * g - 2.0 * g * c, 1.5));
                sum += exp(-st * tt) * ss * ph * I * exp(-st * rr) / r2 * (tend / n);
            }
            want += sum;
            got += r.rgb[3 * (y * 16 + x)];
        }
    printf("# point-light airlight: mean %.6f, quadrature %.6f (%.2f%%), noise floor %.4f\n", got / 256, want / 256,
           100.0 * (got / want - 1.0), r.noise_floor);
    assert_true(fabs(got / want - 1.0) < 0.01);
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
}

/* A point light 1.5 m above a perfect mirror (metallic 1, base 1: reflectance exactly 1) in a box
 * of medium 2 m in front of the camera (so no photon line passes near the pinhole, where a line's
 * pixel value grows as 1/distance and the light tracer's variance with it); the camera looks level at
 * y = 1 with a narrow field, so its rays stay above the mirror until a black wall ends them. The volume caustic of the mirror (vcaustics, light tracing)
 * must equal the airlight of the mirror-image light 1.5 m below the plane in the same scene
 * without the mirror (eye paths with next-event estimation): two independent estimators of one
 * integral. */
static void build_mirror_fog(test_scene *t, gk_ref_scene *rs, bool mirror)
{
    ts_init(t);
    int black = ts_material(t, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f);
    int chrome = ts_material(t, 1.0f, 1.0f, 1.0f, 1.0f, 0.0f);
    ts_quad(t, v3(4, -10, 10), v3(0, 20, 0), v3(0, 0, -20), black); /* faces -x */
    if (mirror)
        ts_quad(t, v3(-30, 0, 30), v3(60, 0, 0), v3(0, 0, -60), chrome); /* faces +y */
    ts_light(t, GK_LIGHT_POINT, v3(1.5f, mirror ? 1.5f : -1.5f, 0), v3(0, -1, 0), v3(1, 0, 0), 10.0f);
    set_medium(t, v3(0.3f, 0.3f, 0.3f), v3(0.1f, 0.1f, 0.1f), 0.3f);
    /* The mirror image of the box is the box itself (symmetric about y = 0), so every light path
       and its unfolded image cross the medium alike. */
    set_bounds(t, v3(0, -3, -2), v3(4, 3, 2));
    t->eye = v3(-2, 1, 0);
    t->target = v3(0, 1, 0);
    t->yfov = 0.3f;
    assert_int_equal(ts_build(t, rs, 16, 16), 0);
}

static void mirror_volume_caustic_equals_image_light(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    build_mirror_fog(&t, &rs, true);
    gk_ref_result b;
    render(&rs, 4096, GK_TERM_VCAUSTICS, 21, &b);
    gk_ref_scene_free(&rs);
    build_mirror_fog(&t, &rs, false);
    gk_ref_result a;
    render(&rs, 256, GK_TERM_AIRLIGHT, 22, &a);
    double sb = 0.0, sa = 0.0;
    for (int i = 0; i < 16 * 16 * 3; i++)
        sb += b.rgb[i], sa += a.rgb[i];
    double rel = gk_ref_rel_rmse(b.rgb, a.rgb, 16 * 16 * 3);
    printf("# mirror volume caustic %.6f vs image-light airlight %.6f (%.2f%%); rel RMSE %.4f, noise floors "
           "%.4f / %.4f\n", sb / 768, sa / 768, 100.0 * (sb / sa - 1.0), rel, b.noise_floor, a.noise_floor);
    assert_true(sa > 0.0);
    /* Measured: per-pixel floors 0.10 (light tracing) and 0.04 (eye paths), so the noise of the two
       768-value means is ~0.4% together; 1% is 2.5 sigma of it (seeds fixed: no flakes), while a
       missing 1/4pi, phase convention or transmittance factor is off by far more. */
    assert_true(fabs(sb / sa - 1.0) < 0.01);
    /* per pixel: within 3 combined noise floors (sqrt of the sum of squares) */
    assert_true(rel < 3.0 * sqrt(b.noise_floor * b.noise_floor + a.noise_floor * a.noise_floor));
    gk_ref_result_free(&a);
    gk_ref_result_free(&b);
    gk_ref_scene_free(&rs);
}

/* A spot on a mirror and a grey floor in fog: the four terms rendered apart add up to the full
 * render, sample by sample (one seed: the random streams stay aligned whatever the terms). */
static void terms_partition_all_paths(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    ts_init(&t);
    int grey = ts_material(&t, 0.6f, 0.6f, 0.6f, 0.0f, 1.0f);
    int chrome = ts_material(&t, 0.9f, 0.9f, 0.9f, 1.0f, 0.0f);
    ts_quad(&t, v3(-3, 0, 3), v3(6, 0, 0), v3(0, 0, -6), grey);           /* floor, faces +y */
    ts_quad(&t, v3(1, 0, 1), v3(0, 1.5f, 0), v3(0, 0, -2), chrome);     /* mirror, faces -x */
    ts_light(&t, GK_LIGHT_SPOT, v3(-1, 1.5f, 0), v3(1, -0.4f, 0), v3(0, 0, 1), 20.0f);
    set_medium(&t, v3(0.3f, 0.35f, 0.4f), v3(0.05f, 0.05f, 0.05f), 0.4f);
    t.eye = v3(-2.5f, 1.2f, 2.5f);
    t.target = v3(0, 0.5f, 0);
    assert_int_equal(ts_build(&t, &rs, 12, 10), 0);
    gk_ref_result all, part[4];
    const unsigned terms[4] = {GK_TERM_AIRLIGHT, GK_TERM_VCAUSTICS, GK_TERM_SURFACES, GK_TERM_MULTIPLE};
    render(&rs, 32, GK_TERM_ALL, 5, &all);
    for (int k = 0; k < 4; k++)
        render(&rs, 32, terms[k], 5, &part[k]);
    double worst = 0.0, mean = 0.0, term_mean[4] = {0, 0, 0, 0};
    for (int i = 0; i < 12 * 10 * 3; i++) {
        double sum = 0.0;
        for (int k = 0; k < 4; k++) {
            sum += part[k].rgb[i];
            term_mean[k] += part[k].rgb[i] / 360.0;
        }
        worst = fmax(worst, fabs(sum - all.rgb[i]));
        mean += all.rgb[i] / 360.0;
    }
    printf("# terms: airlight %.4f vcaustics %.4f surfaces %.4f multiple %.4f, all %.4f; worst |sum - all| %.2g\n",
           term_mean[0], term_mean[1], term_mean[2], term_mean[3], mean, worst);
    for (int k = 0; k < 4; k++)
        assert_true(term_mean[k] > 0.0); /* every term is present in this scene */
    assert_true(worst <= 1e-4 * mean); /* float rounding of the sums only */
    gk_ref_result_free(&all);
    for (int k = 0; k < 4; k++)
        gk_ref_result_free(&part[k]);
    gk_ref_scene_free(&rs);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(phase_is_normalised_and_sampled),
        cmocka_unit_test(slab_transmittance),
        cmocka_unit_test(collimated_beam_airlight),
        cmocka_unit_test(point_light_airlight_integral),
        cmocka_unit_test(mirror_volume_caustic_equals_image_light),
        cmocka_unit_test(terms_partition_all_paths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
