/* The lightmap method's CPU side (app/gi/lightmap/lm_photons.h, lm_aim.h, lm_worker.h), the
 * checklist of photon-mapping-000-004.md B.6 that needs no GPU:
 *  - stability: a static scene over 1,000 ticks: after the first complete trace and the AIM
 *    updates it causes, 0 group invalidations, 0 replaced paths, 0 AIM updates, the atlas
 *    bit-identical, with 1 and with 2 worker threads (and the two atlases equal);
 *  - budgets: never more AIM texels per tick than the budget (beyond the one surface a tick
 *    always gets), surfaces in Δ_f/area order;
 *  - locality (Fig. 5): two disconnected rooms, one light each; moving a box in room A
 *    invalidates groups of room A's light only, and room B's texels stay bit-identical;
 *  - round robin: a change in a group's domain is detected within P = 40 ticks;
 *  - a moving light (cornell-spot-anim's spot) invalidates groups every tick (M2);
 *  - the kd-tree's k nearest hits against brute force. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "gi/lightmap/lm_aim.h"
#include "gi/lightmap/lm_worker.h"

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

typedef struct copy_ctx {
    float *dst;
    size_t n;
    bool *queued;      /* per chart: queued for the final gather in any publication taken (or NULL) */
    int n_charts;
} copy_ctx;
static void copy_irr(void *ctx, const float *indirect, const float *full, const float *queue)
{
    (void)full;
    copy_ctx *c = ctx;
    memcpy(c->dst, indirect, sizeof(float) * c->n);
    for (int i = 0; c->queued && i < c->n_charts; i++)
        c->queued[i] |= queue[i] > 0.0f;
}

/* Ticks until no surface is pending (at most max), returns the ticks taken. */
static int converge(lm_worker *w, const gk_scene *s, const lm_tick_settings *set, int max)
{
    lm_worker_stats st;
    for (int i = 1; i <= max; i++) {
        lm_worker_submit(w, s, set);
        lm_worker_wait(w);
        lm_worker_get_stats(w, &st);
        assert_false(st.failed);
        if (i > 1 && st.pending_surfaces == 0 && st.invalidated == 0)
            return i;
    }
    fail_msg("no steady state within %d ticks", max);
    return -1;
}

static void static_run(const gk_scene *s, const lm_atlas *a, int threads, int ticks, float *out)
{
    gk_err e = {0};
    lm_worker *w = lm_worker_create(s, a, threads, &e);
    assert_non_null(w);
    lm_tick_settings set = {.groups = 77, .aim_texels = 80};
    int t0 = converge(w, s, &set, 200);
    size_t n = (size_t)a->width * (size_t)a->height * 4;
    uint64_t seen = 0;
    copy_ctx c = {out, n, NULL, 0};
    assert_true(lm_worker_take(w, &seen, copy_irr, &c));
    float *later = malloc(sizeof(float) * n);
    lm_worker_stats st;
    lm_worker_get_stats(w, &st);
    uint64_t inv0 = st.invalidations_total, tex0 = st.texels_total;
    for (int i = 0; i < ticks; i++) {
        lm_worker_submit(w, s, &set);
        lm_worker_wait(w);
        lm_worker_get_stats(w, &st);
        assert_int_equal(st.traced, 77);   /* one photon per group, round robin */
        assert_int_equal(st.replaced, 0);
        assert_int_equal(st.invalidated, 0);
        assert_int_equal(st.texels_updated, 0);
    }
    lm_worker_get_stats(w, &st);
    assert_int_equal(st.invalidations_total, inv0);
    assert_int_equal(st.texels_total, tex0);
    /* nothing new was published; the atlas is what it was */
    copy_ctx c2 = {later, n, NULL, 0};
    assert_false(lm_worker_take(w, &seen, copy_irr, &c2));
    double sum = 0;
    for (size_t i = 0; i < n; i += 4)
        sum += out[i] + out[i + 1] + out[i + 2];
    print_message("# cornell, %d thread(s): steady after %d ticks, %d ticks more: 0 invalidations, 0 updates; "
                  "atlas sum %.6g\n", threads, t0, ticks, sum);
    assert_true(sum > 0);
    free(later);
    lm_worker_destroy(w);
}

