/* The direct pass's counted shadow fetches (app/render/render_work.c, #21) on the shipped Cornell
 * box: the counting variant runs only while asked for; hard shadows fetch once per shaded pixel
 * inside the map, and PCSS (PCSS_BLOCKER_N 6, adaptive PCF of 2..12 a side, shaders_gles/shadow/
 * pcss.glsl) 36 blocker-search fetches for each of those same pixels plus 4..144 PCF fetches where
 * it found a blocker -- so its count is 36 x hard's plus a part that the box's shadows make positive
 * and that is at most 144 x hard's, all of the depth map. Each count goes to the roofline's kind of
 * the format it reads: VSSM reads its R32F min/max mips and R32UI SATs, not the depth map; CSSM its
 * mipmapped RGBA16F bases and two R32F texels per shaded pixel (its depth range, cssm_range),
 * 2 x hard's; CSSM_SAT (shadow=cssm_sat) its RGBA32UI bases' SATs, 4 corners x 4 boxes x 2 bases,
 * and where it finds blockers also the z bases and the R32UI z SATs' 8 gathers. */
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

/* the renderer's shadow knob plus the diagnostic cssm_sat (added first, so the renderer keeps it) */
static const gk_knob_def knob_shadow = {
    .name = "shadow", .owner = "test", .n_values = 5,
    .values = {"hard", "pcss", "vssm", "cssm", "cssm_sat"}, .cost = {1, 1, 1, 1, 1}, .default_level = 0,
};

/* the direct pass's kinds (app/render/render_work.c), the index of fetches[] below */
enum { DEPTH, R32F, R32UI, RGBA32UI, RGBA16F, N_KINDS };
static const char *const kind_names[N_KINDS] = {"tex2d_depth32f_nearest", "tex2d_r32f_nearest",
                                                 "tex2d_r32ui_nearest", "tex2d_rgba32f_nearest",
                                                 "tex2d_rgba16f_trilinear"};

/* One frame of method none at `pins`, counting or not; the direct pass's fetches by kind and the
   number of `direct` entries. */
static int direct_fetches(const char *pins, bool count, double fetches[N_KINDS])
{
    gk_err e = {0};
    gk_render_opts o = {.width = W, .height = H, .gles_version = 31, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, &e);
    assert_non_null(r);
    assert_int_equal(gk_renderer_set_scene(r, T.scene, &e), 0);
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &knob_shadow);
    gk_renderer_declare_knobs(r, &b);
    assert_true(gk_budget_pin_list(&b, pins, &e) >= 0);
    assert_true(gk_renderer_count_work(r, count));
    gk_frame_params fp = {.time_s = 0, .method = "none", .budget = &b};
    gk_frame_report rep;
    if (gk_renderer_draw(r, &fp, T.fb.fbo, &rep, &e) != 0)
        fail_msg("%s: %s", pins, e.msg);
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_renderer_pass_work(r, "none", w, GK_MAX_PASS_WORK), direct = 0;
    for (int k = 0; k < N_KINDS; k++)
        fetches[k] = 0.0;
    for (int i = 0; i < n; i++) {
        if (strcmp(w[i].pass, "direct")) { /* the G-buffer's and the compose's: test_render_work.c;
                                              the maps' fragments and the prefilters:
                                              test_shadow_map_work.c */
            assert_true(!strcmp(w[i].pass, "gbuffer") || !strcmp(w[i].pass, "compose") ||
                        !strcmp(w[i].pass, "shadow.shadow_depth") || !strcmp(w[i].pass, "shadow.vssm_prefilter") ||
                        !strcmp(w[i].pass, "shadow.cssm_prefilter"));
            continue;
        }
        int k = 0;
        while (k < N_KINDS && strcmp(w[i].kind, kind_names[k]))
            k++;
        assert_true(k < N_KINDS);
        fetches[k] += w[i].fetches;
        direct++;
    }
    printf("# %s%s: depth %.0f, r32f %.0f, r32ui %.0f, rgba32ui %.0f, rgba16f %.0f\n", pins,
           count ? "" : " (not counting)", fetches[DEPTH], fetches[R32F], fetches[R32UI], fetches[RGBA32UI],
           fetches[RGBA16F]);
    gk_renderer_destroy(r);
    return direct;
}

static void nothing_counted_unless_asked(void **state)
{
    (void)state;
    double f[N_KINDS];
    assert_int_equal(direct_fetches("shadow=pcss", false, f), 0);
}

static void pcss_is_36_fetches_per_hard_fetch_plus_its_pcf(void **state)
{
    (void)state;
    double hard[N_KINDS], pcss[N_KINDS];
    direct_fetches("shadow=hard", true, hard);
    direct_fetches("shadow=pcss", true, pcss);
    /* the box's ceiling light shades about half of the 96x72 pixels inside its map (3555 measured) */
    assert_true(hard[DEPTH] > 0.25 * W * H && hard[DEPTH] <= (double)W * H);
    for (int k = R32F; k < N_KINDS; k++) /* both read the depth map only */
        assert_true(hard[k] == 0.0 && pcss[k] == 0.0);
    double pcf = pcss[DEPTH] - 36.0 * hard[DEPTH];
    printf("# PCF fetches %.0f = %.2f per shaded pixel\n", pcf, pcf / hard[DEPTH]);
    assert_true(pcf > 0.0);                    /* the boxes' shadows: blockers found */
    assert_true(pcf <= 144.0 * hard[DEPTH]);   /* at most 12x12 per pixel */
}

static void vssm_and_cssm_count_their_kinds(void **state)
{
    (void)state;
    double hard[N_KINDS], vssm[N_KINDS], cssm[N_KINDS], sat[N_KINDS];
    direct_fetches("shadow=hard", true, hard);
    direct_fetches("shadow=vssm", true, vssm);
    direct_fetches("shadow=cssm", true, cssm);
    direct_fetches("shadow=cssm_sat", true, sat);
    assert_true(vssm[DEPTH] == 0.0 && vssm[R32F] > 0.0 && vssm[R32UI] > 0.0);
    assert_true(vssm[RGBA32UI] == 0.0 && vssm[RGBA16F] == 0.0);
    assert_true(cssm[R32F] == 2.0 * hard[DEPTH] && cssm[RGBA16F] > 0.0);
    assert_true(cssm[DEPTH] == 0.0 && cssm[R32UI] == 0.0 && cssm[RGBA32UI] == 0.0);
    /* the SAT form: per shaded pixel the range, then the search kernel's cos/sin boxes (32 corners),
       then for the pixels that found blockers the z bases' 32 and the z SATs' 8 gathers, then the
       penumbra kernel's cos/sin 32 again */
    assert_true(sat[R32F] == 2.0 * hard[DEPTH] && sat[RGBA16F] == 0.0 && sat[DEPTH] == 0.0);
    assert_true(sat[RGBA32UI] >= 32.0 * hard[DEPTH] && sat[RGBA32UI] <= 96.0 * hard[DEPTH]);
    assert_true(sat[R32UI] > 0.0 && sat[R32UI] <= 8.0 * hard[DEPTH]);
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
