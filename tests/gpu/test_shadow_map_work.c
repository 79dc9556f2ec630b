/* The shadow maps' work model (app/render/render_work.c, #21: `shadow.shadow_depth`, the depth draws'
 * fragments) against hand counts, on scenes whose coverage from the light is known by construction.
 * The depth draws do not cull faces, and with the counting atomic the depth test runs after the
 * shader, so every surface a face's frustum sees counts once per map texel it covers, hidden or not:
 *   - a spot light 2 m over a floor that fills its one perspective face, looking straight down (its
 *     map's u along world x, so the plane x = 0 falls on the boundary between the middle columns),
 *     and two half planes between them: x < 0 at y = 1 facing up and x > 0 at y = 1.5 facing down
 *     (the G-buffer would cull one of them, the depth draws draw both): S² + 2 x (S / 2) x S = 2 S²;
 *   - a point light inside a closed box (off centre): every direction of each of the 6 cube faces
 *     meets exactly one wall, so 6 S²; a rect light there, one-sided, skips its back face: 5 S².
 * The count is the same under every shadow method (they share the depth maps), scales with the
 * map's size, is reported only by a counting frame, and only by a frame that renders the maps (a
 * static scene's next frame reuses them). VSSM's prefilter (`shadow.vssm_prefilter`, modelled from
 * the map's size and layers) and CSSM's (`shadow.cssm_prefilter`) against hand counts of their
 * compute passes' reads, in the same frames. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "common/gl_fixture.h"
#include "render/renderer.h"

#define W 64
#define H 48

static gk_target FB;
static gkt_gl G;

static int setup(void **state)
{
    (void)state;
    if (gkt_gl_open(&G) != 0)
        return -1;
    const GLenum fmt = GL_RGBA8;
    return gkt_target(&FB, "shadow map work", W, H, 1, &fmt, false);
}

static int teardown(void **state)
{
    (void)state;
    gk_target_destroy(&FB);
    gkt_gl_close(&G);
    return 0;
}

/* The floor and the two half planes under a spot light at (0, 2, 0) looking down (45 degree cone:
   one perspective face of half angle 47.9 degrees, 2.2 m across on the floor, inside its 20 m). */
static void spot_over_halves(gkt_scene *t)
{
    gkt_scene_init(t, "shadow-work-spot");
    int grey = gkt_material_lambert(t, v3(0.5f, 0.5f, 0.5f));
    gkt_quad(t, v3(-10, 1, -10), v3(0, 1, -10), v3(0, 1, 10), v3(-10, 1, 10), v3(0, 1, 0), grey);
    gkt_quad(t, v3(0, 1.5f, -10), v3(10, 1.5f, -10), v3(10, 1.5f, 10), v3(0, 1.5f, 10), v3(0, -1, 0), grey);
    gkt_quad(t, v3(-10, 0, -10), v3(10, 0, -10), v3(10, 0, 10), v3(-10, 0, 10), v3(0, 1, 0), grey);
    gkt_light(t, GK_LIGHT_SPOT, GK_SHAPE_POINT, 10.0f, v3(0, 2, 0), v3(0, -1, 0));
    gkt_camera(t, v3(0, 3, 3), v3(0, 0, 0), 1.0f);
    gkt_scene_bounds(t);
}

/* The inside of the box [-1, 1]³ (six quads facing in, sharing their corners exactly, so that no
   texel is covered by two walls or by none) lit by `shape` at an off-centre point facing down. */
