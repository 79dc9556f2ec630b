/* Moving meshes in the radiosity method (app/gi/radiosity: rad_mesh_refit, rad_tree_refit,
 * rad_links_update, the worker's link update rate; seed 001 ch. 4 Algorithm 1 steps 1-4). cornell
 * with its short block made to move (the node flagged animated, its world matrix set per frame):
 *  - UpdateElements: after a rigid move (rotation about y + translation) every node of the block's
 *    charts sits at M x its rest position and turns its normal by M (within float rounding), the
 *    rest of the hierarchy does not move, and a refit at the build pose moves nothing;
 *  - incremental links equal a full build at the same pose, link for link (targets and weights),
 *    while linking only the pairs with a moving chart (the measured share is printed);
 *  - the links follow the block: the floor's indirect irradiance with links rebuilt at the new pose
 *    against the stale links of the old pose (what radiosity_link_every > 1 shows in between), both
 *    against a geometry built from scratch at the new pose;
 *  - the worker: the render thread's submit/take never wait for a link build (the worker is busy
 *    building while 200 submits return), requests coalesce to the newest, and radiosity_link_every=2
 *    rebuilds the links on every second tick that moved the block;
 *  - research 2.6's "hierarchy not adapted to deformation": the block stretched x3 in height, the
 *    refit (rest areas and grouping) against a geometry built from scratch at the stretched pose;
 *  - the method is offered where a mesh moves. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gi/radiosity/rad_solve.h"
#include "gi/radiosity/radiosity.h"

static gk_scene *load_moving_block(int *block)
{
    gk_err e = {0};
    gk_scene *s = gk_scene_load("config/scenes/cornell.gltf", &e);
    if (!s)
        fail_msg("%s", e.msg);
    gk_scene_evaluate(s, 0.0f);
    *block = -1;
    for (int i = 0; i < s->n_nodes; i++)
        if (strcmp(s->nodes[i].name, "short-block") == 0)
            *block = i;
    assert_true(*block >= 0);
    s->nodes[*block].animated = true; /* as a glTF animation channel on it would flag it */
    return s;
}

/* The block turned by deg about the vertical through (0.186, 0, 0.169) (its centre) and shifted. */
static mat4 block_motion(float deg, vec3 shift)
{
    vec3 c = v3(0.186f, 0.0f, 0.169f), one = v3(1, 1, 1);
    float h = 0.5f * deg * (float)M_PI / 180.0f;
    quat r = {0.0f, sinf(h), 0.0f, cosf(h)};
    quat id = {0.0f, 0.0f, 0.0f, 1.0f};
    mat4 to = m4_trs(v3_scale(c, -1.0f), id, one), back = m4_trs(v3_add(c, shift), id, one);
    return m4_mul(back, m4_mul(m4_trs(v3(0, 0, 0), r, one), to));
}

static mat4 *worlds_of(const gk_scene *s)
{
    mat4 *w = malloc(sizeof *w * (size_t)s->n_nodes);
    for (int i = 0; i < s->n_nodes; i++)
        w[i] = s->nodes[i].world;
    return w;
}

static float dist(vec3 a, vec3 b) { return v3_len(v3_sub(a, b)); }

