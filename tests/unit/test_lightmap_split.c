/* Walls split the surfaces they cross (app/scene/wall_split.h), the light-leak part of issue 16:
 *  - light-leak: the 2 cm wall's two sides cut the floor, the ceiling and the two long walls (8
 *    cuts); afterwards no chart reaches from one room into the other (without the split the
 *    floor's chart does: the failure the test would catch), and the cut surfaces keep their area;
 *  - cornell: no wall crosses a surface (the blocks stand on the floor without crossing it): no
 *    cut, the same 16 charts;
 *  - photons do not cross: after the photon worker settled on light-leak, every texel of the dark
 *    room's charts holds zero irradiance (full and indirect), the lit room's do not. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gi/lightmap/lm_atlas.h"
#include "scene/wall_split.h"
#include "gi/lightmap/lm_worker.h"

#define WALL 0.01f /* light-leak's wall: x in [-0.01, 0.01] */

static gk_scene *load(const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "config/scenes/%s.gltf", name);
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path, &e);
    if (!s)
        fail_msg("%s", e.msg);
    gk_scene_evaluate(s, 0.0f);
    return s;
}

static bool spans_wall(const lm_chart *c) { return c->wmin.x < -WALL - 1e-3f && c->wmax.x > WALL + 1e-3f; }

static double charted_area(const lm_atlas *a)
{
    double s = 0;
    for (int i = 0; i < a->n_charts; i++)
        s += a->charts[i].area;
    return s;
}

static void test_light_leak_charts(void **state)
{
    (void)state;
    gk_scene *s = load("light-leak");
    gk_err e = {0};
    lm_atlas before;
    assert_int_equal(lm_atlas_build(&before, s, 5, &e), 0);
    int spanning = 0;
    for (int i = 0; i < before.n_charts; i++)
        spanning += spans_wall(&before.charts[i]);
    assert_int_equal(spanning, 4); /* floor, ceiling, the two long walls: the leak's cause */
    gk_wall_regions r;
    int cuts = gk_split_walls(s, &r, &e);
    assert_int_equal(cuts, 8); /* 4 surfaces x the wall's 2 sides */
    lm_atlas after;
    assert_int_equal(lm_atlas_build_regions(&after, s, 5, &r, &e), 0);
    for (int i = 0; i < after.n_charts; i++)
        assert_false(spans_wall(&after.charts[i]));
    /* each of the 4 surfaces became 3 charts: a room's part, the strip under the wall, the other's */
    assert_int_equal(after.n_charts, before.n_charts + 8);
    print_message("light-leak: %d cuts, charts %d -> %d, area %.4f -> %.4f m^2\n", cuts, before.n_charts, after.n_charts,
                  charted_area(&before), charted_area(&after));
    assert_true(fabs(charted_area(&after) - charted_area(&before)) < 1e-4 * charted_area(&before));
    lm_atlas_free(&before), lm_atlas_free(&after);
    gk_wall_regions_free(&r);
    gk_scene_free(s);
}

static void test_cornell_untouched(void **state)
{
    (void)state;
    gk_scene *s = load("cornell");
    gk_err e = {0};
    gk_wall_regions r;
    assert_int_equal(gk_split_walls(s, &r, &e), 0);
    lm_atlas a;
    assert_int_equal(lm_atlas_build_regions(&a, s, 5, &r, &e), 0);
    assert_int_equal(a.n_charts, 16);
    lm_atlas_free(&a);
    gk_wall_regions_free(&r);
    gk_scene_free(s);
}

typedef struct copy_ctx {
    float *ind, *full;
    size_t n;
} copy_ctx;
static void copy_both(void *ctx, const float *indirect, const float *full, const float *queue)
{
    (void)queue;
    copy_ctx *c = ctx;
    memcpy(c->ind, indirect, sizeof(float) * c->n);
    memcpy(c->full, full, sizeof(float) * c->n);
}

static void test_photons_stay_in_their_room(void **state)
{
    (void)state;
    gk_scene *s = load("light-leak");
    gk_err e = {0};
    gk_wall_regions r;
    assert_true(gk_split_walls(s, &r, &e) > 0);
    lm_atlas a;
    assert_int_equal(lm_atlas_build_regions(&a, s, 5, &r, &e), 0);
    lm_worker *w = lm_worker_create(s, &a, 1, &e);
    assert_non_null(w);
    lm_tick_settings set = {.groups = 154, .aim_texels = 1 << 20};
    for (int i = 0; i < 4; i++) {
        lm_worker_submit(w, s, &set);
        lm_worker_wait(w);
    }
    lm_worker_stats st;
    lm_worker_get_stats(w, &st);
    assert_false(st.failed);
    assert_int_equal(st.pending_surfaces, 0);
    size_t n = (size_t)a.width * (size_t)a.height * 4;
    copy_ctx c = {malloc(sizeof(float) * n), malloc(sizeof(float) * n), n};
    uint64_t seen = 0;
    assert_true(lm_worker_take(w, &seen, copy_both, &c));
    int dark = 0, lit = 0;
    for (int i = 0; i < a.n_charts; i++) {
        const lm_chart *ch = &a.charts[i];
        bool in_dark = ch->wmin.x > WALL - 1e-3f;
        for (int y = ch->y; y < ch->y + ch->h; y++)
            for (int x = ch->x; x < ch->x + ch->w; x++) {
                size_t k = ((size_t)y * (size_t)a.width + (size_t)x) * 4;
                float v = c.full[k] + c.full[k + 1] + c.full[k + 2] + c.ind[k] + c.ind[k + 1] + c.ind[k + 2];
                if (in_dark) {
                    assert_true(v == 0.0f);
                    dark++;
                } else if (ch->wmax.x < -WALL + 1e-3f && v > 0.0f) {
                    lit++;
                }
            }
    }
    print_message("light-leak: %d dark-room texels all 0, %d lit-room texels lit\n", dark, lit);
    assert_true(dark > 0 && lit > 0);
    free(c.ind), free(c.full);
    lm_worker_destroy(w);
    lm_atlas_free(&a);
    gk_wall_regions_free(&r);
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_light_leak_charts),
        cmocka_unit_test(test_cornell_untouched),
        cmocka_unit_test(test_photons_stay_in_their_room),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
