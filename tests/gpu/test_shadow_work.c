/* The direct pass's counted shadow fetches (app/render/render_work.c, #21) on the shipped Cornell
 * box: the counting variant runs only while asked for; hard shadows fetch once per shaded pixel
 * inside the map, and PCSS (PCSS_BLOCKER_N 6, adaptive PCF of 2..12 a side, shaders_gles/shadow/
 * pcss.glsl) 36 blocker-search fetches for each of those same pixels plus 4..144 PCF fetches where
 * it found a blocker -- so its count is 36 x hard's plus a part that the box's shadows make positive
 * and that is at most 144 x hard's. VSSM counts unfiltered fetches only; CSSM filtered ones (its
 * bases) and two unfiltered ones per shaded pixel (its depth range, cssm_range), 2 x hard's. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "common/gl_fixture.h"
#include "render/renderer.h"
#include "scene/scene.h"

#define W 96
#define H 72

static gkt_shipped T; /* the Cornell box */

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

/* One frame of method none at `pins`, counting or not; the direct pass's fetches by kind
   ([0] unfiltered 32-bit, [1] filtered RGBA16F) and the number of `direct` entries. */
static int direct_fetches(const char *pins, bool count, double fetches[2])
{
    gk_err e = {0};
    gk_render_opts o = {.width = W, .height = H, .gles_version = 31, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, &e);
    assert_non_null(r);
    assert_int_equal(gk_renderer_set_scene(r, T.scene, &e), 0);
    gk_budget b;
    gk_budget_init(&b);
    gk_renderer_declare_knobs(r, &b);
    assert_true(gk_budget_pin_list(&b, pins, &e) >= 0);
    assert_true(gk_renderer_count_work(r, count));
    gk_frame_params fp = {.time_s = 0, .method = "none", .budget = &b};
    gk_frame_report rep;
    if (gk_renderer_draw(r, &fp, T.fb.fbo, &rep, &e) != 0)
        fail_msg("%s: %s", pins, e.msg);
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_renderer_pass_work(r, "none", w, GK_MAX_PASS_WORK), direct = 0;
    fetches[0] = fetches[1] = 0.0;
    for (int i = 0; i < n; i++) {
        assert_string_equal(w[i].pass, "direct");
        fetches[strcmp(w[i].kind, "tex2d_rgba32f_nearest") == 0 ? 0 : 1] += w[i].fetches;
        direct++;
    }
    printf("# %s%s: %.0f unfiltered, %.0f filtered fetches\n", pins, count ? "" : " (not counting)", fetches[0],
           fetches[1]);
    gk_renderer_destroy(r);
    return direct;
}

static void nothing_counted_unless_asked(void **state)
{
    (void)state;
    double f[2];
    assert_int_equal(direct_fetches("shadow=pcss", false, f), 0);
}

static void pcss_is_36_fetches_per_hard_fetch_plus_its_pcf(void **state)
{
    (void)state;
    double hard[2], pcss[2];
    direct_fetches("shadow=hard", true, hard);
    direct_fetches("shadow=pcss", true, pcss);
    /* the box's ceiling light shades about half of the 96x72 pixels inside its map (3555 measured) */
    assert_true(hard[0] > 0.25 * W * H && hard[0] <= (double)W * H);
    assert_true(hard[1] == 0.0 && pcss[1] == 0.0);
    double pcf = pcss[0] - 36.0 * hard[0];
    printf("# PCF fetches %.0f = %.2f per shaded pixel\n", pcf, pcf / hard[0]);
    assert_true(pcf > 0.0);                /* the boxes' shadows: blockers found */
    assert_true(pcf <= 144.0 * hard[0]);   /* at most 12x12 per pixel */
}

static void vssm_and_cssm_count_their_kinds(void **state)
{
    (void)state;
    double hard[2], vssm[2], cssm[2];
    direct_fetches("shadow=hard", true, hard);
    direct_fetches("shadow=vssm", true, vssm);
    direct_fetches("shadow=cssm", true, cssm);
    assert_true(vssm[0] > hard[0] && vssm[1] == 0.0);
    assert_true(cssm[0] == 2.0 * hard[0] && cssm[1] > 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(nothing_counted_unless_asked),
        cmocka_unit_test(pcss_is_36_fetches_per_hard_fetch_plus_its_pcf),
        cmocka_unit_test(vssm_and_cssm_count_their_kinds),
    };
    return cmocka_run_group_tests_name("shadow_work", tests, setup, teardown);
}