static void light_in_box(gkt_scene *t, enum gk_light_shape shape)
{
    gkt_scene_init(t, "shadow-work-box");
    int grey = gkt_material_lambert(t, v3(0.5f, 0.5f, 0.5f));
    for (int axis = 0; axis < 3; axis++)
        for (int side = -1; side <= 1; side += 2) {
            vec3 c[4];
            for (int k = 0; k < 4; k++) {
                float p[3];
                p[axis] = (float)side;
                p[(axis + 1) % 3] = k == 0 || k == 3 ? -1.0f : 1.0f;
                p[(axis + 2) % 3] = k < 2 ? -1.0f : 1.0f;
                c[k] = v3(p[0], p[1], p[2]);
            }
            float in[3] = {0, 0, 0};
            in[axis] = (float)-side;
            gkt_quad(t, c[0], c[1], c[2], c[3], v3(in[0], in[1], in[2]), grey);
        }
    gk_light *l = gkt_light(t, GK_LIGHT_POINT, shape, 10.0f, v3(0.2f, 0.6f, -0.3f), v3(0, -1, 0));
    if (shape == GK_SHAPE_RECT)
        l->size[0] = l->size[1] = 0.2f;
    gkt_camera(t, v3(0, 0, 0.9f), v3(0, -0.5f, 0), 1.2f);
    gkt_scene_bounds(t);
}

/* A renderer on t's scene with the knobs pinned (extra: a knob the test declares before the
   renderer's, or NULL), counting work or not: the set-up the two counting loops below share. */
static gk_renderer *pinned_renderer(gkt_scene *t, const char *pins, const gk_knob_def *extra, bool count, gk_budget *b)
{
    gk_err e = {0};
    gk_render_opts o = {.width = W, .height = H, .gles_version = 31, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, &e);
    assert_non_null(r);
    assert_int_equal(gk_renderer_set_scene(r, &t->s, &e), 0);
    gk_budget_init(b);
    if (extra)
        gk_budget_add(b, extra);
    gk_renderer_declare_knobs(r, b);
    if (gk_budget_pin_list(b, pins, &e) < 0)
        fail_msg("%s: %s", pins, e.msg);
    assert_true(gk_renderer_count_work(r, count));
    return r;
}

/* The shadow maps' counted fragments in each of `frames` frames of method none at `pins` (-1: no
   shadow.shadow_depth entry), counting or not. */
static void map_fragments(gkt_scene *t, const char *pins, bool count, int frames, double *out)
{
    gk_err e = {0};
    gk_budget b;
    gk_renderer *r = pinned_renderer(t, pins, NULL, count, &b);
    for (int f = 0; f < frames; f++) {
        gk_frame_params fp = {.time_s = 0, .method = "none", .budget = &b};
        gk_frame_report rep;
        if (gk_renderer_draw(r, &fp, FB.fbo, &rep, &e) != 0)
            fail_msg("%s: %s", pins, e.msg);
        gk_pass_work w[GK_MAX_PASS_WORK];
        int n = gk_renderer_pass_work(r, "none", w, GK_MAX_PASS_WORK);
        out[f] = -1.0;
        for (int i = 0; i < n; i++)
            if (!strcmp(w[i].pass, "shadow.shadow_depth")) {
                assert_string_equal(w[i].kind, "raster_r16f_depth_fill");
                out[f] = w[i].fetches;
            }
        printf("# %s %s%s, frame %d: %.0f fragments\n", t->s.name, pins, count ? "" : " (not counting)", f, out[f]);
    }
    gk_renderer_destroy(r);
}

static double one_frame(gkt_scene *t, const char *pins)
{
    double n;
    map_fragments(t, pins, true, 1, &n);
    return n;
}

static void nothing_counted_unless_asked_nor_when_the_maps_are_kept(void **state)
{
    (void)state;
    gkt_scene t;
    spot_over_halves(&t);
    double n[2];
    map_fragments(&t, "shadow=hard,shadow_map=256", false, 1, n);
    assert_true(n[0] == -1.0);
    map_fragments(&t, "shadow=hard,shadow_map=256", true, 2, n);
    assert_true(n[0] == 2.0 * 256 * 256);
    assert_true(n[1] == -1.0); /* the static scene's second frame draws no map */
    gkt_scene_free(&t);
}

static void spot_face_counts_every_surface_in_its_frustum(void **state)
{
    (void)state;
    gkt_scene t;
    spot_over_halves(&t);
    static const char *const pins[] = {"shadow=hard,shadow_map=256", "shadow=pcss,shadow_map=512",
                                       "shadow=vssm,shadow_map=512", "shadow=cssm,shadow_map=1024"};
    static const double size[] = {256, 512, 512, 1024};
    for (int i = 0; i < 4; i++)
        assert_true(one_frame(&t, pins[i]) == 2.0 * size[i] * size[i]);
    gkt_scene_free(&t);
}

