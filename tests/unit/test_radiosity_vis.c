/* radiosity_vis=rays (app/gi/radiosity/rad_vis.h, issue 11): walls split the surfaces they cross
 * (scene/wall_split.h) and every leaf link is tested with a shadow ray.
 *  - light-leak, whose dark room's correct radiance is 0: with the seed's implicit visibility the
 *    dark room receives light (the failure this would catch); with the cuts alone still; with cuts
 *    and rays every dark-room surfel's radiance is exactly 0 after 4 bounces (direct light from the
 *    tracer's shadow rays, as the method's worker does), while the lit room's is not; at the
 *    default refinement and at the seed's leaking 792-vertex one;
 *  - the furnace, where nothing stands between any two surfaces: the rays remove no link. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/scene_file.h"
#include "gi/radiosity/rad_direct.h"
#include "gi/radiosity/rad_solve.h"
#include "gi/radiosity/rad_vis.h"
#include "scene/wall_split.h"

#define WALL 0.01f /* light-leak's wall: x in [-0.01, 0.01] */

static gk_scene *load(const char *name)
{
    gk_err e = {0};
    gk_scene *s = gkt_load_scene(name, &e);
    if (!s)
        fail_msg("%s", e.msg);
    return s;
}

static float default_edge(const gk_scene *s) { return v3_len(v3_sub(s->bmax, s->bmin)) / 24.0f; } /* radiosity_tess 24 */

typedef struct rooms {
    double lit, dark;   /* mean radiance (sum of RGB) over each room's surfels, area-weighted */
    double dark_max;    /* the brightest dark-room surfel */
    long culled;
} rooms;

/* Builds light-leak's radiosity (cut along its walls when regions is given, link rays when rays) and
   solves 4 bounces on the CPU. */
static rooms solve(const gk_scene *s, const gk_wall_regions *regions, bool rays, float edge)
{
    gk_ref_scene rs;
    gk_err e = {0};
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 0), 1, 1, &e), 0);
    rad_geometry g;
    assert_int_equal(rad_geometry_build_regions(&g, s, regions, edge, 60000, 12, RAD_WEIGHT_SPILL, &e), 0);
    rooms r = {0};
    if (rays)
        r.culled = rad_links_cull_occluded(&g.links, &g.tree, &rs);
    int nl = g.tree.n_leaves, nn = g.tree.n_nodes;
    float *ed = malloc(sizeof *ed * 3 * (size_t)nl), *b0 = malloc(sizeof *b0 * 3 * (size_t)nn);
    float *ind = malloc(sizeof *ind * 3 * (size_t)nl);
    assert_non_null(ed), assert_non_null(b0), assert_non_null(ind);
    rad_direct_irradiance(&rs, &g.tree, 16, 0, nl, ed);
    rad_initial_radiance(&g, ed, b0);
    assert_int_equal(rad_solve_cpu(&g, b0, 4, ind), 0);
    double lit_a = 0, dark_a = 0;
    for (int i = 0; i < nl; i++) {
        double L = 0;
        for (int c = 0; c < 3; c++)
            L += b0[3 * i + c] + g.albedo[3 * i + c] / M_PI * ind[3 * i + c];
        double a = g.tree.area[i];
        if (g.tree.pos[i].x < -WALL)
            r.lit += L * a, lit_a += a;
        else if (g.tree.pos[i].x > WALL) {
            r.dark += L * a, dark_a += a;
            r.dark_max = fmax(r.dark_max, L);
        }
    }
    r.lit /= lit_a, r.dark /= dark_a;
    free(ed), free(b0), free(ind);
    rad_geometry_free(&g);
    gk_ref_scene_free(&rs);
    return r;
}

static void test_light_leak_dark_room_black(void **state)
{
    (void)state;
    gk_scene *s = load("light-leak");
    float edge = default_edge(s);
    rooms seed = solve(s, NULL, false, edge);
    gk_wall_regions regions;
    gk_err e = {0};
    assert_int_equal(gk_split_walls(s, &regions, &e), 8); /* test_lightmap_split.c: 4 surfaces x 2 sides */
    rooms cut = solve(s, &regions, false, edge);
    rooms rays = solve(s, &regions, true, edge);
    rooms coarse = solve(s, &regions, true, 0.95f); /* the seed's ~792 vertices (test_radiosity_limits.c) */
    printf("# light-leak dark / lit room mean radiance: seed %.4f, walls cut %.4f, cut + rays %.3g "
           "(%ld links culled; brightest dark surfel %.3g), coarse cut + rays %.3g\n",
           seed.dark / seed.lit, cut.dark / cut.lit, rays.dark / rays.lit, rays.culled, rays.dark_max,
           coarse.dark / coarse.lit);
    /* measured: seed 0.0515, cut 0.0509 (the dark room lit through the bins that look through the
       wall, rad_vis.h), cut + rays exactly 0 at both refinements (183,570 links culled) */
    assert_true(seed.dark / seed.lit > 0.01);
    assert_true(cut.dark / cut.lit > 0.01);
    assert_true(rays.lit > 0.0 && coarse.lit > 0.0);
    assert_true(rays.culled > 0);
    assert_true(rays.dark_max == 0.0);
    assert_true(coarse.dark_max == 0.0);
    gk_wall_regions_free(&regions);
    gk_scene_free(s);
}

static void test_furnace_nothing_culled(void **state)
{
    (void)state;
    gk_scene *s = load("furnace");
    gk_ref_scene rs;
    gk_err e = {0};
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 0), 1, 1, &e), 0);
    rad_geometry g;
    assert_int_equal(rad_geometry_build(&g, s, default_edge(s), 60000, 12, RAD_WEIGHT_SPILL, &e), 0);
    double before = 0, after = 0;
    uint32_t n = g.links.offset[g.links.n_leaves];
    for (uint32_t k = 0; k < n; k++)
        before += g.links.weight[k];
    long culled = rad_links_cull_occluded(&g.links, &g.tree, &rs);
    for (uint32_t k = 0; k < n; k++)
        after += g.links.weight[k];
    printf("# furnace: %ld of %u links culled, %.3g of their weight\n", culled, n, (before - after) / before);
    /* measured: none of its 859,881 links (the furnace image is identical with and without rays) */
    assert_int_equal(culled, 0);
    assert_true(after == before);
    rad_geometry_free(&g);
    gk_ref_scene_free(&rs);
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_light_leak_dark_room_black),
        cmocka_unit_test(test_furnace_nothing_culled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
