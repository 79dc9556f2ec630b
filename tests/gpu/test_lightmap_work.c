/* The lightmap passes' work models (app/gi/lightmap/lm_work.c, #21) against hand counts on the
 * floor view (test_floor_view.h: the floor charted, about a fifth of the view background). The
 * compose looks the light map up once per pixel whose visible surface is charted, and the UV pass
 * rasterizes the charted geometry, here one layer: both are the pixels where the G-buffer holds the
 * floor, counted on the CPU. The IIM blend reads two texels per atlas texel: 2 x the atlas's size
 * (gk_lightmap_stats). Without count_work nothing is reported. (The caustic filter's model is
 * checked in test_lightmap_caustics.c.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "gi/lightmap/lightmap.h"
#include "test_floor_view.h"
#include "test_pass_work.h"

#define W TFV_W
#define HH TFV_H

static gkt_scene T;
static ispm_h H; /* the ispm harness's scene, G-buffer and frame (ih_frame_of) */
static void *LM;

static void one_thread(void *self) { gk_lightmap_set_threads(self, 1); }

static int setup(void **state)
{
    (void)state;
    /* lockstep: the first frame waits for the worker's first result, so it shows the light map */
    LM = tfv_open(&H, &T, "lightmap-work-floor", &gk_gi_lightmap, one_thread, "lightmap_sync=lockstep");
    return LM ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    if (LM)
        gk_gi_lightmap.destroy(LM);
    ih_close_built(&H, &T);
    return 0;
}

static double compose_lookups(void)
{
    return tpw_fetches(&gk_gi_lightmap, LM, "gi.lightmap_compose", "tex2d_rgba16f_trilinear");
}

static double work_of(const char *pass, const char *kind) { return tpw_fetches(&gk_gi_lightmap, LM, pass, kind); }

static void compose_lookups_match_the_charted_pixels(void **state)
{
    (void)state;
    H.count_work = false;
    assert_int_equal(ih_frame_of(&H, &gk_gi_lightmap, LM), 0);
    assert_true(gk_lightmap_get_stats(LM)->shown);
    assert_true(compose_lookups() < 0.0); /* not a counting frame: nothing counted */
    assert_true(work_of("gi.lightmap_uv", "raster_r16f_depth_fill") < 0.0);
    assert_true(work_of("gi.lightmap_blend", "tex2d_rgba32f_nearest") < 0.0);
    H.count_work = true;
    assert_int_equal(ih_frame_of(&H, &gk_gi_lightmap, LM), 0);
    H.count_work = false;
    long floor = tfv_floor_pixels(&H);
    double counted = compose_lookups();
    print_message("# compose: %.0f light-map lookups counted, %ld floor pixels of %d\n", counted, floor, W * HH);
    /* the view's edge is the floor's: part of it background, the rest the floor */
    assert_true(floor > W * HH / 2 && floor < W * HH);
    assert_true(counted == (double)floor);
    double uv = work_of("gi.lightmap_uv", "raster_r16f_depth_fill");
    double blend = work_of("gi.lightmap_blend", "tex2d_rgba32f_nearest");
    const gk_lightmap_stats *st = gk_lightmap_get_stats(LM);
    print_message("# uv: %.0f fragments; blend: %.0f texel reads, atlas %dx%d\n", uv, blend, st->atlas_w, st->atlas_h);
    assert_true(uv == (double)floor);
    assert_true(st->atlas_w > 0 && blend == 2.0 * st->atlas_w * st->atlas_h);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(compose_lookups_match_the_charted_pixels),
    };
    return cmocka_run_group_tests_name("lightmap_work", tests, setup, teardown);
}
