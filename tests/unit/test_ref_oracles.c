/* Oracle tests of the reference path tracer against analytic answers, on in-memory scenes:
 * white furnace, point light over a plane, area-light visibility (plane over plane), caustics of a
 * point light in a mirror (light tracing) against the mirror-image light, and the path-class
 * partition direct + indirect + caustics = all. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ref/lights.h"
#include "ref/render.h"
#include "ref/trace.h"
#include "test_ref_scenes.h"

static void render_or_fail(const gk_ref_scene *rs, int spp, unsigned paths, uint64_t seed, int threads, gk_ref_result *r)
{
    gk_ref_options o;
    gk_ref_options_default(&o);
    o.spp = spp;
    o.paths = paths;
    o.seed = seed;
    o.threads = threads;
    gk_err e = {0};
    assert_int_equal(gk_ref_render(rs, &o, r, &e), 0);
}

/* Closed box, every wall albedo a = 0.8 and emission Le = 1: the radiance everywhere is
 * Le / (1 - a) = 5 (the GGX lobe is dropped so the albedo is exactly a, see ref_scene.h). */
static void build_furnace(test_scene *t, gk_ref_scene *rs, int size)
{
    ts_init(t);
    int m = ts_material(t, 0.8f, 0.8f, 0.8f, 0.0f, 1.0f);
    t->mats[m].emissive[0] = t->mats[m].emissive[1] = t->mats[m].emissive[2] = 1.0f;
    ts_box(t, v3(-1, -1, -1), v3(1, 1, 1), m, 1);
    t->eye = v3(0.1f, -0.2f, 0.05f);
    t->target = v3(0.5f, 0.3f, 1.0f);
    assert_int_equal(ts_build(t, rs, size, size), 0);
    rs->diffuse_only = true;
}

static void render_opts(const gk_ref_scene *rs, int spp, int rr_depth, gk_ref_result *r)
{
    gk_ref_options o;
    gk_ref_options_default(&o);
    o.spp = spp;
    o.seed = 3;
    o.threads = 2;
    o.rr_depth = rr_depth;
    gk_err e = {0};
    assert_int_equal(gk_ref_render(rs, &o, r, &e), 0);
}

/* Every pixel within 0.5% of Le/(1-a). Without Russian roulette the only error is the depth-32
 * truncation (a^33 = 6e-4 of the answer) and noise: measured per-pixel floor 0.13% at 4096 spp,
 * so the worst of 16 pixels sits near 0.3%. */
static void furnace_every_pixel(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    build_furnace(&t, &rs, 4);
    gk_ref_result r;
    render_opts(&rs, 4096, 1000, &r);
    double worst = 0.0;
    for (int i = 0; i < 4 * 4 * 3; i++)
        worst = fmax(worst, fabs(r.rgb[i] / 5.0 - 1.0));
    printf("# furnace (no RR, 4096 spp): worst pixel error %.3f%%, noise floor %.3f%%\n", 100.0 * worst,
           100.0 * r.noise_floor);
    assert_true(worst < 0.005);
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
}

/* Russian roulette (default settings) must stay unbiased: the image mean within 0.5% of 5. RR
 * raises the per-pixel noise (measured floor ~1% at 4096 spp), so the mean of 64 independent
 * pixels has sigma ~0.13%: 0.5% is about 4 sigma, while a biased roulette (e.g. not dividing by
 * the survival probability) is off by tens of percent. */
static void furnace_roulette_unbiased(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    build_furnace(&t, &rs, 8);
    gk_ref_result r;
    gk_ref_options d;
    gk_ref_options_default(&d);
    render_opts(&rs, 4096, d.rr_depth, &r);
    double mean = 0.0;
    for (int i = 0; i < 8 * 8 * 3; i++)
        mean += r.rgb[i] / (8 * 8 * 3);
    printf("# furnace (RR from vertex %d): mean %.5f (expected 5), error %.3f%%, noise floor %.3f%%\n", d.rr_depth,
           mean, 100.0 * fabs(mean / 5.0 - 1.0), 100.0 * r.noise_floor);
    assert_true(fabs(mean / 5.0 - 1.0) < 0.005);
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
}

static float plane_hit(vec3 o, vec3 d, vec3 *x)
{
    float t = -o.y / d.y;
    *x = v3_add(o, v3_scale(d, t));
    return t;
}

/* A point light of I cd over a plane: radiance f(wo, wi) I cos / d^2 in every pixel, exactly
 * (one delta light: next-event estimation has no variance; nothing else to bounce off). */