static void test_refit_moves_the_block_rigidly(void **state)
{
    (void)state;
    int block;
    gk_scene *s = load_moving_block(&block);
    rad_geometry g;
    gk_err e = {0};
    assert_int_equal(rad_geometry_build(&g, s, 0.1f, 60000, 8, RAD_WEIGHT_SPILL, &e), 0);
    mat4 *w = worlds_of(s);
    assert_int_equal(rad_geometry_refit(&g, w, s->n_nodes), 0); /* the build pose: nothing moves */
    rad_tree rest;
    rad_geometry copy;
    assert_int_equal(rad_geometry_clone(&copy, &g), 0);
    rest = copy.tree;
    mat4 M = block_motion(20.0f, v3(0.05f, 0.0f, 0.03f));
    w[block] = m4_mul(M, s->nodes[block].world);
    int moved = rad_geometry_refit(&g, w, s->n_nodes);
    assert_int_equal(moved, rad_geometry_moving_charts(&g));
    assert_int_equal(moved, 5); /* top and four sides (the bottom is not drawn) */
    float worst_pos = 0.0f, worst_nrm = 0.0f, static_moved = 0.0f;
    for (int i = 0; i < g.tree.n_nodes; i++) {
        bool mv = g.mesh.charts[g.tree.node_chart[i]].moving;
        if (mv) {
            worst_pos = fmaxf(worst_pos, dist(g.tree.pos[i], m4_point(M, rest.pos[i])));
            worst_nrm = fmaxf(worst_nrm, dist(g.tree.nrm[i], v3_norm(m4_dir(M, rest.nrm[i]))));
        } else
            static_moved = fmaxf(static_moved, dist(g.tree.pos[i], rest.pos[i]) + dist(g.tree.nrm[i], rest.nrm[i]));
        assert_true(g.tree.area[i] == rest.area[i]); /* the seed: areas are not refit */
    }
    printf("# refit: worst node position error %.2g m, normal %.2g\n", (double)worst_pos, (double)worst_nrm);
    /* float rounding of a 4x4 product at 0.5 m coordinates: ~1e-7 m; 1e-5 leaves room and still
       catches any averaging or transform mistake (a misplaced node is centimetres off) */
    assert_true(worst_pos < 1e-5f);
    assert_true(worst_nrm < 1e-5f);
    assert_true(static_moved == 0.0f);
    /* back to the build pose: the rest positions again (the refit starts from the rest pose) */
    w[block] = s->nodes[block].world;
    assert_int_equal(rad_geometry_refit(&g, w, s->n_nodes), 5);
    for (int i = 0; i < g.tree.n_nodes; i++)
        assert_true(dist(g.tree.pos[i], rest.pos[i]) < 1e-6f);
    rad_geometry_free(&copy);
    rad_geometry_free(&g);
    free(w);
    gk_scene_free(s);
}

static void test_incremental_links_equal_full(void **state)
{
    (void)state;
    int block;
    gk_scene *s = load_moving_block(&block);
    rad_geometry g;
    gk_err e = {0};
    assert_int_equal(rad_geometry_build(&g, s, 0.1f, 60000, 8, RAD_WEIGHT_SPILL, &e), 0);
    mat4 *w = worlds_of(s);
    rad_link_cache cache = {0};
    long pairs_total = (long)g.tree.n_charts * (g.tree.n_charts - 1) / 2;
    for (int step = 0; step < 3; step++) {
        w[block] = m4_mul(block_motion(10.0f * (float)(step + 1), v3(0.02f * (float)step, 0.0f, 0.0f)),
                          s->nodes[block].world);
        rad_geometry_refit(&g, w, s->n_nodes);
        assert_int_equal(rad_geometry_relink(&g, &cache, &e), 0);
        rad_links full;
        assert_int_equal(rad_links_build(&full, &g.tree, 8, RAD_WEIGHT_SPILL, &e), 0);
        assert_int_equal(full.offset[full.n_leaves], g.links.offset[g.links.n_leaves]);
        assert_memory_equal(full.offset, g.links.offset, sizeof *full.offset * ((size_t)full.n_leaves + 1));
        assert_memory_equal(full.target, g.links.target, sizeof *full.target * full.offset[full.n_leaves]);
        assert_memory_equal(full.weight, g.links.weight, sizeof *full.weight * full.offset[full.n_leaves]);
        /* the empty bins, where the environment comes in (rad_env.h), too */
        assert_memory_equal(full.empty, g.links.empty, sizeof *full.empty * (size_t)full.n_leaves * (size_t)full.empty_words);
        assert_int_equal(g.links.pairs_linked + g.links.pairs_cached, pairs_total);
        printf("# step %d: %ld leaf links, identical to the full build; %ld of %ld root pairs linked (%.1f%%)\n",
               step, g.links.leaf_links, g.links.pairs_linked, pairs_total,
               100.0 * (double)g.links.pairs_linked / (double)pairs_total);
        /* 15 charts, the block's 5 moving: 5 x 10 pairs with a static chart + 10 among themselves */
        assert_int_equal(g.links.pairs_linked, 60);
        rad_links_free(&full);
    }
    rad_link_cache_free(&cache);
    rad_geometry_free(&g);
    free(w);
    gk_scene_free(s);
}

/* area-weighted mean of |a - b| / mean(b) over the floor's leaves (normal +y, y < 1 mm) */
static double floor_difference(const rad_geometry *g, const float *a, const float *b)
{
    double d = 0.0, m = 0.0;
    for (int i = 0; i < g->tree.n_leaves; i++) {
        if (g->tree.nrm[i].y < 0.99f || g->tree.pos[i].y > 1e-3f)
            continue;
        for (int c = 0; c < 3; c++)
            d += fabs((double)a[3 * i + c] - b[3 * i + c]) * g->tree.area[i], m += b[3 * i + c] * g->tree.area[i];
    }
    return m > 0.0 ? d / m : 0.0;
}

