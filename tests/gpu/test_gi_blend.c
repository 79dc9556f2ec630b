/* No pops (scheduler issue): when the GI method or a budget level changes, the renderer fades the GI
 * contribution from the old result to the new over `gi_blend` frames (app/render/render_gi_blend.c).
 * On the shipped Cornell box (a static scene: the only frame-to-frame change is the switch itself),
 * the same frames are drawn with the fade off (gi_blend=0: the raw jump J) and on (gi_blend=4), and
 * the test asserts that
 *   - before the switch the two runs are the same image (the fade's copy changes nothing),
 *   - the switch is a real pop (J above a stated fraction of the image), so the bound can fail,
 *   - with the fade, no frame-to-frame change exceeds J/4 (plus fp16 rounding), both in the mean
 *     and at every pixel, the mean moves monotonically, and
 *   - from the 4th frame after the switch on, the image is the new result alone.
 * Switches: vct_mips aniso -> iso (the step the issue saw cut the bounce light to 30% in one frame),
 * vct -> none, none -> vct, and vct at render_scale 1 -> 0.75 (the held result at another size). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "common/gl_fixture.h"
#include "io/image_io.h"
#include "render/renderer.h"
#include "scene/scene.h"

#define W 64
#define H 48
#define FRAMES 8
#define SWITCH 3 /* first frame drawn with the new method/levels */

static gkt_shipped T; /* the Cornell box */

/* fp16 storage of the image before GI, the held contribution and the blended image: relative
   rounding 2^-11 each. The comparisons below allow 3 such roundings of the pixel's value plus a
   floor for near-black pixels: 3 * 2^-11 = 0.0015 (relative), 1e-4 absolute. Measured worst excess
   over the exact J/4 on llvmpipe: printed by each case. */
#define FP16_REL 0.0015
#define FP16_ABS 1e-4

static int setup(void **state)
{
    (void)state;
    return gkt_shipped_open(&T, "config/scenes/cornell.gltf", W, H);
}

static int teardown(void **state)
{
    (void)state;
    gkt_shipped_close(&T);
    return 0;
}

static float lum(const float *p) { return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]; }

/* A renderer on the Cornell box and the budgets of the two sides of a switch: `common` pinned in
   both, pins_a in a, pins_b in b. */
static gk_renderer *open_switch(const char *common, const char *pins_a, const char *pins_b, gk_budget *a, gk_budget *b)
{
    gk_err e = {0};
    gk_render_opts o = {.width = W, .height = H, .gles_version = 31, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, &e);
    assert_non_null(r);
    assert_int_equal(gk_renderer_set_scene(r, T.scene, &e), 0);
    gk_budget_init(a);
    gk_budget_init(b);
    gk_renderer_declare_knobs(r, a);
    gk_renderer_declare_knobs(r, b);
    char list[256];
    snprintf(list, sizeof list, "%s%s%s", common, pins_a[0] ? "," : "", pins_a);
    assert_true(gk_budget_pin_list(a, list, &e) >= 0);
    snprintf(list, sizeof list, "%s%s%s", common, pins_b[0] ? "," : "", pins_b);
    assert_true(gk_budget_pin_list(b, list, &e) >= 0);
    return r;
}

/* Draws FRAMES frames: method_a/pins_a before SWITCH, method_b/pins_b from it on; img[f] gets each
   frame's linear image (RGBA, W x H). common: pins of both sides (gi_blend). */
static void draw_run(const char *common, const char *method_a, const char *pins_a, const char *method_b,
                     const char *pins_b, float *img[FRAMES])
{
    gk_err e = {0};
    gk_budget a, b;
    gk_renderer *r = open_switch(common, pins_a, pins_b, &a, &b);
    for (int f = 0; f < FRAMES; f++) {
        bool after = f >= SWITCH;
        gk_frame_params fp = {.time_s = 0, .method = after ? method_b : method_a, .budget = after ? &b : &a};
        gk_frame_report rep;
        if (gk_renderer_draw(r, &fp, T.fb.fbo, &rep, &e) != 0)
            fail_msg("frame %d: %s", f, e.msg);
        gk_image im;
        assert_int_equal(gk_renderer_read_linear(r, &im, &e), 0);
        assert_int_equal(im.width * im.height, W * H);
        memcpy(img[f], im.pixels, sizeof(float) * 4 * W * H);
        gk_image_free(&im);
    }
    gk_renderer_destroy(r);
}

static double mean_lum(const float *p)
{
    double s = 0;
    for (int i = 0; i < W * H; i++)
        s += lum(p + 4 * i);
    return s / (W * H);
}

