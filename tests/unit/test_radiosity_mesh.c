/* The radiosity method's geometry (app/gi/radiosity/rad_mesh.h, rad_tree.h), research
 * dong-001.md §2.2: refinement to a target edge length, charts, surfels, the pointer-less quadtree.
 *  - area conservation: the surfels' areas (1/3 of their triangles') sum to the scene's surface;
 *  - refinement counts: furnace (6 faces of 4 x 4 cells of 0.5 m) at edge 0.5 m cuts each cell's
 *    diagonal (0.71 m) in two: an 8 x 8 grid, 81 vertices a face, 6 charts;
 *  - the seed's full 3-level tree: 16 leaves -> 21 nodes, leaves 0-15, level 1 16-19, root 20;
 *  - parent/children arithmetic against each other for every node of real scenes, areas summing
 *    up, a root per chart;
 *  - a refinement past the vertex limit is an input error naming the scene;
 *  - the refined vertex counts `gikiosk scenes` prints (gk_radiosity_refined_vertices), counted
 *    another way: by Euler's formula from the refined triangles alone, a chart being a triangulated
 *    disc (V = 1 + (F + B) / 2, F its triangles, B its boundary edges). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gi/radiosity/rad_tree.h"
#include "gi/radiosity/radiosity.h"

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

static double sum_area(const rad_mesh *m)
{
    double a = 0.0;
    for (int i = 0; i < m->n_verts; i++)
        a += m->area[i];
    return a;
}

static void test_area_conservation(void **state)
{
    (void)state;
    const char *scenes[] = {"furnace", "cornell", "cornell-spot"};
    const float edges[] = {0.5f, 0.25f, 0.1f};
    for (int si = 0; si < 3; si++) {
        gk_scene *s = load(scenes[si]);
        for (int k = 0; k < 3; k++) {
            rad_mesh m;
            gk_err e = {0};
            if (rad_mesh_build(&m, s, edges[k] * v3_len(v3_sub(s->bmax, s->bmin)) / 3.5f, 200000, &e))
                fail_msg("%s: %s", scenes[si], e.msg);
            double a = sum_area(&m);
            /* float sums over thousands of surfels: 1e-4 relative is ~10x their rounding */
            assert_true(fabs(a - m.surface_area) <= 1e-4 * m.surface_area);
            printf("# %s edge %.3f: %d source triangles -> %d vertices, %d triangles, %d charts, area %.4f\n", scenes[si],
                   (double)m.edge, m.n_source_tris, m.n_verts, m.n_tris, m.n_charts, a);
            /* every refined triangle's vertices lie in its chart */
            for (int t = 0; t < m.n_tris; t++)
                assert_int_equal(m.chart[m.tris[3 * t]], m.chart[m.tris[3 * t + 2]]);
            rad_mesh_free(&m);
        }
        gk_scene_free(s);
    }
}

static void test_furnace_counts(void **state)
{
    (void)state;
    gk_scene *s = load("furnace");
    rad_mesh m;
    gk_err e = {0};
    assert_int_equal(rad_mesh_build(&m, s, 0.5f, 100000, &e), 0);
    assert_int_equal(m.n_charts, 6);
    assert_int_equal(m.n_verts, 6 * 81);
    assert_int_equal(m.n_tris, 6 * 8 * 8 * 2);
    assert_true(fabs(m.surface_area - 24.0) < 1e-3);
    for (int c = 0; c < 6; c++) {
        assert_int_equal(m.charts[c].n_verts, 81);
        /* the chart's normal points into the box (the furnace's faces face the centre) */
        vec3 p = m.pos[m.charts[c].first_vert];
        assert_true(v3_dot(m.charts[c].normal, p) < 0.0f);
    }
    /* interior surfels: (0.25 m)² each, edge ones half, corner ones a quarter or an eighth */
    int interior = 0;
    for (int i = 0; i < m.n_verts; i++)
        interior += fabsf(m.area[i] - 0.0625f) < 1e-6f;
    assert_int_equal(interior, 6 * 7 * 7);
    rad_mesh_free(&m);
    /* an edge as long as a cell's diagonal leaves the 4 x 4 grid as it is */
    assert_int_equal(rad_mesh_build(&m, s, 0.75f, 100000, &e), 0);
    assert_int_equal(m.n_verts, 6 * 25);
    rad_mesh_free(&m);
    gk_scene_free(s);
}