/* Indirect irradiance of geometry g with emission on the ceiling light only: B0 = the light's
   direct light is not needed to see the block's links; the white walls lit uniformly (B0 = 1 nit
   everywhere but the floor) make the floor's gather show which walls and block faces it sees. */
static void gather_floor(const rad_geometry *g, float *e_ind)
{
    float *b0 = malloc(sizeof *b0 * 3 * (size_t)g->tree.n_nodes);
    for (int i = 0; i < g->tree.n_leaves; i++)
        for (int c = 0; c < 3; c++)
            b0[3 * i + c] = g->tree.nrm[i].y > 0.99f && g->tree.pos[i].y < 1e-3f ? 0.0f
                            : g->mesh.charts[g->mesh.chart[i]].moving ? 4.0f : 1.0f;
    rad_pullup(&g->tree, b0);
    assert_int_equal(rad_solve_cpu(g, b0, 1, e_ind), 0);
    free(b0);
}

static void test_links_follow_the_block(void **state)
{
    (void)state;
    int block;
    gk_scene *s = load_moving_block(&block);
    rad_geometry g, stale;
    gk_err e = {0};
    assert_int_equal(rad_geometry_build(&g, s, 0.1f, 60000, 8, RAD_WEIGHT_SPILL, &e), 0);
    mat4 *w = worlds_of(s);
    mat4 M = block_motion(0.0f, v3(0.12f, 0.0f, 0.10f));
    w[block] = m4_mul(M, s->nodes[block].world);
    rad_geometry_refit(&g, w, s->n_nodes);
    assert_int_equal(rad_geometry_clone(&stale, &g), 0); /* refit, links of the build pose */
    rad_link_cache cache = {0};
    assert_int_equal(rad_geometry_relink(&g, &cache, &e), 0);
    /* from scratch at the new pose (a translation keeps the Morton order, so the same leaves) */
    s->nodes[block].world = w[block];
    rad_geometry fresh;
    assert_int_equal(rad_geometry_build(&fresh, s, 0.1f, 60000, 8, RAD_WEIGHT_SPILL, &e), 0);
    assert_int_equal(fresh.tree.n_leaves, g.tree.n_leaves);
    size_t n = 3 * (size_t)g.tree.n_leaves;
    float *eg = malloc(sizeof *eg * n), *es = malloc(sizeof *es * n), *ef = malloc(sizeof *ef * n);
    gather_floor(&g, eg);
    gather_floor(&stale, es);
    gather_floor(&fresh, ef);
    double d_relinked = floor_difference(&g, eg, ef), d_stale = floor_difference(&g, es, ef);
    printf("# block moved 16 cm: floor irradiance vs a fresh build: relinked %.4f, stale links %.4f\n", d_relinked,
           d_stale);
    /* measured: relinked 0.0000 (the same links: leaves, hierarchy and pose agree to rounding),
       stale 0.375 (the floor gathers from where the block was); the bounds: relinked below 1e-3,
       stale above 0.1 (a third of the measured) */
    assert_true(d_relinked < 1e-3);
    assert_true(d_stale > 0.1);
    free(eg), free(es), free(ef);
    rad_link_cache_free(&cache);
    rad_geometry_free(&fresh), rad_geometry_free(&stale), rad_geometry_free(&g);
    free(w);
    gk_scene_free(s);
}

/* Research 2.6: "hierarchy precomputed once, not adapted to deformation". The short block
   stretched x3 in height (a scale about its base): the refit moves the surfels but keeps the rest
   pose's areas and vertex grouping; against a geometry built from scratch at the stretched pose
   (three times the block's surfels), the floor's gather is off. The floor's leaves are the same in
   both (chart 0, static). */