static void point_light_over_plane(void **state)
{
    (void)state;
    static test_scene t;
    ts_init(&t);
    int m = ts_material(&t, 0.5f, 0.5f, 0.5f, 0.0f, 0.6f);
    ts_quad(&t, v3(-10, 0, -10), v3(0, 0, 20), v3(20, 0, 0), m);
    vec3 lp = v3(0.3f, 2.0f, 0.2f);
    ts_light(&t, GK_LIGHT_POINT, lp, v3(0, -1, 0), v3(1, 0, 0), 10.0f);
    t.eye = v3(0, 3, 3);
    t.target = v3(0, 0, 0);
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, 16, 16), 0);
    gk_ref_result r;
    render_or_fail(&rs, 4, GK_PATH_ALL, 1, 1, &r);
    double worst = 0.0;
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            vec3 p;
            plane_hit(rs.eye, gk_ref_camera_dir(&rs, x + 0.5f, y + 0.5f), &p);
            vec3 wi = v3_sub(lp, p);
            float d2 = v3_dot(wi, wi);
            wi = v3_norm(wi);
            vec3 wo = v3_norm(v3_sub(rs.eye, p));
            float expect = ts_brdf_spec(0.5f, 0.0f, 0.6f, v3(0, 1, 0), wo, wi) * 10.0f * wi.y / d2;
            worst = fmax(worst, fabs(r.rgb[3 * (y * 16 + x)] / expect - 1.0));
        }
    printf("# point light over plane: worst relative error %.2e\n", worst);
    assert_true(worst < 1e-3); /* float rounding only (measured ~1e-6) */
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
}

/* dong-001 §9.2 T1: receiver y = 0, black 2x2 occluder at y = 1, square light S = 1 at y = 4
 * facing down. From receiver point x the occluder projects onto the light plane scaled by
 * k = 4/1 about x, so V = 1 - overlap_x overlap_z / S^2 exactly. The light sampler is uniform by
 * area, so the fraction of unoccluded light samples estimates V. */
static double overlap(double a0, double a1, double b0, double b1) { return fmax(0.0, fmin(a1, b1) - fmax(a0, b0)); }

static void area_light_visibility(void **state)
{
    (void)state;
    static test_scene t;
    ts_init(&t);
    int recv = ts_material(&t, 0.8f, 0.8f, 0.8f, 0.0f, 1.0f);
    int black = ts_material(&t, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f);
    ts_quad(&t, v3(-5, 0, -5), v3(0, 0, 10), v3(10, 0, 0), recv);
    ts_quad(&t, v3(-1, 1, -1), v3(2, 0, 0), v3(0, 0, 2), black);
    gk_light *l = ts_light(&t, GK_LIGHT_POINT, v3(0, 4, 0), v3(0, -1, 0), v3(1, 0, 0), 1.0f);
    l->shape = GK_SHAPE_RECT;
    l->size[0] = l->size[1] = 1.0f;
    t.eye = v3(0, 6, 6);
    t.target = v3(0, 0, 0);
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, 8, 8), 0);
    const int N = 16384;
    double worst = 0.0;
    int penumbra_points = 0;
    for (int i = 0; i < 21; i++) {
        /* penumbra in x for px in (1.167, 1.5); every other point also in z's penumbra */
        double px = 1.10 + 0.02 * i, pz = (i % 2) ? 0.2 - 0.01 * i : 1.2 + 0.015 * i;
        double ox = overlap(-4.0 - 3.0 * px, 4.0 - 3.0 * px, -0.5, 0.5);
        double oz = overlap(-4.0 - 3.0 * pz, 4.0 - 3.0 * pz, -0.5, 0.5);
        double v_exact = 1.0 - ox * oz;
        penumbra_points += v_exact > 0.02 && v_exact < 0.98;
        gk_rng rng;
        gk_rng_seed(&rng, 11, (uint64_t)i, 0, 0);
        vec3 p = v3((float)px, 1e-4f, (float)pz);
        int visible = 0;
        for (int k = 0; k < N; k++) {
            gk_light_sample ls;
            assert_true(gk_light_sample_from(&rs, p, &rng, &ls));
            visible += !gk_scene_occluded(&rs, p, ls.wi, ls.dist * (1.0f - 1e-4f));
        }
        double v = (double)visible / N;
        worst = fmax(worst, fabs(v - v_exact));
    }
    printf("# visibility: worst |V - V_exact| = %.4f over 21 points (%d in the penumbra)\n", worst, penumbra_points);
    assert_true(penumbra_points >= 4);
    /* binomial sigma <= sqrt(0.25 / 16384) = 0.0039; 0.02 is 5 sigma */
    assert_true(worst < 0.02);
    gk_ref_scene_free(&rs);
}

/* Point light between a diffuse floor (y = 0) and a perfect mirror ceiling (y = 2, F0 = 1): the
 * floor's caustic (L S D E, light tracing) is lit by the mirror-image light at y = 2*2 - 1 = 3,
 * the direct part by the light itself. */
static void build_mirror_scene(test_scene *t, vec3 lp)
{
    ts_init(t);
    int floor_m = ts_material(t, 0.5f, 0.5f, 0.5f, 0.0f, 0.6f);
    int mirror = ts_material(t, 1.0f, 1.0f, 1.0f, 1.0f, 0.0f);
    ts_quad(t, v3(-10, 0, -10), v3(0, 0, 20), v3(20, 0, 0), floor_m);
    ts_quad(t, v3(-10, 2, -10), v3(20, 0, 0), v3(0, 0, 20), mirror);
    ts_light(t, GK_LIGHT_POINT, lp, v3(0, -1, 0), v3(1, 0, 0), 10.0f);
    t->eye = v3(0, 1.5f, 2.5f);
    t->target = v3(0, 0, 0);
}

