/* The final gather's draws' work model (app/gi/lightmap/lm_work.c, #21) against a hand count: inside
 * a closed box of six inward-facing walls, all charted, each gathered texel's tile looks from a wall
 * into the box through a 127 degree field of view, so every tile pixel sees exactly one wall: the
 * box is convex, the wall the texel lies on is behind the camera, and walls sharing an edge share its
 * corners, so the rasterizer's fill rule gives each pixel centre one triangle. gather.frag's counting
 * variant must then count lightmap_gather² fragments per gathered texel, each of them charted: as
 * many AIM lookups. Without count_work nothing is reported. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "gi/lightmap/lightmap.h"
#include "test_ispm_harness.h"
#include "test_pass_work.h"

#define W 64
#define HH 48

static gkt_scene T;
static ispm_h H;
static void *LM;

static int setup(void **state)
{
    (void)state;
    gkt_scene_init(&T, "lightmap-gather-box");
    int grey = gkt_material_lambert(&T, v3(0.75f, 0.75f, 0.75f));
    const float a = 1.0f;
    /* the six walls, each facing the box's inside */
    gkt_quad(&T, v3(-a, -a, -a), v3(a, -a, -a), v3(a, -a, a), v3(-a, -a, a), v3(0, 1, 0), grey);
    gkt_quad(&T, v3(-a, a, -a), v3(a, a, -a), v3(a, a, a), v3(-a, a, a), v3(0, -1, 0), grey);
    gkt_quad(&T, v3(-a, -a, -a), v3(-a, a, -a), v3(-a, a, a), v3(-a, -a, a), v3(1, 0, 0), grey);
    gkt_quad(&T, v3(a, -a, -a), v3(a, a, -a), v3(a, a, a), v3(a, -a, a), v3(-1, 0, 0), grey);
    gkt_quad(&T, v3(-a, -a, -a), v3(a, -a, -a), v3(a, a, -a), v3(-a, a, -a), v3(0, 0, 1), grey);
    gkt_quad(&T, v3(-a, -a, a), v3(a, -a, a), v3(a, a, a), v3(-a, a, a), v3(0, 0, -1), grey);
    gkt_light(&T, GK_LIGHT_POINT, GK_SHAPE_POINT, 10.0f, v3(0.3f, 0.5f, 0.2f), v3(1, 1, 1));
    gkt_camera(&T, v3(0, 0, 0.8f), v3(0, -0.2f, 0), 60.0f * (float)M_PI / 180.0f);
    gkt_scene_bounds(&T);
    if (ih_open_built(&H, &T, W, HH))
        return -1;
    gk_err e = {0};
    gk_gi_context ctx = {.programs = H.programs, .gles_version = H.gl.egl.gles_version};
    LM = gk_gi_lightmap.create(&ctx, &e);
    if (!LM) {
        fprintf(stderr, "lightmap: %s\n", e.msg);
        return -1;
    }
    gk_lightmap_set_threads(LM, 1);
    gk_budget_init(&H.budget);
    gk_gi_lightmap.declare_knobs(&H.budget);
    /* lockstep: each frame waits for the worker, so the frame gathers what it queued */
    if (gk_gi_lightmap.set_scene(LM, &T.s, &e) || gk_budget_pin_list(&H.budget, "lightmap_sync=lockstep", &e)) {
        fprintf(stderr, "lightmap: %s\n", e.msg);
        return -1;
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    if (LM)
        gk_gi_lightmap.destroy(LM);
    ih_close_built(&H, &T);
    return 0;
}

static double work_of(const char *kind) { return tpw_fetches(&gk_gi_lightmap, LM, "gi.lightmap_gather", kind); }

static void gather_draws_fill_every_tile_once(void **state)
{
    (void)state;
    static const char *const budgets[2] = {"lightmap_sync=lockstep,lightmap_gather=8",
                                           "lightmap_sync=lockstep,lightmap_gather=16"};
    static const int res[2] = {8, 16};
    for (int b = 0; b < 2; b++) {
        gk_err e = {0};
        gk_budget_init(&H.budget);
        gk_gi_lightmap.declare_knobs(&H.budget);
        assert_int_equal(gk_budget_pin_list(&H.budget, budgets[b], &e), 0);
        H.count_work = false;
        assert_int_equal(ih_frame_of(&H, &gk_gi_lightmap, LM), 0);
        assert_true(work_of("raster_r16f_depth_fill") < 0.0); /* not a counting frame: nothing counted */
        H.count_work = true;
        assert_int_equal(ih_frame_of(&H, &gk_gi_lightmap, LM), 0);
        H.count_work = false;
        const gk_lightmap_stats *st = gk_lightmap_get_stats(LM);
        double fragments = work_of("raster_r16f_depth_fill"), lookups = work_of("tex2d_rgba16f_trilinear");
        double reads = work_of("tex2d_rgba32f_nearest");
        print_message("# lightmap_gather=%d: %d texels gathered: %.0f fragments, %.0f AIM lookups, %.0f tile reads "
                      "(res² a texel: %d)\n", res[b], st->gathered, fragments, lookups, reads, res[b] * res[b]);
        assert_true(st->gathered > 0);
        double tiles = (double)st->gathered * res[b] * res[b];
        assert_true(fragments == tiles && lookups == tiles && reads == tiles);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gather_draws_fill_every_tile_once),
    };
    return cmocka_run_group_tests_name("lightmap_gather_work", tests, setup, teardown);
}
