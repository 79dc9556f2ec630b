/* The vct soft-shadow cone (thesis §3.3, Fig. 17; research vct-003 A.2.6; knob vct_shadow) against
 * the exact visibility of the analytic plane-over-plane scene T1 (dong-001.md §9.2, the closed form
 * of test_shadow_util.h), beside the shadow maps' PCSS, through the real renderer with method vct
 * (its indirect light is ~0 here: the blocker is black and a lone receiver does not light itself,
 * test_vct.c), at the thesis's apertures 9, 6, 3, 0 degrees and the light-sized cone; and
 * Algorithm 1 (A.2.7, knob vct_skip) on vs off: the same visibility within a measured tolerance in
 * fewer cone samples (counted by the shader, gk_vct_stats.last_shadow_steps). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gpu/test_shadow_util.h"

SX_SESSION_GROUP(128)



static const char *const variants[] = {"map", "cone9", "cone6", "cone3", "cone0", "cone"};
enum { V_PCSS, V_CONE9, V_CONE6, V_CONE3, V_CONE0, V_CONE, V_N };

static void measure(int res, sx_stats *stats)
{
    sx_setup st = sx_t1(1.0f);
    fx_scene with, without;
    sx_build(&with, &st, true);
    sx_build(&without, &st, false);
    sx_truth t;
    sx_truth_build(&t, &with, &st, W, H);
    float *a = malloc(sizeof(float) * W * H), *b = malloc(sizeof(float) * W * H), *v = malloc(sizeof(float) * W * H);
    gk_err e = {0};
    char pins[160];
    snprintf(pins, sizeof pins, "shadow=hard,shadow_map=512,vct_shadow=map,vct_res=%d", res);
    if (gk_renderer_set_scene(ses.r, &without.s, &e) != 0 || sx_draw_method(&ses, "vct", pins, b) != 0)
        fail_msg("render without blockers: %s", e.msg);
    if (gk_renderer_set_scene(ses.r, &with.s, &e) != 0)
        fail_msg("set_scene: %s", e.msg);
    for (int m = 0; m < V_N; m++) {
        snprintf(pins, sizeof pins, "shadow=pcss,shadow_map=512,vct_shadow=%s,vct_res=%d,vct_skip=off", variants[m], res);
        if (sx_draw_method(&ses, "vct", pins, a) != 0)
            fail_msg("render %s", variants[m]);
        sx_ratio(a, b, &t, v);
        stats[m] = sx_compare(v, &t);
        char what[32];
        snprintf(what, sizeof what, "T1 %d^3", res);
        sx_print(what, m == V_PCSS ? "pcss (map)" : variants[m], &stats[m]);
    }
    gk_renderer_set_scene(ses.r, NULL, &e);
    free(a);
    free(b);
    free(v);
    sx_truth_free(&t);
    gkt_scene_free(&with);
    gkt_scene_free(&without);
}

static void cone_matches_analytic_t1(void **state)
{
    (void)state;
    sx_stats s64[V_N], s128[V_N];
    measure(64, s64);
    measure(128, s128);
    for (int m = 0; m < V_N; m++)
        assert_true(s128[m].n[SX_PENUMBRA] > 300 && s128[m].n[SX_UMBRA] > 300 && s128[m].n[SX_LIT] > 3000);
    /* Measured (llvmpipe, 128^2 pixels, vct_res 64 / 128, skipping off), mean |dV| umbra / penumbra
       / lit against the received light:
                    64^3                        128^3
         pcss (map) 0      / 0.029 / 0          0      / 0.029 / 0
         cone9      0.229  / 0.167 / 0          0.121  / 0.101 / 0.002
         cone6      0.229  / 0.167 / 0          0.127  / 0.079 / 0.0001
         cone3      0.229  / 0.167 / 0          0.157  / 0.152 / 0
         cone0      0.229  / 0.167 / 0          0.157  / 0.152 / 0
         cone       0.144  / 0.197 / 0.005      0.054  / 0.144 / 0.010   (aperture 0.28: the light's)
       The blocker is a quad one voxel thick: the narrow cones' trilinear samples straddle it and see
       part of its opacity (the umbra lets 12-23% through: the thesis's Fig. 17 leaking, without
       its thin voxelization), and below a voxel's width (64^3: 9 degrees at the blocker's 1 m is
       under one voxel) every fixed aperture reads the same level-0 samples. The light-sized cone
       has the best umbra but a penumbra too dark (bias -0.13: conservative voxels and the
       footprint's reach widen the blocker). PCSS stays 3-5x more accurate here; the cone's case
       is cost (README "Voxel cone tracing"). Bounds: 1.5x the 128^3 measurement (0.005 where
       ~0); the finer grid must help every fixed aperture's umbra, and the light-sized cone must
       beat the thesis's apertures in the umbra. */
    assert_true(s128[V_PCSS].mean[SX_PENUMBRA] < 0.043 && s128[V_PCSS].mean[SX_UMBRA] < 0.005);
    assert_true(s128[V_CONE9].mean[SX_UMBRA] < 0.18 && s128[V_CONE9].mean[SX_PENUMBRA] < 0.15);
    assert_true(s128[V_CONE6].mean[SX_UMBRA] < 0.19 && s128[V_CONE6].mean[SX_PENUMBRA] < 0.12);
    assert_true(s128[V_CONE3].mean[SX_UMBRA] < 0.24 && s128[V_CONE3].mean[SX_PENUMBRA] < 0.23);
    assert_true(s128[V_CONE0].mean[SX_UMBRA] < 0.24 && s128[V_CONE0].mean[SX_PENUMBRA] < 0.23);
    assert_true(s128[V_CONE].mean[SX_UMBRA] < 0.081 && s128[V_CONE].mean[SX_PENUMBRA] < 0.22);
    for (int m = V_CONE9; m < V_N; m++) {
        assert_true(s128[m].mean[SX_LIT] < 0.015);
        assert_true(s128[m].mean[SX_UMBRA] < s64[m].mean[SX_UMBRA]);
        assert_true(s128[m].mean[SX_PENUMBRA] > s128[V_PCSS].mean[SX_PENUMBRA]);
    }
    for (int m = V_CONE9; m <= V_CONE0; m++)
        assert_true(s128[V_CONE].mean[SX_UMBRA] < s128[m].mean[SX_UMBRA]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cone_matches_analytic_t1),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