static void static_scene_is_stable_and_deterministic(void **state)
{
    (void)state;
    gk_scene *s = load("cornell");
    gk_err e = {0};
    lm_atlas a;
    assert_int_equal(lm_atlas_build(&a, s, 5, &e), 0);
    size_t n = (size_t)a.width * (size_t)a.height * 4;
    float *one = malloc(sizeof(float) * n), *two = malloc(sizeof(float) * n);
    static_run(s, &a, 1, 1000, one);
    static_run(s, &a, 2, 200, two);
    assert_memory_equal(one, two, sizeof(float) * n);
    free(one), free(two);
    lm_atlas_free(&a);
    gk_scene_free(s);
}

static void aim_budget_and_order(void **state)
{
    (void)state;
    gk_scene *s = load("cornell");
    gk_err e = {0};
    lm_atlas a;
    assert_int_equal(lm_atlas_build(&a, s, 5, &e), 0);
    lm_worker *w = lm_worker_create(s, &a, 1, &e);
    lm_tick_settings set = {.groups = 77, .aim_texels = 20};
    lm_worker_stats st;
    int ticks = 0;
    do {
        lm_worker_submit(w, s, &set);
        lm_worker_wait(w);
        lm_worker_get_stats(w, &st);
        ticks++;
        /* the largest cornell chart has 25 texels: one surface alone may exceed 20 */
        assert_true(st.texels_updated <= 20 || st.surfaces_updated == 1);
    } while ((st.pending_surfaces > 0 || ticks < 2) && ticks < 100);
    print_message("# cornell: AIM budget 20 texels: %d ticks to update every surface\n", ticks);
    assert_true(ticks > 2); /* 16 surfaces, 173 texels: the budget spreads them */
    lm_worker_destroy(w);

    /* Δ_f/area order, directly on the photons */
    lm_photons ph;
    gk_ref_scene rs;
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 0), 1, 1, &e), 0);
    assert_int_equal(lm_photons_init(&ph, &rs, 77, a.n_charts, 0.01f, &e), 0);
    for (int k = 0; k < ph.n_photons; k++) {
        lm_path p;
        lm_trace_photon(&ph, &rs, a.ref_chart, k, &p);
        lm_photons_replace(&ph, k, &p);
    }
    int *sel = malloc(sizeof *sel * (size_t)a.n_charts);
    int m = lm_aim_select(&a, &ph, 1 << 30, sel);
    assert_true(m >= 10);
    for (int i = 1; i < m; i++)
        assert_true(ph.stores[sel[i - 1]].delta_f / a.charts[sel[i - 1]].area >=
                    ph.stores[sel[i]].delta_f / a.charts[sel[i]].area);
    free(sel);
    lm_photons_free(&ph);
    gk_ref_scene_free(&rs);
    lm_atlas_free(&a);
    gk_scene_free(s);
}

/* Two closed rooms 1 m apart (room A: x in [0, 1], room B: x in [2, 3]), a point light in each,
   a small box in room A. */
static int box_node;
static void two_rooms(gkt_scene *t)
{
    gkt_scene_init(t, "two-rooms");
    int grey = gkt_material_lambert(t, v3(0.7f, 0.7f, 0.7f));
    for (int r = 0; r < 2; r++) {
        gkw_geom g = {0};
        gkb_box(&g, v3(2.0f * r, 0, 0), v3(2.0f * r + 1, 1, 1), true);
        gkt_object(t, &g, grey);
        gkt_light(t, GK_LIGHT_POINT, GK_SHAPE_POINT, 1.0f, v3(2.0f * r + 0.5f, 0.8f, 0.5f), v3(0, -1, 0));
    }
    gkw_geom b = {0};
    gkb_box(&b, v3(-0.1f, 0, -0.1f), v3(0.1f, 0.2f, 0.1f), false);
    box_node = gkt_object(t, &b, grey);
    t->nodes[box_node].translation = v3(0.3f, 0, 0.3f);
    gkt_scene_bounds(t);
    gk_scene_evaluate(&t->s, 0.0f);
}