typedef struct edge_key { uint32_t a, b; } edge_key;

static int cmp_edge_key(const void *x, const void *y)
{
    const edge_key *p = x, *q = y;
    return p->a != q->a ? (p->a < q->a ? -1 : 1) : p->b != q->b ? (p->b < q->b ? -1 : 1) : 0;
}

/* Σ over charts of 1 + (F + B) / 2, from the triangles only */
static long euler_vertices(const rad_mesh *m)
{
    edge_key *ed = malloc(sizeof *ed * 3 * (size_t)m->n_tris);
    long total = 0;
    for (int c = 0; c < m->n_charts; c++) {
        size_t n = 0;
        long f = 0;
        for (int t = 0; t < m->n_tris; t++) {
            if (m->chart[m->tris[3 * t]] != c)
                continue;
            f++;
            for (int k = 0; k < 3; k++) {
                uint32_t a = m->tris[3 * t + k], b = m->tris[3 * t + (k + 1) % 3];
                ed[n++] = (edge_key){a < b ? a : b, a < b ? b : a};
            }
        }
        qsort(ed, n, sizeof *ed, cmp_edge_key);
        long boundary = 0;
        for (size_t i = 0; i < n;) {
            size_t j = i;
            while (j < n && cmp_edge_key(&ed[i], &ed[j]) == 0)
                j++;
            boundary += j - i == 1;
            i = j;
        }
        total += 1 + (f + boundary) / 2;
    }
    free(ed);
    return total;
}

static void test_refined_counts_by_euler(void **state)
{
    (void)state;
    const char *scenes[] = {"cornell", "furnace", "light-leak"};
    for (int si = 0; si < 3; si++) {
        gk_scene *s = load(scenes[si]);
        printf("# %s:", scenes[si]);
        for (int l = 0; l < gk_radiosity_tess_levels(); l++) {
            gk_err e = {0};
            int n = gk_radiosity_refined_vertices(s, l, &e);
            vec3 ext = v3_sub(s->bmax, s->bmin);
            rad_mesh m;
            assert_int_equal(rad_mesh_build(&m, s, v3_len(ext) / gk_radiosity_tess(l), 60000, &e), 0);
            long by_euler = euler_vertices(&m);
            printf(" tess %g: %d (Euler %ld)", (double)gk_radiosity_tess(l), n, by_euler);
            assert_int_equal(n, m.n_verts);
            assert_int_equal(by_euler, n);
            rad_mesh_free(&m);
        }
        printf("\n");
        gk_scene_free(s);
    }
}

static void test_segments(void **state)
{
    (void)state;
    assert_int_equal(rad_mesh_segments(1.0f, 2.0f), 1);
    assert_int_equal(rad_mesh_segments(1.0f, 0.5f), 2);
    assert_int_equal(rad_mesh_segments(1.0f, 0.3f), 4);
    assert_int_equal(rad_mesh_segments(1.0f, 0.0f), 1);
}

/* A hand-made mesh: one chart of n vertices on a line (the tree does not look at positions). */
static void line_mesh(rad_mesh *m, int n)
{
    memset(m, 0, sizeof *m);
    m->n_verts = n;
    m->pos = calloc((size_t)n, sizeof *m->pos);
    m->area = calloc((size_t)n, sizeof *m->area);
    m->centre = calloc((size_t)n, sizeof *m->centre);
    m->chart = calloc((size_t)n, sizeof *m->chart);
    m->n_charts = 1;
    m->charts = calloc(1, sizeof *m->charts);
    m->charts[0] = (rad_chart){.normal = v3(0, 1, 0), .tu = v3(1, 0, 0), .tv = v3(0, 0, 1), .first_vert = 0, .n_verts = n};
    for (int i = 0; i < n; i++)
        m->pos[i] = m->centre[i] = v3((float)i, 0, 0), m->area[i] = 1.0f;
}

