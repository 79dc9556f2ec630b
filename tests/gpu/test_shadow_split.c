/* The lighting pass's two draws for VSSM (app/render/render_split.c, #21): draw 1 adds the pixels
 * with no light and those the HSM settles and marks them in a stencil, draw 2 (early stencil test)
 * the rest. Against the one-draw pass (GK_SHADOW_ONE_DRAW=1) on the shipped Cornell box (area
 * light, cube map) and its spot-light variant (one face), and for cssm_plane, whose draw 1 marks only
 * the pixels with no light, on env-studio (16 environment lights, sky background; whatever the shadow
 * knob, the environment's lights use cssm_plane): the linear image is bit-identical (a pixel
 * drawn by both draws would add its light twice, one by neither would lose it) and the counted
 * shadow fetches are the same (each pixel's lookup counted once: draw 1 counts the settled pixels'
 * HSM reads, draw 2 the others' whole lookup; a settled pixel that draw 2 also ran would add its
 * HSM reads again). The split FBO exists only where the split ran, so the test cannot pass by
 * comparing the one-draw pass with itself. */
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
#include "render/renderer_internal.h"
#include "scene/scene.h"

#define W 160
#define H 120

static const gk_knob_def knob_shadow = {
    .name = "shadow", .owner = "test", .n_values = 2,
    .values = {"vssm", "vssm_thesis"}, .cost = {1, 1}, .default_level = 0,
};

typedef struct drawn {
    gk_image img;
    double fetches[5]; /* the direct pass's counted fetches by kind (render_work.c's order) */
    bool split_ran;
} drawn;

/* One counting frame of method none at `pins`, with the split or without. */
static void draw(gkt_shipped *t, const char *pins, bool split, drawn *out)
{
    if (split)
        unsetenv("GK_SHADOW_ONE_DRAW");
    else
        setenv("GK_SHADOW_ONE_DRAW", "1", 1);
    gk_err e = {0};
    gk_render_opts o = {.width = W, .height = H, .gles_version = 31, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, &e);
    assert_non_null(r);
    assert_int_equal(gk_renderer_set_scene(r, t->scene, &e), 0);
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &knob_shadow);
    gk_renderer_declare_knobs(r, &b);
    assert_true(gk_budget_pin_list(&b, pins, &e) >= 0);
    assert_true(gk_renderer_count_work(r, true));
    gk_frame_params fp = {.time_s = 0, .method = "none", .budget = &b};
    gk_frame_report rep;
    if (gk_renderer_draw(r, &fp, t->fb.fbo, &rep, &e) != 0)
        fail_msg("%s: %s", pins, e.msg);
    assert_int_equal(gk_renderer_read_linear(r, &out->img, &e), 0);
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_renderer_pass_work(r, "none", w, GK_MAX_PASS_WORK), k = 0;
    memset(out->fetches, 0, sizeof out->fetches);
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].pass, "direct") && k < 5)
            out->fetches[k++] = w[i].fetches; /* the kinds VSSM reads, in render_work.c's order */
    out->split_ran = r->split.fbo != 0;
    gk_renderer_destroy(r);
    unsetenv("GK_SHADOW_ONE_DRAW");
}

static void same_as_one_draw(const char *gltf, const char *pins)
{
    gkt_shipped t;
    assert_int_equal(gkt_shipped_open(&t, gltf, W, H), 0);
    drawn one, two;
    draw(&t, pins, false, &one);
    draw(&t, pins, true, &two);
    assert_false(one.split_ran);
    assert_true(two.split_ran);
    assert_int_equal(one.img.width * one.img.height * one.img.channels,
                     two.img.width * two.img.height * two.img.channels);
    size_t n = (size_t)one.img.width * one.img.height * one.img.channels, differ = 0;
    double lit = 0.0;
    for (size_t i = 0; i < n; i++) {
        differ += memcmp(&one.img.pixels[i], &two.img.pixels[i], sizeof(float)) != 0;
        lit += one.img.pixels[i];
    }
    printf("# %s %s: %zu of %zu channels differ; fetches one draw %.0f %.0f, two draws %.0f %.0f\n", gltf, pins,
           differ, n, one.fetches[0], one.fetches[1], two.fetches[0], two.fetches[1]);
    assert_true(lit > 0.0); /* a lit image, not two black ones */
    assert_int_equal(differ, 0);
    double counted = 0.0;
    for (int k = 0; k < 5; k++) {
        assert_true(one.fetches[k] == two.fetches[k]);
        counted += one.fetches[k];
    }
    assert_true(counted > 0.0); /* VSSM reads the depth map, CSSM only its range and bases */
    gk_image_free(&one.img);
    gk_image_free(&two.img);
    gkt_shipped_close(&t);
}

static void cornell_vssm(void **state)
{
    (void)state;
    same_as_one_draw("config/scenes/cornell.gltf", "shadow=vssm");
}

static void cornell_vssm_thesis(void **state)
{
    (void)state;
    same_as_one_draw("config/scenes/cornell.gltf", "shadow=vssm_thesis");
}

static void env_studio_cssm_plane(void **state)
{
    (void)state;
    same_as_one_draw("config/scenes/env-studio.gltf", "shadow=vssm");
}

static void cornell_spot_vssm(void **state)
{
    (void)state;
    same_as_one_draw("config/scenes/cornell-spot.gltf", "shadow=vssm");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cornell_vssm),
        cmocka_unit_test(cornell_vssm_thesis),
        cmocka_unit_test(cornell_spot_vssm),
        cmocka_unit_test(env_studio_cssm_plane),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