static void locality_two_rooms(void **state)
{
    (void)state;
    gkt_scene t;
    two_rooms(&t);
    gk_err e = {0};
    lm_atlas a;
    assert_int_equal(lm_atlas_build(&a, &t.s, 5, &e), 0);
    lm_worker *w = lm_worker_create(&t.s, &a, 2, &e);
    assert_non_null(w);
    lm_tick_settings set = {.groups = 77, .aim_texels = 1 << 20};
    converge(w, &t.s, &set, 100);
    size_t n = (size_t)a.width * (size_t)a.height * 4;
    float *before = malloc(sizeof(float) * n), *after = malloc(sizeof(float) * n);
    uint64_t seen = 0;
    copy_ctx c = {before, n, NULL, 0};
    lm_worker_take(w, &seen, copy_irr, &c);
    unsigned inv0[77], inv1[77];
    float first[3 * 77];
    assert_int_equal(lm_worker_group_invalidations(w, inv0, 77), 77);
    lm_worker_group_first_hits(w, first, 77);

    /* move the box 20 cm, then run 2 P ticks */
    t.nodes[box_node].translation = v3(0.5f, 0, 0.5f);
    gk_scene_evaluate(&t.s, 0.0f);
    int detected_by = -1;
    lm_worker_stats st;
    bool *queued = calloc((size_t)a.n_charts, sizeof *queued);
    copy_ctx c2 = {after, n, queued, a.n_charts};
    for (int i = 0; i < 2 * LM_PHOTONS_PER_GROUP; i++) {
        lm_worker_submit(w, &t.s, &set);
        lm_worker_wait(w);
        lm_worker_take(w, &seen, copy_irr, &c2);
        lm_worker_get_stats(w, &st);
        if (st.invalidated > 0 && detected_by < 0)
            detected_by = i + 1;
    }
    for (int i = 0; i < 100; i++) {
        lm_worker_submit(w, &t.s, &set);
        lm_worker_wait(w);
        lm_worker_take(w, &seen, copy_irr, &c2);
    }
    assert_int_equal(lm_worker_group_invalidations(w, inv1, 77), 77);
    int in_a = 0, in_b = 0, inv_a = 0, inv_b = 0;
    for (int g = 0; g < 77; g++) {
        bool room_b = first[3 * g] > 1.5f;
        in_a += !room_b, in_b += room_b;
        inv_a += !room_b && inv1[g] > inv0[g];
        inv_b += room_b && inv1[g] > inv0[g];
    }
    /* room B's charts: texels bit-identical, none queued for the final gather */
    int texels_b = 0, changed_b = 0, changed_a = 0, queued_a = 0, queued_b = 0;
    for (int ci = 0; ci < a.n_charts; ci++)
        queued_a += queued[ci] && a.charts[ci].node != 2, queued_b += queued[ci] && a.charts[ci].node == 2;
    for (int ci = 0; ci < a.n_charts; ci++) {
        const lm_chart *ch = &a.charts[ci];
        bool room_b = a.charts[ci].node == 2; /* the second room's node (object, light, object...) */
        for (int y = ch->y; y < ch->y + ch->h; y++)
            for (int x = ch->x; x < ch->x + ch->w; x++) {
                size_t o = 4 * ((size_t)y * (size_t)a.width + (size_t)x);
                bool diff = memcmp(&before[o], &after[o], sizeof(float) * 4) != 0;
                texels_b += room_b;
                changed_b += room_b && diff;
                changed_a += !room_b && diff;
            }
    }
    print_message("# two rooms: groups A %d (%d invalidated), B %d (%d invalidated); detected after %d ticks; "
                  "texels changed: room A %d, room B %d of %d; surfaces queued for the gather: A %d, B %d\n", in_a,
                  inv_a, in_b, inv_b, detected_by, changed_a, changed_b, texels_b, queued_a, queued_b);
    assert_true(queued_a > 0);
    assert_int_equal(queued_b, 0);
    free(queued);
    assert_true(in_a > 20 && in_b > 20);
    assert_true(inv_a > 0);
    assert_int_equal(inv_b, 0);
    assert_true(texels_b > 0);
    assert_int_equal(changed_b, 0);
    assert_true(changed_a > 0);
    assert_true(detected_by > 0 && detected_by <= LM_PHOTONS_PER_GROUP);
    free(before), free(after);
    lm_worker_destroy(w);
    lm_atlas_free(&a);
    gkt_scene_free(&t);
}

