/* The renderer's own passes' work models (app/render/render_work.c, #21) against hand counts, on a
 * scene whose coverage is known by construction: a camera 2 m over the origin looking straight down
 * (so the plane x = 0 projects onto the screen's middle column boundary), a floor at y = 0 that
 * fills the view, a quad at y = 1 over the half x < 0 facing the camera, drawn before the floor (an
 * early depth test would drop the floor's fragments under it: the count must not), and a quad at
 * y = 1.5 over the half x > 0 facing away, single-sided (culled: no fragments). So the G-buffer
 * draws rasterize W x H + (W / 2) x H fragments at render size W x H, and the compose reads the HDR
 * image once per output pixel whatever the render scale (the upsample). Without count_work nothing
 * is reported. The glass pass on a second scene seen the same way: an opaque floor, a glass quad
 * over the half x < 0 at y = 1 (in front) and one under the half x > 0 at y = -0.5 (hidden by the
 * floor), both facing the camera: every glass fragment reads the G-buffer's depth once, W x H in all,
 * and the W/2 x H in front look up the image behind twice, plus the pass's copy of that image, one
 * lookup a pixel: 2 W x H lookups. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "common/gl_fixture.h"
#include "render/renderer.h"

#define W 96
#define H 72

static gkt_gl G;
static gk_target FB;
static gkt_scene T;

static int setup(void **state)
{
    (void)state;
    if (gkt_gl_open(&G) != 0)
        return -1;
    const GLenum fmt = GL_RGBA8;
    if (gkt_target(&FB, "render work", W, H, 1, &fmt, false) != 0)
        return -1;
    gkt_scene_init(&T, "render-work-halves");
    int grey = gkt_material_lambert(&T, v3(0.5f, 0.5f, 0.5f));
    gkt_quad(&T, v3(-10, 1, -10), v3(0, 1, -10), v3(0, 1, 10), v3(-10, 1, 10), v3(0, 1, 0), grey);
    gkt_quad(&T, v3(0, 1.5f, -10), v3(10, 1.5f, -10), v3(10, 1.5f, 10), v3(0, 1.5f, 10), v3(0, -1, 0), grey);
    gkt_quad(&T, v3(-10, 0, -10), v3(10, 0, -10), v3(10, 0, 10), v3(-10, 0, 10), v3(0, 1, 0), grey);
    gkt_camera(&T, v3(0, 2, 0), v3(0, 0, 0), 60.0f * (float)M_PI / 180.0f);
    gkt_scene_bounds(&T);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    gkt_scene_free(&T);
    gk_target_destroy(&FB);
    gkt_gl_close(&G);
    return 0;
}

/* The glass scene: the floor and the two glass halves under the same camera. */
static void glass_halves(gkt_scene *t)
{
    gkt_scene_init(t, "render-work-glass");
    int grey = gkt_material_lambert(t, v3(0.5f, 0.5f, 0.5f)), glass = gkt_material(t, v3(1, 1, 1), 0.0f, 0.0f);
    t->mats[glass].transmission = 1.0f;
    gkt_quad(t, v3(-10, 1, -10), v3(0, 1, -10), v3(0, 1, 10), v3(-10, 1, 10), v3(0, 1, 0), glass);
    gkt_quad(t, v3(0, -0.5f, -10), v3(10, -0.5f, -10), v3(10, -0.5f, 10), v3(0, -0.5f, 10), v3(0, 1, 0), glass);
    gkt_quad(t, v3(-10, 0, -10), v3(10, 0, -10), v3(10, 0, 10), v3(-10, 0, 10), v3(0, 1, 0), grey);
    gkt_camera(t, v3(0, 2, 0), v3(0, 0, 0), 60.0f * (float)M_PI / 180.0f);
    gkt_scene_bounds(t);
    t->s.features.has_transmission = true; /* what gk_scene_derive_features finds in a loaded scene */
}

typedef struct counted {
    double gbuffer, compose; /* -1: not reported */
    int entries;
} counted;