static void test_full_tree(void **state)
{
    (void)state;
    rad_mesh m;
    line_mesh(&m, 16);
    rad_tree t;
    gk_err e = {0};
    assert_int_equal(rad_tree_build(&t, &m, &e), 0);
    assert_int_equal(t.n_nodes, 21);
    assert_int_equal(t.n_levels, 3);
    assert_int_equal(t.level_first[1], 16);
    assert_int_equal(t.level_first[2], 20);
    assert_int_equal(t.roots[0], 20);
    assert_int_equal(rad_tree_parent(&t, 0), 16);
    assert_int_equal(rad_tree_parent(&t, 7), 17);
    assert_int_equal(rad_tree_parent(&t, 15), 19);
    assert_int_equal(rad_tree_parent(&t, 19), 20);
    assert_int_equal(rad_tree_parent(&t, 20), -1);
    int first;
    assert_int_equal(rad_tree_children(&t, 18, &first), 4);
    assert_int_equal(first, 8);
    assert_int_equal(rad_tree_children(&t, 20, &first), 4);
    assert_int_equal(first, 16);
    assert_int_equal(rad_tree_children(&t, 3, &first), 0);
    assert_true(fabsf(t.area[20] - 16.0f) < 1e-6f);
    assert_true(fabsf(t.pos[17].x - 5.5f) < 1e-6f); /* average of leaves 4..7 */
    rad_tree_free(&t);
    rad_mesh_free(&m);
    /* a ragged chart: 5 leaves -> 2 -> 1 (8 nodes); the second level-1 node has one child */
    line_mesh(&m, 5);
    assert_int_equal(rad_tree_build(&t, &m, &e), 0);
    assert_int_equal(t.n_nodes, 8);
    assert_int_equal(rad_tree_children(&t, 6, &first), 1);
    assert_int_equal(first, 4);
    assert_int_equal(rad_tree_parent(&t, 4), 6);
    assert_int_equal(t.roots[0], 7);
    rad_tree_free(&t);
    rad_mesh_free(&m);
}

/* Every node of a real scene's hierarchy: its children name it as parent, levels fall by one,
 * areas sum, and each chart has one root holding the chart's area. */
static void test_tree_consistency(void **state)
{
    (void)state;
    const char *scenes[] = {"cornell", "furnace"};
    for (int si = 0; si < 2; si++) {
        gk_scene *s = load(scenes[si]);
        rad_mesh m;
        rad_tree t;
        gk_err e = {0};
        assert_int_equal(rad_mesh_build(&m, s, 0.1f * v3_len(v3_sub(s->bmax, s->bmin)) / 3.5f, 100000, &e), 0);
        assert_int_equal(rad_tree_build(&t, &m, &e), 0);
        int roots = 0, leaves_seen = 0;
        for (int i = 0; i < t.n_nodes; i++) {
            int first, k = rad_tree_children(&t, i, &first);
            if (k == 0) {
                assert_true(i < t.n_leaves);
                leaves_seen++;
            }
            float a = 0.0f;
            for (int c = first; c < first + k; c++) {
                assert_int_equal(rad_tree_parent(&t, c), i);
                assert_int_equal(t.node_level[c] + 1, t.node_level[i]);
                a += t.area[c];
            }
            if (k)
                assert_true(fabsf(a - t.area[i]) <= 1e-4f * t.area[i]);
            if (rad_tree_parent(&t, i) < 0) {
                roots++;
                assert_int_equal(t.roots[t.node_chart[i]], i);
            } else
                assert_true(rad_tree_parent(&t, i) > i); /* parents after children: one bottom-up sweep */
        }
        assert_int_equal(roots, m.n_charts);
        assert_int_equal(leaves_seen, m.n_verts);
        printf("# %s: %d leaves, %d nodes, %d levels, %d charts\n", scenes[si], t.n_leaves, t.n_nodes, t.n_levels,
               t.n_charts);
        rad_tree_free(&t);
        rad_mesh_free(&m);
        gk_scene_free(s);
    }
}

static void test_too_fine_is_input_error(void **state)
{
    (void)state;
    gk_scene *s = load("cornell");
    rad_mesh m;
    gk_err e = {0};
    assert_int_not_equal(rad_mesh_build(&m, s, 0.001f, 20000, &e), 0);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "cornell"));
    assert_non_null(strstr(e.msg, "20000"));
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_segments),
        cmocka_unit_test(test_area_conservation),
        cmocka_unit_test(test_furnace_counts),
        cmocka_unit_test(test_full_tree),
        cmocka_unit_test(test_tree_consistency),
        cmocka_unit_test(test_too_fine_is_input_error),
        cmocka_unit_test(test_refined_counts_by_euler),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