static void moving_spot_invalidates(void **state)
{
    (void)state;
    gk_scene *s = load("cornell-spot-anim");
    gk_err e = {0};
    lm_atlas a;
    assert_int_equal(lm_atlas_build(&a, s, 5, &e), 0);
    lm_worker *w = lm_worker_create(s, &a, 1, &e);
    lm_tick_settings set = {.groups = 77, .aim_texels = 80};
    lm_worker_stats st;
    lm_worker_submit(w, s, &set);
    lm_worker_wait(w);
    int frames = 30, with_inv = 0;
    for (int i = 1; i <= frames; i++) {
        gk_scene_evaluate(s, (float)i / 60.0f);
        lm_worker_submit(w, s, &set);
        lm_worker_wait(w);
        lm_worker_get_stats(w, &st);
        with_inv += st.invalidated > 0;
    }
    print_message("# cornell-spot-anim: %d of %d frames invalidated groups; %llu invalidations in all\n", with_inv,
                  frames, (unsigned long long)st.invalidations_total);
    assert_false(st.failed);
    /* the spot turns every frame: at 1/60 s a frame its hits move more than tau on the far walls */
    assert_true(with_inv >= frames - 1);
    lm_worker_destroy(w);
    lm_atlas_free(&a);
    gk_scene_free(s);
}

static void kdtree_matches_brute_force(void **state)
{
    (void)state;
    lm_store s = {0};
    int n = 500;
    s.hits = calloc((size_t)n, sizeof *s.hits);
    s.n = s.cap = n;
    uint32_t r = 12345;
    for (int i = 0; i < n; i++) {
        float c[3];
        for (int k = 0; k < 3; k++) {
            r = r * 1664525u + 1013904223u;
            c[k] = (float)(r >> 8) / 16777216.0f;
        }
        s.hits[i] = (lm_hit){v3(c[0], c[1], 0.1f * c[2]), v3((float)i, 1, 0), i, 0, LM_HIT_INDIRECT};
    }
    lm_kdtree t = {0};
    const lm_store *one = &s;
    lm_kdtree_build(&t, &one, 1, 1u << LM_HIT_INDIRECT);
    assert_int_equal(t.n, n);
    for (int q = 0; q < 20; q++) {
        vec3 p = v3(0.05f * (float)q, 0.5f, 0.0f);
        float rk;
        vec3 sum = lm_kdtree_knn(&t, p, LM_KNN, &rk);
        /* brute force: the 100 smallest distances */
        float *d = malloc(sizeof(float) * (size_t)n);
        for (int i = 0; i < n; i++)
            d[i] = v3_len(v3_sub(s.hits[i].pos, p));
        float kth = 0;
        double bsum = 0;
        for (int k = 0; k < LM_KNN; k++) {
            int best = -1;
            for (int i = 0; i < n; i++)
                if (d[i] >= 0 && (best < 0 || d[i] < d[best]))
                    best = i;
            kth = d[best], bsum += best, d[best] = -1;
        }
        assert_float_equal(rk, kth, 1e-6f);
        assert_float_equal(sum.x, (float)bsum, 1e-2f);
        assert_float_equal(sum.y, (float)LM_KNN, 1e-4f);
        free(d);
    }
    lm_kdtree_free(&t);
    free(s.hits);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(kdtree_matches_brute_force),
        cmocka_unit_test(static_scene_is_stable_and_deterministic),
        cmocka_unit_test(aim_budget_and_order),
        cmocka_unit_test(locality_two_rooms),
        cmocka_unit_test(moving_spot_invalidates),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
