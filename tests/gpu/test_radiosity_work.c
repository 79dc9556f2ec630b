/* The radiosity display pass's work model (app/gi/radiosity/rad_work.c, #21) against a hand count
 * on the floor view (test_floor_view.h: about a fifth of it background). The display draws the
 * radiosity mesh -- the floor's surfels, tiling the quad in one layer -- without depth test or
 * culling, so it rasterizes one fragment per pixel whose G-buffer holds the floor (albedo > 0; the
 * background is cleared to 0), counted on the CPU. Without count_work nothing is reported, and the
 * bounces' entry (rad_work.c, checked in test_radiosity.c) is reported either way. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "gi/radiosity/radiosity.h"
#include "test_floor_view.h"
#include "test_pass_work.h"

#define W TFV_W
#define HH TFV_H

static gkt_scene T;
static ispm_h H; /* the ispm harness's scene, G-buffer and frame (ih_frame_of) */
static void *RAD;

static int setup(void **state)
{
    (void)state;
    /* lockstep: the first frame waits for the worker's first result, so it shows the radiosity */
    RAD = tfv_open(&H, &T, "radiosity-work-floor", &gk_gi_radiosity, NULL, "radiosity_sync=lockstep");
    return RAD ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    if (RAD)
        gk_gi_radiosity.destroy(RAD);
    ih_close_built(&H, &T);
    return 0;
}

static double display_fragments(void)
{
    return tpw_fetches(&gk_gi_radiosity, RAD, "gi.radiosity_display", "raster_r16f_depth_fill");
}

static void display_fragments_match_the_floor_pixels(void **state)
{
    (void)state;
    H.count_work = false;
    assert_int_equal(ih_frame_of(&H, &gk_gi_radiosity, RAD), 0);
    assert_true(gk_radiosity_get_stats(RAD)->shown);
    assert_true(display_fragments() < 0.0); /* not a counting frame: nothing counted */
    H.count_work = true;
    assert_int_equal(ih_frame_of(&H, &gk_gi_radiosity, RAD), 0);
    H.count_work = false;
    long floor = tfv_floor_pixels(&H);
    double counted = display_fragments();
    print_message("# display: %.0f fragments counted, %ld floor pixels of %d\n", counted, floor, W * HH);
    /* the view's edge is the floor's: part of it background, the rest the floor */
    assert_true(floor > W * HH / 2 && floor < W * HH);
    assert_true(counted == (double)floor);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(display_fragments_match_the_floor_pixels),
    };
    return cmocka_run_group_tests_name("radiosity_work", tests, setup, teardown);
}