static void mirror_caustic_matches_image_light(void **state)
{
    (void)state;
    static test_scene t;
    vec3 lp = v3(0, 1, 0), img = v3(0, 3, 0);
    build_mirror_scene(&t, lp);
    enum { W = 32 };
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, W, W), 0);
    assert_true(rs.has_delta_lights && rs.has_delta_surfaces);
    gk_ref_result rc, rd;
    render_or_fail(&rs, 512, GK_PATH_CAUSTICS, 5, 2, &rc);
    render_or_fail(&rs, 4, GK_PATH_DIRECT, 5, 2, &rd);
    double sum_r = 0.0, sum_e = 0.0, worst_direct = 0.0, worst_block = 0.0;
    double blk_r[2][2] = {{0}}, blk_e[2][2] = {{0}};
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            vec3 p;
            plane_hit(rs.eye, gk_ref_camera_dir(&rs, x + 0.5f, y + 0.5f), &p);
            vec3 wo = v3_norm(v3_sub(rs.eye, p));
            vec3 wi = v3_sub(img, p);
            float d2 = v3_dot(wi, wi);
            wi = v3_norm(wi);
            double e_c = ts_brdf_spec(0.5f, 0.0f, 0.6f, v3(0, 1, 0), wo, wi) * 10.0 * wi.y / d2;
            wi = v3_sub(lp, p);
            d2 = v3_dot(wi, wi);
            wi = v3_norm(wi);
            double e_d = ts_brdf_spec(0.5f, 0.0f, 0.6f, v3(0, 1, 0), wo, wi) * 10.0 * wi.y / d2;
            double r = rc.rgb[3 * (y * W + x)];
            sum_r += r;
            sum_e += e_c;
            blk_r[y / 16][x / 16] += r;
            blk_e[y / 16][x / 16] += e_c;
            worst_direct = fmax(worst_direct, fabs(rd.rgb[3 * (y * W + x)] / e_d - 1.0));
        }
    for (int by = 0; by < 2; by++)
        for (int bx = 0; bx < 2; bx++)
            worst_block = fmax(worst_block, fabs(blk_r[by][bx] / blk_e[by][bx] - 1.0));
    printf("# mirror caustic: mean ratio %.4f, worst 16x16 block %.4f, direct worst %.2e, floor %.4f\n",
           sum_r / sum_e, worst_block, worst_direct, rc.noise_floor);
    /* Per-pixel noise of the caustic at 512 spp is ~23% (floor printed above): the image mean has
       sigma ~0.7% and a 16x16 block ~1.5%; the bounds are about 4 sigma. */
    assert_true(fabs(sum_r / sum_e - 1.0) < 0.03);
    assert_true(worst_block < 0.06);
    assert_true(worst_direct < 1e-3);
    gk_ref_result_free(&rc);
    gk_ref_result_free(&rd);
    gk_ref_scene_free(&rs);
}

/* The three classes partition the paths: with one seed each class render draws the same random
 * numbers as the full render, so they add up to it up to float rounding, and each is non-zero. */
static void classes_add_up_to_all(void **state)
{
    (void)state;
    static test_scene t;
    build_mirror_scene(&t, v3(0, 1, 0));
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, 16, 16), 0);
    gk_ref_result all, part[3];
    unsigned masks[3] = {GK_PATH_DIRECT, GK_PATH_INDIRECT, GK_PATH_CAUSTICS};
    render_or_fail(&rs, 16, GK_PATH_ALL, 9, 2, &all);
    double means[3] = {0};
    for (int k = 0; k < 3; k++)
        render_or_fail(&rs, 16, masks[k], 9, 2, &part[k]);
    double worst = 0.0, mean_all = 0.0;
    for (int i = 0; i < 16 * 16 * 3; i++) {
        double s = part[0].rgb[i] + part[1].rgb[i] + part[2].rgb[i];
        worst = fmax(worst, fabs(s - all.rgb[i]) / fmax(all.rgb[i], 1e-6));
        mean_all += all.rgb[i];
        for (int k = 0; k < 3; k++)
            means[k] += part[k].rgb[i];
    }
    printf("# partition: direct %.4f indirect %.4f caustics %.4f of all; worst pixel mismatch %.2e\n",
           means[0] / mean_all, means[1] / mean_all, means[2] / mean_all, worst);
    for (int k = 0; k < 3; k++)
        assert_true(means[k] / mean_all > 0.01);
    assert_true(worst < 1e-4);
    gk_ref_result_free(&all);
    for (int k = 0; k < 3; k++)
        gk_ref_result_free(&part[k]);
    gk_ref_scene_free(&rs);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(furnace_every_pixel),
        cmocka_unit_test(furnace_roulette_unbiased),
        cmocka_unit_test(point_light_over_plane),
        cmocka_unit_test(area_light_visibility),
        cmocka_unit_test(mirror_caustic_matches_image_light),
        cmocka_unit_test(classes_add_up_to_all),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