/* Largest per-pixel |luminance(a) - luminance(b)|. */
static double max_pixel_step(const float *a, const float *b)
{
    double m = 0;
    for (int i = 0; i < W * H; i++)
        m = fmax(m, fabs(lum(a + 4 * i) - lum(b + 4 * i)));
    return m;
}

static void check_switch(const char *name, const char *method_a, const char *pins_a, const char *method_b,
                         const char *pins_b, double min_jump)
{
    float *off[FRAMES], *on[FRAMES], *direct[FRAMES];
    for (int f = 0; f < FRAMES; f++) {
        off[f] = malloc(sizeof(float) * 4 * W * H);
        on[f] = malloc(sizeof(float) * 4 * W * H);
        direct[f] = malloc(sizeof(float) * 4 * W * H);
    }
    draw_run("gi_blend=0", method_a, pins_a, method_b, pins_b, off);
    draw_run("gi_blend=4", method_a, pins_a, method_b, pins_b, on);
    /* the same switch without GI: what changes in the direct light (the render scale), not faded */
    draw_run("gi_blend=0", "none", pins_a, "none", pins_b, direct);

    double m_before = mean_lum(off[SWITCH - 1]), m_after = mean_lum(off[SWITCH]);
    double jump = m_after - m_before;
    double d_jump = mean_lum(direct[SWITCH]) - mean_lum(direct[SWITCH - 1]);
    double pix_jump = max_pixel_step(off[SWITCH - 1], off[SWITCH]);
    double worst_mean_step = 0, worst_pix_step = 0;
    for (int f = SWITCH; f < FRAMES; f++) {
        worst_mean_step = fmax(worst_mean_step, fabs(mean_lum(on[f]) - mean_lum(on[f - 1])));
        worst_pix_step = fmax(worst_pix_step, max_pixel_step(on[f - 1], on[f]));
    }
    double end_diff = max_pixel_step(on[SWITCH + 3], off[SWITCH + 3]);
    print_message("# %s: mean luminance %.4f -> %.4f (jump %.1f%%, of it direct light %.4f), largest pixel jump "
                  "%.4f; faded over 4 frames: largest mean step %.4f (%.2f of the jump), largest pixel step %.4f "
                  "(%.2f); frame +3 vs unfaded %.2g\n",
                  name, m_before, m_after, 100 * fabs(jump) / m_before, d_jump, pix_jump, worst_mean_step,
                  worst_mean_step / fabs(jump), worst_pix_step, worst_pix_step / pix_jump, end_diff);

    /* before the switch: the fade's copy leaves the image as it was */
    for (int f = 0; f < SWITCH; f++)
        assert_true(max_pixel_step(on[f], off[f]) == 0.0);
    /* a real pop (see each case's min_jump) */
    assert_true(fabs(jump) > min_jump * m_before);
    /* The mean of a faded frame: jump = D + G (direct light D, GI G); the first faded frame moves
       D + G/4 and each later one G/4 (held and new contributions are averaged over the same
       image area, whatever their resolution). */
    assert_true(worst_mean_step <= fabs(d_jump) + 0.25 * fabs(jump - d_jump) * (1 + 4 * FP16_REL) + FP16_ABS);
    bool same_size = d_jump == 0.0;
    if (same_size) {
        /* every pixel moves at most a quarter of its own jump per frame (+ fp16 rounding) */
        for (int f = SWITCH; f < FRAMES; f++)
            for (int i = 0; i < W * H; i++) {
                double a = lum(on[f - 1] + 4 * i), b = lum(on[f] + 4 * i);
                double pj = fabs(lum(off[SWITCH] + 4 * i) - lum(off[SWITCH - 1] + 4 * i));
                assert_true(fabs(b - a) <= 0.25 * pj + FP16_REL * fmax(a, b) + FP16_ABS);
            }
        /* monotone: the mean moves towards the new result every frame */
        for (int f = SWITCH; f <= SWITCH + 3; f++)
            assert_true((jump > 0 ? 1 : -1) * (mean_lum(on[f]) - mean_lum(on[f - 1])) >= -FP16_ABS);
    }
    /* from the 4th frame after the switch: the new result alone */
    for (int f = SWITCH + 3; f < FRAMES; f++)
        assert_true(max_pixel_step(on[f], off[f]) <= FP16_REL * 4 + FP16_ABS);
    for (int f = 0; f < FRAMES; f++)
        free(off[f]), free(on[f]), free(direct[f]);
}

/* Bounds on the raw jump (min_jump, fraction of the mean luminance) are set well under what the
   switch measured on llvmpipe (printed above each case's assertion), only to prove the pop exists. */
static void budget_step_is_faded(void **state)
{
    (void)state;
    check_switch("vct_mips aniso -> iso", "vct", "vct_res=32,vct_mips=aniso", "vct", "vct_res=32,vct_mips=iso", 0.02);
}

