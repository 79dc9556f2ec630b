/* The renderer's own passes' work models (app/render/render_work.c, #21) against hand counts, on a
 * scene whose coverage is known by construction: a camera 2 m over the origin looking straight down
 * (so the plane x = 0 projects onto the screen's middle column boundary), a floor at y = 0 that
 * fills the view, a quad at y = 1 over the half x < 0 facing the camera, drawn before the floor (an
 * early depth test would drop the floor's fragments under it: the count must not), and a quad at
 * y = 1.5 over the half x > 0 facing away, single-sided (culled: no fragments). So the G-buffer
 * draws rasterize W x H + (W / 2) x H fragments at render size W x H, and the compose reads the HDR
 * image once per output pixel whatever the render scale (the upsample). Without count_work nothing
 * is reported. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(nothing_counted_unless_asked),
        cmocka_unit_test(gbuffer_fragments_and_compose_lookups_at_full_scale),
        cmocka_unit_test(half_scale_halves_the_gbuffer_not_the_compose),
    };
    return cmocka_run_group_tests_name("render_work", tests, setup, teardown);
}
