/* Reference path tracer: determinism across thread counts and Monte Carlo convergence rate. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ref/render.h"
#include "test_ref_scenes.h"

/* dong-001 §9.2 T1 plus a red wall: soft shadows and indirect light; with_caustics adds a mirror
 * and a spot light, so every code path (eye tiles and light-tracing chunks) runs. */
static void build_t1(test_scene *t, gk_ref_scene *rs, int size, int with_caustics)
{
    ts_init(t);
    int recv = ts_material(t, 0.8f, 0.8f, 0.8f, 0.0f, 1.0f);
    int black = ts_material(t, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f);
    int red = ts_material(t, 0.7f, 0.1f, 0.1f, 0.0f, 0.5f);
    int mirror = ts_material(t, 0.9f, 0.9f, 0.9f, 1.0f, 0.0f);
    ts_quad(t, v3(-5, 0, -5), v3(0, 0, 10), v3(10, 0, 0), recv);
    ts_quad(t, v3(-1, 1, -1), v3(2, 0, 0), v3(0, 0, 2), black);
    ts_quad(t, v3(-3, 0, -3), v3(0, 3, 0), v3(0, 0, 6), red);
    if (with_caustics)
        ts_quad(t, v3(2.5f, 0, -3), v3(0, 0, 6), v3(0, 3, 0), mirror);
    gk_light *l = ts_light(t, GK_LIGHT_POINT, v3(0, 4, 0), v3(0, -1, 0), v3(1, 0, 0), 1.0f);
    l->shape = GK_SHAPE_RECT;
    l->size[0] = l->size[1] = 1.0f;
    if (with_caustics)
        ts_light(t, GK_LIGHT_SPOT, v3(1, 3, 1), v3(0.3f, -1, -0.2f), v3(1, 0, 0), 2.0f);
    t->eye = v3(0, 6, 6);
    t->target = v3(0, 0, 0);
    assert_int_equal(ts_build(t, rs, size, size), 0);
}

static void render(const gk_ref_scene *rs, int spp, uint64_t seed, int threads, gk_ref_result *r)
{
    gk_ref_options o;
    gk_ref_options_default(&o);
    o.spp = spp;
    o.seed = seed;
    o.threads = threads;
    gk_err e = {0};
    assert_int_equal(gk_ref_render(rs, &o, r, &e), 0);
}

/* Same seed, 1 vs 2 vs 3 threads: bit-identical images (tiles and light chunks are independent
 * of the thread count; chunk sums are reduced in a fixed order). */
static void threads_bit_identical(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    build_t1(&t, &rs, 24, 1);
    assert_true(rs.has_delta_surfaces);
    gk_ref_result a, b, c, d;
    render(&rs, 8, 42, 1, &a);
    render(&rs, 8, 42, 2, &b);
    render(&rs, 8, 42, 3, &c);
    render(&rs, 8, 43, 2, &d);
    size_t n = 24 * 24 * 3 * sizeof(float);
    assert_memory_equal(a.rgb, b.rgb, n);
    assert_memory_equal(a.rgb, c.rgb, n);
    assert_memory_not_equal(a.rgb, d.rgb, n); /* the seed matters: the comparison can fail */
    gk_ref_result_free(&a);
    gk_ref_result_free(&b);
    gk_ref_result_free(&c);
    gk_ref_result_free(&d);
    gk_ref_scene_free(&rs);
}

/* Error against a 2048-spp reference at 8, 32 and 128 spp (other seeds): the log-log slope of rel
 * RMSE against spp must be -0.5 for an unbiased estimator (on the scene without caustics: their
 * heavy-tailed light-tracing splats make low-spp errors look small, measured slope -0.39); [-0.6, -0.4] allows the sampling
 * error of the RMSE estimates themselves (768 values each) and the reference's own noise. */
static void error_falls_as_inverse_sqrt_spp(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    build_t1(&t, &rs, 16, 0);
    gk_ref_result ref;
    render(&rs, 2048, 1000, 2, &ref);
    const int spp[3] = {8, 32, 128};
    double lx[3], ly[3];
    for (int i = 0; i < 3; i++) {
        gk_ref_result r;
        render(&rs, spp[i], 7 + i, 2, &r);
        double err = gk_ref_rel_rmse(r.rgb, ref.rgb, 16 * 16 * 3);
        lx[i] = log((double)spp[i]);
        ly[i] = log(err);
        printf("# spp %4d: rel RMSE %.4f (own noise floor %.4f)\n", spp[i], err, r.noise_floor);
        gk_ref_result_free(&r);
    }
    double mx = (lx[0] + lx[1] + lx[2]) / 3, my = (ly[0] + ly[1] + ly[2]) / 3, sxy = 0, sxx = 0;
    for (int i = 0; i < 3; i++) {
        sxy += (lx[i] - mx) * (ly[i] - my);
        sxx += (lx[i] - mx) * (lx[i] - mx);
    }
    double slope = sxy / sxx;
    printf("# log-log slope %.3f (expected -0.5)\n", slope);
    assert_true(slope > -0.6 && slope < -0.4);
    gk_ref_result_free(&ref);
    gk_ref_scene_free(&rs);
}

/* The noise floor the renderer reports (from its two half-sample images) predicts the error
 * against an independent high-spp render: at 64 spp the measured rel RMSE should equal
 * sqrt(floor_64^2 + floor_ref^2) within 25% (the RMSE of 768 noisy values varies by a few %). */
static void noise_floor_predicts_error(void **state)
{
    (void)state;
    static test_scene t;
    gk_ref_scene rs;
    build_t1(&t, &rs, 16, 0);
    gk_ref_result ref, r;
    render(&rs, 2048, 2000, 2, &ref);
    render(&rs, 64, 5, 2, &r);
    double err = gk_ref_rel_rmse(r.rgb, ref.rgb, 16 * 16 * 3);
    double predicted = sqrt(r.noise_floor * r.noise_floor + ref.noise_floor * ref.noise_floor);
    printf("# 64 spp: rel RMSE %.4f, predicted from noise floors %.4f\n", err, predicted);
    assert_true(err / predicted > 0.75 && err / predicted < 1.25);
    gk_ref_result_free(&ref);
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(threads_bit_identical),
        cmocka_unit_test(error_falls_as_inverse_sqrt_spp),
        cmocka_unit_test(noise_floor_predicts_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