static void method_switch_off_is_faded(void **state)
{
    (void)state;
    check_switch("vct -> none", "vct", "vct_res=32", "none", "vct_res=32", 0.05);
}

static void method_switch_on_is_faded(void **state)
{
    (void)state;
    check_switch("none -> vct", "none", "vct_res=32", "vct", "vct_res=32", 0.05);
}

static void render_scale_step_is_faded(void **state)
{
    (void)state;
    check_switch("vct, render_scale 1 -> 0.5", "vct", "vct_res=32,render_scale=1", "vct", "vct_res=32,render_scale=0.5",
                 0.005);
}

/* The cross-fade's work (app/render/render_work.c, #21) against a hand count: in every frame with GI
   and gi_blend > 1 the copy of the image before GI reads one texel a pixel (gi.blend_hold: W x H);
   in a frame of a transition the blend reads three a pixel (gi.blend: 3 W x H); at render_scale 0.5
   both count the render size's pixels; nothing is reported unless the frame counts. Cornell has no
   occlusion texture (gi.occlusion does not run). At the switch's frame the hold of the last frame's
   contribution adds 2 bilinear lookups a pixel of the LAST frame's render size to gi.blend_hold
   (tex2d_rgba16f_trilinear, beside the copy's unfiltered texels): 2 W x H and 2 (W/2)(H/2) on a
   switch at one scale, 2 W x H on a switch from render_scale 1 to 0.5, whose copy and blend read the
   new size. */
static double cross_fade_work(gk_renderer *r, const char *pass, const char *kind)
{
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_renderer_pass_work(r, "vct", w, GK_MAX_PASS_WORK);
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].pass, pass) && !strcmp(w[i].kind, kind))
            return w[i].fetches;
    return -1.0;
}

static void cross_fade_work_by_hand(void **state)
{
    (void)state;
    /* the pins of both sides: at one scale the switch is vct_mips', the last one render_scale's */
    static const char *const commons[3] = {"gi_blend=4,render_scale=1", "gi_blend=4,render_scale=0.5", "gi_blend=4"};
    static const char *const pins[3][2] = {{"vct_mips=aniso", "vct_mips=iso"}, {"vct_mips=aniso", "vct_mips=iso"},
                                           {"render_scale=1", "render_scale=0.5"}};
    const double full = (double)W * H, half = (double)(W / 2) * (H / 2);
    const double px[3] = {full, half, half}, last_px[3] = {full, half, full};
    for (int k = 0; k < 3; k++) {
        gk_err e = {0};
        gk_budget a, b;
        gk_renderer *r = open_switch(commons[k], pins[k][0], pins[k][1], &a, &b);
        for (int f = 0; f < 3; f++) {
            assert_true(gk_renderer_count_work(r, f > 0));
            gk_frame_params fp = {.time_s = 0, .method = "vct", .budget = f < 2 ? &a : &b};
            gk_frame_report rep;
            if (gk_renderer_draw(r, &fp, T.fb.fbo, &rep, &e) != 0)
                fail_msg("frame %d: %s", f, e.msg);
            double copy = cross_fade_work(r, "gi.blend_hold", "tex2d_rgba32f_nearest");
            double hold = cross_fade_work(r, "gi.blend_hold", "tex2d_rgba16f_trilinear");
            double blend = cross_fade_work(r, "gi.blend", "tex2d_rgba16f_trilinear");
            printf("# %s, %s -> %s, frame %d%s: blend_hold %.0f texels + %.0f hold lookups, blend %.0f\n", commons[k],
                   pins[k][0], pins[k][1], f, f == 2 ? " (the switch)" : "", copy, hold, blend);
            assert_true(copy == (f == 0 ? -1.0 : f == 2 ? px[k] : last_px[k])); /* frame 0 does not count */
            assert_true(hold == (f == 2 ? 2.0 * last_px[k] : -1.0)); /* only the switch's frame holds */
            assert_true(blend == (f == 2 ? 3.0 * px[k] : -1.0));     /* ... and blends */
            /* the hold is timed inside gi.blend_hold, whose parent is gi */
            int i = gk_frame_report_find(&rep, "gi.blend_hold");
            assert_true(i >= 0 && rep.pass[i].ms > 0.0 && rep.pass[rep.pass[i].parent].ms >= rep.pass[i].ms);
        }
        gk_renderer_destroy(r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(budget_step_is_faded),
        cmocka_unit_test(method_switch_off_is_faded),
        cmocka_unit_test(method_switch_on_is_faded),
        cmocka_unit_test(render_scale_step_is_faded),
        cmocka_unit_test(cross_fade_work_by_hand),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
