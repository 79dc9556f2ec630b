/* CSSM's umbra on T1 "plane-over-plane" (#11): the shadow-planes scene's set-up (light S = 1 at
 * y = 4, blocker 2 x 2 at y = 1, receiver y = 0; the rect spot light of test_shadow_accuracy.c).
 * With the depth normalised over [near, far] as the thesis does (cssm_thesis) the 1 m gap is
 * 0.105 of the range while the scaled, clamped K = 4 test needs 0.064 past the shifted receiver
 * (dong-001.md §3.3) plus the shift itself: the umbra kept 0.19-0.22 of the light. cssm and
 * cssm_sat normalise each map layer over the depths it holds (cssm_range.comp), which keeps the
 * thesis's order M = 4, alpha = 1.12 and shift and reaches #11's target, umbra <= 0.05.
 * 128x128 pixels, map 512. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gpu/test_shadow_util.h"

#define W 128
#define H 128

static const gk_knob_def knob_cssm = {
    .name = "shadow", .owner = "test", .n_values = 5,
    .values = {"hard", "cssm", "cssm_sat", "cssm_thesis", "cssm_plane"},
    .cost = {1, 1, 1, 1, 1}, .default_level = 0,
};

static sx_session ses;

static int setup(void **state)
{
    (void)state;
    return sx_open_knob(&ses, W, H, &knob_cssm);
}

static int teardown(void **state)
{
    (void)state;
    sx_close(&ses);
    return 0;
}

static sx_stats measure(const char *method)
{
    sx_setup st = {.S = 1, .light = v3(0, SX_LIGHT_Y, 0), .n_rects = 1, .eye = v3(0, 6, 6), .target = v3(0, 0, 0),
                   .yfov = 1.0471976f};
    st.rect[0] = (sx_rect){-1, 1, -1, 1, 1};
    fx_scene with, without;
    sx_build(&with, &st, true);
    sx_build(&without, &st, false);
    sx_truth t;
    sx_truth_build(&t, &with, &st, W, H);
    static float a[W * H], b[W * H], v[W * H];
    char pins[96];
    gk_err e = {0};
    snprintf(pins, sizeof pins, "shadow=%s,shadow_map=512", method);
    if (gk_renderer_set_scene(ses.r, &without.s, &e) != 0 || sx_draw(&ses, "shadow=hard,shadow_map=512", b) != 0 ||
        gk_renderer_set_scene(ses.r, &with.s, &e) != 0 || sx_draw(&ses, pins, a) != 0)
        fail_msg("render %s: %s", method, e.msg);
    gk_renderer_set_scene(ses.r, NULL, &e);
    sx_ratio(a, b, &t, v);
    sx_stats s = sx_compare(v, &t);
    sx_print("T1 S=1", method, &s);
    sx_truth_free(&t);
    gkt_scene_free(&with);
    gkt_scene_free(&without);
    return s;
}

static void cssm_umbra_at_default_order(void **state)
{
    (void)state;
    sx_stats mm = measure("cssm"), sat = measure("cssm_sat"), thesis = measure("cssm_thesis"),
             plane = measure("cssm_plane");
    assert_true(mm.n[SX_UMBRA] > 300);
    /* Measured umbra / penumbra mean |dV| against the received light: cssm 0.049 / 0.088,
       cssm_sat 0.0001 / 0.062, cssm_thesis 0.217 / 0.092. Bounds: #11's target 0.05 for the
       umbra; the baseline above 0.15 (the test can fail); no penumbra worse than the baseline's. */
    assert_true(mm.mean[SX_UMBRA] <= 0.05 && sat.mean[SX_UMBRA] <= 0.005);
    assert_true(thesis.mean[SX_UMBRA] > 0.15);
    assert_true(mm.mean[SX_PENUMBRA] <= thesis.mean[SX_PENUMBRA] + 0.002);
    assert_true(sat.mean[SX_PENUMBRA] < thesis.mean[SX_PENUMBRA]);
    /* cssm_plane (the environment's lights: the final kernel against the receiver plane instead of
       the slope-scaled shift) on a receiver facing the light: measured the same as cssm, 0.049 /
       0.088 (the plane spans less than the series' shift over the kernel: one lookup, as cssm).
       The same bounds as cssm. */
    assert_true(plane.mean[SX_UMBRA] <= 0.05);
    assert_true(plane.mean[SX_PENUMBRA] <= thesis.mean[SX_PENUMBRA] + 0.002);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cssm_umbra_at_default_order),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
