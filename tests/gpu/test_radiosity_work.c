/* The radiosity display pass's work model (app/gi/radiosity/rad_work.c, #21) against a hand count:
 * a grey floor 6 m square lit by a point light, seen straight down from 2 m over a point 0.6 m
 * inside its edge, so that about a fifth of the view is background. The display draws the
 * radiosity mesh -- the floor's surfels, tiling the quad in one layer -- without depth test or
 * culling, so it rasterizes one fragment per pixel whose G-buffer holds the floor (albedo > 0; the
 * background is cleared to 0), counted on the CPU. Without count_work nothing is reported, and the
 * bounces' entry (rad_work.c, checked in test_radiosity.c) is reported either way. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "gi/radiosity/radiosity.h"
#include "test_ispm_harness.h"
#include "test_pass_work.h"

#define W 160
#define HH 120

static gkt_scene T;
static ispm_h H; /* the ispm harness's scene, G-buffer and frame (ih_frame_of) */
static void *RAD;

static int setup(void **state)
{
    (void)state;
    gkt_scene_init(&T, "radiosity-work-floor");
    int grey = gkt_material_lambert(&T, v3(0.75f, 0.75f, 0.75f));
    gkt_quad(&T, v3(-3, 0, -3), v3(3, 0, -3), v3(3, 0, 3), v3(-3, 0, 3), v3(0, 1, 0), grey);
    gkt_light(&T, GK_LIGHT_POINT, GK_SHAPE_POINT, 10.0f, v3(1.0f, 1.5f, 0.0f), v3(1, 1, 0));
    gkt_camera(&T, v3(2.4f, 2.0f, 0), v3(2.4f, 0, 0), 40.0f * (float)M_PI / 180.0f);
    gkt_scene_bounds(&T);
    if (ih_open_built(&H, &T, W, HH))
        return -1;
    gk_err e = {0};
    gk_gi_context ctx = {.programs = H.programs, .gles_version = H.gl.egl.gles_version};
    RAD = gk_gi_radiosity.create(&ctx, &e);
    if (!RAD) {
        fprintf(stderr, "radiosity: %s\n", e.msg);
        return -1;
    }
    gk_budget_init(&H.budget);
    gk_gi_radiosity.declare_knobs(&H.budget);
    /* lockstep: the first frame waits for the worker's first result, so it shows the radiosity */
    if (gk_gi_radiosity.set_scene(RAD, &T.s, &e) || gk_budget_pin_list(&H.budget, "radiosity_sync=lockstep", &e)) {
        fprintf(stderr, "radiosity: %s\n", e.msg);
        return -1;
    }
    return 0;
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
    long floor = 0;
    for (int i = 0; i < W * HH; i++)
        floor += H.albedo[i * 4] > 0.0f;
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