static void test_stretch_not_adapted(void **state)
{
    (void)state;
    int block;
    gk_scene *s = load_moving_block(&block);
    rad_geometry g;
    gk_err e = {0};
    assert_int_equal(rad_geometry_build(&g, s, 0.1f, 60000, 8, RAD_WEIGHT_SPILL, &e), 0);
    mat4 *w = worlds_of(s);
    mat4 stretch = m4_trs(v3(0, 0, 0), (quat){0, 0, 0, 1}, v3(1, 3, 1));
    w[block] = m4_mul(stretch, s->nodes[block].world);
    rad_geometry_refit(&g, w, s->n_nodes);
    rad_link_cache cache = {0};
    assert_int_equal(rad_geometry_relink(&g, &cache, &e), 0);
    s->nodes[block].world = w[block];
    rad_geometry fresh;
    assert_int_equal(rad_geometry_build(&fresh, s, 0.1f, 60000, 8, RAD_WEIGHT_SPILL, &e), 0);
    assert_int_equal(fresh.mesh.charts[0].n_verts, g.mesh.charts[0].n_verts);
    assert_int_equal(fresh.mesh.charts[0].first_vert, g.mesh.charts[0].first_vert);
    size_t n = 3 * (size_t)fresh.tree.n_leaves;
    float *eg = malloc(sizeof *eg * 3 * (size_t)g.tree.n_leaves), *ef = malloc(sizeof *ef * n);
    gather_floor(&g, eg);
    gather_floor(&fresh, ef);
    double d = floor_difference(&fresh, eg, ef);
    double block_area_refit = 0, block_area_fresh = 0;
    for (int i = 0; i < g.tree.n_leaves; i++)
        block_area_refit += g.mesh.charts[g.mesh.chart[i]].moving ? g.tree.area[i] : 0.0f;
    for (int i = 0; i < fresh.tree.n_leaves; i++)
        block_area_fresh += fresh.mesh.charts[fresh.mesh.chart[i]].moving ? fresh.tree.area[i] : 0.0f;
    printf("# block stretched x3: %d vs %d surfels, block area %.4f (rest, kept) vs %.4f m²; floor irradiance vs a fresh build %.4f\n",
           g.tree.n_leaves, fresh.tree.n_leaves, block_area_refit, block_area_fresh, d);
    /* measured 0.234 (601 refit surfels with the rest pose's 0.137 m² against 733 with 0.357 m²:
       the kept areas weigh the block's surfels 2.6x too low, and the grouping is the rest pose's);
       a rigidly moved block: 0.0000 (test_links_follow_the_block). Bound: above 0.1 -- the
       limitation shows, as research 2.6 expects of a strong deformation */
    assert_true(d > 0.1);
    free(eg), free(ef);
    rad_link_cache_free(&cache);
    rad_geometry_free(&fresh), rad_geometry_free(&g);
    free(w);
    gk_scene_free(s);
}

typedef struct taken { uint64_t links_id; mat4 pose; int moving_chart; } taken;

static void take_pose(void *ctx, const rad_geometry *g, uint64_t geometry_id, const float *b0)
{
    (void)geometry_id, (void)b0;
    taken *t = ctx;
    t->links_id = g->links_id;
    for (int c = 0; c < g->mesh.n_charts; c++)
        if (g->mesh.charts[c].moving) {
            t->pose = g->mesh.charts[c].pose;
            t->moving_chart = c;
        }
}

static void test_worker_never_blocks_the_frame(void **state)
{
    (void)state;
    int block;
    gk_scene *s = load_moving_block(&block);
    gk_err e = {0};
    rad_worker *wk = rad_worker_create(s, NULL, &e);
    assert_non_null(wk);
    /* 6x16² at ~5k vertices: a link build of seconds on llvmpipe's machine */
    vec3 ext = v3_sub(s->bmax, s->bmin);
    rad_settings set = {.edge = v3_len(ext) / 32.0f, .n_face = 16, .weight = RAD_WEIGHT_SPILL, .samples = 4,
                        .max_verts = 60000, .link_every = 1};
    mat4 rest = s->nodes[block].world;
    rad_worker_submit(wk, s, &set);
    rad_worker_stats st;
    do { /* until the worker took the request (it is building) */
        sched_yield();
        rad_worker_get_stats(wk, &st);
    } while (!st.busy && st.ticks == 0);
    uint64_t seen = 0;
    taken tk = {0};
    int submits = 200;
    for (int k = 1; k <= submits; k++) {
        s->nodes[block].world = m4_mul(block_motion(0.0f, v3(0.0005f * (float)k, 0, 0)), rest);
        rad_worker_submit(wk, s, &set);
        rad_worker_take(wk, &seen, take_pose, &tk);
    }
    rad_worker_get_stats(wk, &st);
    printf("# %d submits returned while the first tick built (ticks %llu, busy %d)\n", submits,
           (unsigned long long)st.ticks, st.busy);
    assert_int_equal(st.ticks, 0); /* the first build is still running: no submit waited for it */
    rad_worker_wait(wk);
    rad_worker_get_stats(wk, &st);
    assert_false(st.failed);
    /* the 200 requests coalesced: the build, then the newest pose (one refit and one link update) */
    assert_int_equal(st.ticks, 2);
    assert_int_equal(st.submitted, (uint64_t)submits + 1);
    assert_int_equal(st.refits, 1);
    assert_int_equal(st.link_updates, 1);
    assert_true(rad_worker_take(wk, &seen, take_pose, &tk));
    mat4 want = m4_mul(m4_mul(block_motion(0.0f, v3(0.0005f * (float)submits, 0, 0)), rest), m4_inverse(rest));
    for (int i = 0; i < 16; i++)
        assert_true(fabsf(tk.pose.m[i] - want.m[i]) < 1e-5f);
    rad_worker_destroy(wk);
    gk_scene_free(s);
}