/* One frame of method none at `pins`, counting or not: the renderer's reported work. */
static counted frame_work(const char *pins, bool count)
{
    gk_err e = {0};
    gk_render_opts o = {.width = W, .height = H, .gles_version = 31, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, &e);
    assert_non_null(r);
    assert_int_equal(gk_renderer_set_scene(r, &T.s, &e), 0);
    gk_budget b;
    gk_budget_init(&b);
    gk_renderer_declare_knobs(r, &b);
    assert_true(gk_budget_pin_list(&b, pins, &e) >= 0);
    assert_true(gk_renderer_count_work(r, count));
    gk_frame_params fp = {.time_s = 0, .method = "none", .budget = &b};
    gk_frame_report rep;
    if (gk_renderer_draw(r, &fp, FB.fbo, &rep, &e) != 0)
        fail_msg("%s: %s", pins, e.msg);
    gk_pass_work w[GK_MAX_PASS_WORK];
    counted c = {-1.0, -1.0, gk_renderer_pass_work(r, "none", w, GK_MAX_PASS_WORK)};
    for (int i = 0; i < c.entries; i++) {
        if (!strcmp(w[i].pass, "gbuffer")) {
            assert_string_equal(w[i].kind, "raster_r16f_depth_fill");
            c.gbuffer = w[i].fetches;
        } else if (!strcmp(w[i].pass, "compose")) {
            assert_string_equal(w[i].kind, "tex2d_rgba16f_trilinear");
            c.compose = w[i].fetches;
        }
    }
    printf("# %s%s: gbuffer %.0f fragments, compose %.0f lookups, %d entries\n", pins,
           count ? "" : " (not counting)", c.gbuffer, c.compose, c.entries);
    gk_renderer_destroy(r);
    return c;
}

static void nothing_counted_unless_asked(void **state)
{
    (void)state;
    assert_int_equal(frame_work("render_scale=1", false).entries, 0);
}

static void gbuffer_fragments_and_compose_lookups_at_full_scale(void **state)
{
    (void)state;
    counted c = frame_work("render_scale=1", true);
    assert_true(c.gbuffer == (double)W * H + (double)(W / 2) * H); /* 10 368: the floor and the near half */
    assert_true(c.compose == (double)W * H);
    assert_int_equal(c.entries, 2); /* no light: the direct pass has no shadow lookups */
}

static void half_scale_halves_the_gbuffer_not_the_compose(void **state)
{
    (void)state;
    counted c = frame_work("render_scale=0.5", true);
    int w = W / 2, h = H / 2;
    assert_true(c.gbuffer == (double)w * h + (double)(w / 2) * h);
    assert_true(c.compose == (double)W * H); /* the bilinear upsample: one lookup per output pixel */
}

/* The glass pass's reads by kind in one frame of method none, counting or not (-1: none reported). */
static void glass_work(gkt_scene *t, bool count, double *depth, double *lookups)
{
    gk_err e = {0};
    gk_render_opts o = {.width = W, .height = H, .gles_version = 31, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, &e);
    assert_non_null(r);
    assert_int_equal(gk_renderer_set_scene(r, &t->s, &e), 0);
    assert_true(gk_renderer_count_work(r, count));
    gk_frame_params fp = {.time_s = 0, .method = "none"};
    gk_frame_report rep;
    if (gk_renderer_draw(r, &fp, FB.fbo, &rep, &e) != 0)
        fail_msg("glass: %s", e.msg);
    assert_true(gk_frame_report_find(&rep, "glass") >= 0); /* the pass ran */
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_renderer_pass_work(r, "none", w, GK_MAX_PASS_WORK);
    *depth = *lookups = -1.0;
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].pass, "glass")) {
            if (!strcmp(w[i].kind, "tex2d_depth32f_nearest"))
                *depth = w[i].fetches;
            else if (!strcmp(w[i].kind, "tex2d_rgba16f_trilinear"))
                *lookups = w[i].fetches;
            else
                fail_msg("glass: kind %s", w[i].kind);
        }
    printf("# glass%s: %.0f depth reads, %.0f lookups\n", count ? "" : " (not counting)", *depth, *lookups);
    gk_renderer_destroy(r);
}