static void cube_faces_inside_a_closed_box(void **state)
{
    (void)state;
    gkt_scene t;
    light_in_box(&t, GK_SHAPE_POINT);
    assert_true(one_frame(&t, "shadow=hard,shadow_map=256") == 6.0 * 256 * 256);
    assert_true(one_frame(&t, "shadow=vssm,shadow_map=512") == 6.0 * 512 * 512);
    gkt_scene_free(&t);
    light_in_box(&t, GK_SHAPE_RECT);
    assert_true(one_frame(&t, "shadow=pcss,shadow_map=256") == 5.0 * 256 * 256); /* its back face skipped */
    gkt_scene_free(&t);
}

/* A prefilter's work (`pass`: shadow.vssm_prefilter or shadow.cssm_prefilter,
   app/render/shadow/shadow_prefilter_work.h) in each of `frames` counting frames at `pins`: its depth
   reads, R32F reads, image loads and mip lookups (-1: no entry). */
/* the renderer's shadow knob plus the diagnostic CSSM variants (added first, so the renderer keeps it,
   as tests/gpu/test_shadow_work.c does) */
static const gk_knob_def knob_shadow = {
    .name = "shadow", .owner = "test", .n_values = 6,
    .values = {"hard", "pcss", "vssm", "cssm", "cssm_sat", "cssm_thesis"}, .cost = {1, 1, 1, 1, 1, 1},
};

static void prefilter_fetches(gkt_scene *t, const char *pass, const char *pins, int frames, double out[][4])
{
    gk_err e = {0};
    gk_budget b;
    gk_renderer *r = pinned_renderer(t, pins, &knob_shadow, true, &b);
    static const char *const kinds[4] = {"tex2d_depth32f_nearest", "tex2d_r32f_nearest", "image3d_rgba16f_load",
                                         "tex2d_rgba16f_trilinear"};
    for (int f = 0; f < frames; f++) {
        gk_frame_params fp = {.time_s = 0, .method = "none", .budget = &b};
        gk_frame_report rep;
        if (gk_renderer_draw(r, &fp, FB.fbo, &rep, &e) != 0)
            fail_msg("%s: %s", pins, e.msg);
        gk_pass_work w[GK_MAX_PASS_WORK];
        int n = gk_renderer_pass_work(r, "none", w, GK_MAX_PASS_WORK);
        for (int k = 0; k < 4; k++) {
            out[f][k] = -1.0;
            for (int i = 0; i < n; i++)
                if (!strcmp(w[i].pass, pass) && !strcmp(w[i].kind, kinds[k]))
                    out[f][k] = w[i].fetches;
        }
        printf("# %s %s, frame %d: %s %.0f depth, %.0f r32f, %.0f image loads, %.0f mip lookups\n", t->s.name, pins, f,
               pass, out[f][0], out[f][1], out[f][2], out[f][3]);
    }
    gk_renderer_destroy(r);
}

/* Hand counts of VSSM's prefilter per layer of a map of side S: the linearize reads S² depth texels,
   the SAT's rows S² R32F texels, and the image loads are the min-max pyramid's -- each of its two
   chains reads levels S, S/2, .., 2 once: 4/3 (S² - 1) -- and the SAT columns' 2 S²:
     S = 256: 2 x 87 380 + 131 072 = 305 832;  S = 512: 2 x 349 524 + 524 288 = 1 223 336.
   The spot's one face is one layer, the point light's cube six. Other methods report none, and a
   static scene's second frame, which keeps its maps, none. */