static void test_link_update_rate(void **state)
{
    (void)state;
    int block;
    gk_scene *s = load_moving_block(&block);
    gk_err e = {0};
    rad_worker *wk = rad_worker_create(s, NULL, &e);
    assert_non_null(wk);
    vec3 ext = v3_sub(s->bmax, s->bmin);
    rad_settings set = {.edge = v3_len(ext) / 16.0f, .n_face = 8, .weight = RAD_WEIGHT_SPILL, .samples = 4,
                        .max_verts = 60000, .link_every = 2};
    mat4 rest = s->nodes[block].world;
    uint64_t seen = 0, ids[9] = {0};
    taken tk = {0};
    for (int k = 0; k < 9; k++) { /* lockstep: every request its own tick */
        s->nodes[block].world = m4_mul(block_motion(5.0f * (float)k, v3(0, 0, 0)), rest);
        rad_worker_submit(wk, s, &set);
        rad_worker_wait(wk);
        assert_true(rad_worker_take(wk, &seen, take_pose, &tk));
        ids[k] = tk.links_id;
    }
    rad_worker_stats st;
    rad_worker_get_stats(wk, &st);
    assert_false(st.failed);
    /* tick 0 builds; ticks 1..8 move the block: links on ticks 2, 4, 6, 8 */
    assert_int_equal(st.geometry_builds, 1);
    assert_int_equal(st.refits, 8);
    assert_int_equal(st.link_updates, 4);
    for (int k = 1; k < 9; k++)
        assert_true((ids[k] != ids[k - 1]) == (k % 2 == 0));
    assert_int_equal(st.moving_charts, 5);
    rad_worker_destroy(wk);
    gk_scene_free(s);
}

/* the bench's --rebuild-gi: a static scene redoes the seed's whole per-frame pipeline on request */
static void test_redo_rebuilds_every_link(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_scene *s = gk_scene_load("config/scenes/cornell.gltf", &e);
    if (!s)
        fail_msg("%s", e.msg);
    gk_scene_evaluate(s, 0.0f);
    rad_worker *wk = rad_worker_create(s, NULL, &e);
    assert_non_null(wk);
    vec3 ext = v3_sub(s->bmax, s->bmin);
    rad_settings set = {.edge = v3_len(ext) / 16.0f, .n_face = 8, .weight = RAD_WEIGHT_SPILL, .samples = 4,
                        .max_verts = 60000, .link_every = 1};
    uint64_t seen = 0;
    taken tk = {0};
    for (int k = 0; k < 2; k++) { /* static: the second request publishes nothing */
        rad_worker_submit(wk, s, &set);
        rad_worker_wait(wk);
        assert_true(rad_worker_take(wk, &seen, take_pose, &tk) == (k == 0));
    }
    uint64_t first_links = tk.links_id;
    rad_worker_redo(wk);
    rad_worker_submit(wk, s, &set);
    rad_worker_wait(wk);
    assert_true(rad_worker_take(wk, &seen, take_pose, &tk));
    rad_worker_stats st;
    rad_worker_get_stats(wk, &st);
    assert_false(st.failed);
    assert_int_equal(st.geometry_builds, 1);
    assert_int_equal(st.link_updates, 1);
    assert_int_equal(st.direct_updates, 2);
    assert_true(tk.links_id != first_links);
    assert_int_equal(st.pairs_cached, 0); /* every pair linked anew */
    assert_int_equal(st.pairs_linked, (long)st.charts * (st.charts - 1) / 2);
    rad_worker_destroy(wk);
    gk_scene_free(s);
}

static void test_offered_where_a_mesh_moves(void **state)
{
    (void)state;
    int block;
    gk_scene *s = load_moving_block(&block);
    assert_true(gk_gi_radiosity.applies(s));
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refit_moves_the_block_rigidly),
        cmocka_unit_test(test_incremental_links_equal_full),
        cmocka_unit_test(test_links_follow_the_block),
        cmocka_unit_test(test_stretch_not_adapted),
        cmocka_unit_test(test_worker_never_blocks_the_frame),
        cmocka_unit_test(test_link_update_rate),
        cmocka_unit_test(test_redo_rebuilds_every_link),
        cmocka_unit_test(test_offered_where_a_mesh_moves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