static void glass_reads_depth_per_fragment_and_the_image_behind_per_visible_one(void **state)
{
    (void)state;
    gkt_scene t;
    glass_halves(&t);
    double depth, lookups;
    glass_work(&t, false, &depth, &lookups);
    assert_true(depth == -1.0 && lookups == -1.0);
    glass_work(&t, true, &depth, &lookups);
    assert_true(depth == (double)W * H);
    assert_true(lookups == 2.0 * (W / 2) * H + (double)W * H);
    gkt_scene_free(&t);
}

/* The blend pass (blend/forward.frag BLEND_COUNT_FRAGMENTS): the floor, an alpha-blended quad over
   the half x < 0 at y = 1 (in front of it) and one under the half x > 0 at y = -0.5 (behind it),
   both facing the camera: every blended draw rasterizes W/2 x H + W/2 x H = W x H fragments (the
   hidden half too: with the atomic the depth test runs after the shader). Without a light a mesh
   has its ambient draw only: W x H; with one point light an added draw each: 2 W x H. */
static double blend_fragments(bool light)
{
    gkt_scene t;
    gkt_scene_init(&t, "render-work-blend");
    int grey = gkt_material_lambert(&t, v3(0.5f, 0.5f, 0.5f)), veil = gkt_material_lambert(&t, v3(0.8f, 0.2f, 0.2f));
    t.mats[veil].alpha_blend = true;
    gkt_quad(&t, v3(-10, 1, -10), v3(0, 1, -10), v3(0, 1, 10), v3(-10, 1, 10), v3(0, 1, 0), veil);
    gkt_quad(&t, v3(0, -0.5f, -10), v3(10, -0.5f, -10), v3(10, -0.5f, 10), v3(0, -0.5f, 10), v3(0, 1, 0), veil);
    gkt_quad(&t, v3(-10, 0, -10), v3(10, 0, -10), v3(10, 0, 10), v3(-10, 0, 10), v3(0, 1, 0), grey);
    if (light)
        gkt_light(&t, GK_LIGHT_POINT, GK_SHAPE_POINT, 10.0f, v3(0.3f, 1.8f, 0.2f), v3(0, -1, 0));
    gkt_camera(&t, v3(0, 2, 0), v3(0, 0, 0), 60.0f * (float)M_PI / 180.0f);
    gkt_scene_bounds(&t);
    gk_err e = {0};
    gk_render_opts o = {.width = W, .height = H, .gles_version = 31, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, &e);
    assert_non_null(r);
    assert_int_equal(gk_renderer_set_scene(r, &t.s, &e), 0);
    assert_true(gk_renderer_count_work(r, true));
    gk_frame_params fp = {.time_s = 0, .method = "none"};
    gk_frame_report rep;
    if (gk_renderer_draw(r, &fp, FB.fbo, &rep, &e) != 0)
        fail_msg("blend: %s", e.msg);
    assert_true(gk_frame_report_find(&rep, "blend") >= 0); /* the pass ran */
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_renderer_pass_work(r, "none", w, GK_MAX_PASS_WORK);
    double fragments = -1.0;
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].pass, "blend")) {
            assert_string_equal(w[i].kind, "raster_r16f_depth_fill");
            fragments = w[i].fetches;
        }
    printf("# blend%s: %.0f fragments\n", light ? " (one light)" : "", fragments);
    gk_renderer_destroy(r);
    gkt_scene_free(&t);
    return fragments;
}

static void blend_fragments_by_hand(void **state)
{
    (void)state;
    assert_true(blend_fragments(false) == (double)W * H);
    assert_true(blend_fragments(true) == 2.0 * W * H);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(nothing_counted_unless_asked),
        cmocka_unit_test(gbuffer_fragments_and_compose_lookups_at_full_scale),
        cmocka_unit_test(half_scale_halves_the_gbuffer_not_the_compose),
        cmocka_unit_test(glass_reads_depth_per_fragment_and_the_image_behind_per_visible_one),
        cmocka_unit_test(blend_fragments_by_hand),
    };
    return cmocka_run_group_tests_name("render_work", tests, setup, teardown);
}