static void vssm_prefilter_by_hand(void **state)
{
    (void)state;
    gkt_scene t;
    spot_over_halves(&t);
    double f[2][4];
    prefilter_fetches(&t, "shadow.vssm_prefilter", "shadow=vssm,shadow_map=256", 2, f);
    assert_true(f[0][0] == 65536.0 && f[0][1] == 65536.0 && f[0][2] == 305832.0 && f[0][3] == -1.0);
    assert_true(f[1][0] == -1.0 && f[1][1] == -1.0 && f[1][2] == -1.0);
    prefilter_fetches(&t, "shadow.vssm_prefilter", "shadow=vssm,shadow_map=512", 1, f);
    assert_true(f[0][0] == 262144.0 && f[0][1] == 262144.0 && f[0][2] == 1223336.0);
    prefilter_fetches(&t, "shadow.vssm_prefilter", "shadow=pcss,shadow_map=512", 1, f);
    assert_true(f[0][0] == -1.0 && f[0][1] == -1.0 && f[0][2] == -1.0);
    gkt_scene_free(&t);
    light_in_box(&t, GK_SHAPE_POINT);
    prefilter_fetches(&t, "shadow.vssm_prefilter", "shadow=vssm,shadow_map=256", 1, f);
    assert_true(f[0][0] == 6 * 65536.0 && f[0][1] == 6 * 65536.0 && f[0][2] == 6 * 305832.0);
    gkt_scene_free(&t);
}

/* Hand counts of CSSM's prefilter per layer of side S = 256 (S² = 65 536): the linearize's S² depth
   reads; the depth range's S² loads (the layer's reduction) and 3 S² (each texel's renormalisation
   reads it and the layer's two range texels): 262 144; by mipmaps (cssm) the two basis passes' 2 S²
   R32F reads and the 5 RGBA16F chains' mips, one lookup per texel of levels 128² .. 1: 5 x 21 845 =
   109 225; by SATs (cssm_sat) 3 basis pairs' S² R32F reads and 2 S² loads each: 196 608 reads and
   262 144 + 393 216 = 655 360 loads, no mips; cssm_thesis (the fixed range) no loads. VSSM reports
   none, nor a frame that keeps its maps. */
static void cssm_prefilter_by_hand(void **state)
{
    (void)state;
    gkt_scene t;
    spot_over_halves(&t);
    double f[2][4];
    prefilter_fetches(&t, "shadow.cssm_prefilter", "shadow=cssm,shadow_map=256", 2, f);
    assert_true(f[0][0] == 65536.0 && f[0][1] == 131072.0 && f[0][2] == 262144.0 && f[0][3] == 109225.0);
    assert_true(f[1][0] == -1.0 && f[1][1] == -1.0 && f[1][2] == -1.0 && f[1][3] == -1.0);
    prefilter_fetches(&t, "shadow.cssm_prefilter", "shadow=cssm_sat,shadow_map=256", 1, f);
    assert_true(f[0][0] == 65536.0 && f[0][1] == 196608.0 && f[0][2] == 655360.0 && f[0][3] == -1.0);
    prefilter_fetches(&t, "shadow.cssm_prefilter", "shadow=cssm_thesis,shadow_map=256", 1, f); /* no range pass */
    assert_true(f[0][0] == 65536.0 && f[0][1] == 131072.0 && f[0][2] == -1.0 && f[0][3] == 109225.0);
    prefilter_fetches(&t, "shadow.cssm_prefilter", "shadow=vssm,shadow_map=256", 1, f);
    assert_true(f[0][0] == -1.0 && f[0][1] == -1.0 && f[0][2] == -1.0 && f[0][3] == -1.0);
    gkt_scene_free(&t);
    light_in_box(&t, GK_SHAPE_POINT);
    prefilter_fetches(&t, "shadow.cssm_prefilter", "shadow=cssm,shadow_map=256", 1, f);
    assert_true(f[0][0] == 6 * 65536.0 && f[0][1] == 6 * 131072.0 && f[0][2] == 6 * 262144.0 && f[0][3] == 6 * 109225.0);
    gkt_scene_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(nothing_counted_unless_asked_nor_when_the_maps_are_kept),
        cmocka_unit_test(spot_face_counts_every_surface_in_its_frustum),
        cmocka_unit_test(cube_faces_inside_a_closed_box),
        cmocka_unit_test(vssm_prefilter_by_hand),
        cmocka_unit_test(cssm_prefilter_by_hand),
    };
    return cmocka_run_group_tests_name("shadow_map_work", tests, setup, teardown);
}
