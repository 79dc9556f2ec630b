/* The limitations of implicit visibility (research dong-001.md §2.6), each measured as a number
 * with a bound (the numbers below are this file's own output, gcc -O2, x86-64):
 *  - leakage through coarse tessellation (the seed's 792-vertex teapot leaks, ~2.5k-5k do not):
 *    light-leak's dark room, whose correct radiance is 0, against the lit room's, at ~800 and ~5k
 *    vertices (a refinement of the scene to those counts);
 *  - block artefacts at coarse bins: a floor under a small square emitter with a square occluder
 *    between them, the floor's irradiance against the exact integral (quadrature of the emitter
 *    with exact visibility against the occluder), over the shadow and penumbra, at 6x8², 6x12²,
 *    6x16², 6x24²;
 *  - "elements entirely visible or occluded" (the derivation's assumption 3) near contact shadows:
 *    the same occluder lowered to 2 cm above the floor: the error on the floor along its outline
 *    against the error there with the occluder high up;
 *  - world-fixed bins alias under rotation: cornell turned as a whole (every node animated) about
 *    the room's vertical axis in 0.5° steps to 10°; the correct irradiance of every surfel is
 *    invariant (the emission rides on the surfaces), the bins are not: the surfels' variation;
 *  - link count and memory against vertex count: the furnace at five refinements, least-squares
 *    fits of log(links) to p log N + c and to log(N log N) + c, with their residuals (the seed:
 *    "roughly O(N log N)"). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/rad_squares.h"
#include "gi/radiosity/rad_direct.h"
#include "gi/radiosity/rad_solve.h"

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

/* ---- leakage ------------------------------------------------------------------------------- */

/* The dark room's mean radiance over the lit room's (light-leak: rooms x < -0.01 lit, x > 0.01
   dark), direct light from the tracer's shadow rays (0 in the dark room), 4 bounces. */
static double leak_ratio(const gk_scene *s, const gk_ref_scene *rs, float edge, int *verts)
{
    rad_geometry g;
    gk_err e = {0};
    assert_int_equal(rad_geometry_build(&g, s, edge, 60000, 12, RAD_WEIGHT_SPILL, &e), 0);
    int nl = g.tree.n_leaves, nn = g.tree.n_nodes;
    float *ed = malloc(sizeof *ed * 3 * (size_t)nl), *b0 = malloc(sizeof *b0 * 3 * (size_t)nn);
    float *ind = malloc(sizeof *ind * 3 * (size_t)nl);
    rad_direct_irradiance(rs, &g.tree, 16, 0, nl, ed);
    rad_initial_radiance(&g, ed, b0);
    assert_int_equal(rad_solve_cpu(&g, b0, 4, ind), 0);
    double lit = 0, lit_a = 0, dark = 0, dark_a = 0;
    for (int i = 0; i < nl; i++) {
        double L = 0;
        for (int c = 0; c < 3; c++)
            L += b0[3 * i + c] + g.albedo[3 * i + c] / M_PI * ind[3 * i + c];
        double a = g.tree.area[i];
        if (g.tree.pos[i].x < -0.01f)
            lit += L * a, lit_a += a;
        else if (g.tree.pos[i].x > 0.01f)
            dark += L * a, dark_a += a;
    }
    *verts = nl;
    free(ed), free(b0), free(ind);
    rad_geometry_free(&g);
    return (dark / dark_a) / (lit / lit_a);
}

static void test_leak_coarse_vs_fine(void **state)
{
    (void)state;
    gk_scene *s = load("light-leak");
    gk_ref_scene rs;
    gk_err e = {0};
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 0), 1, 1, &e), 0);
    /* edges that refine the scene to about the seed's 792 and 5k vertices */
    const float edges[] = {0.95f, 0.32f};
    int verts[2];
    double ratio[2];
    for (int k = 0; k < 2; k++) {
        ratio[k] = leak_ratio(s, &rs, edges[k], &verts[k]);
        printf("# light-leak at %d vertices (edge %.2f m): dark room / lit room mean radiance %.4f\n", verts[k],
               (double)edges[k], ratio[k]);
    }
    assert_true(verts[0] > 600 && verts[0] < 1000);
    assert_true(verts[1] > 4000 && verts[1] < 6500);
    /* measured 0.079 at 760 vertices, 0.037 at 5,040: the coarse mesh leaks 2.1x as much (its
       surfels are ~1 m apart, 50x the wall's thickness, so the bins of a surfel near the wall see
       the other room's wall elements through it). Bounds: coarse > 1.5x fine, and a leak at both
       (ratio above 1%: the correct value is 0, the tracer's direct light puts none there) */
    assert_true(ratio[0] > 1.5 * ratio[1]);
    assert_true(ratio[1] > 0.01);
    gk_ref_scene_free(&rs);
    gk_scene_free(s);
}

/* ---- block artefacts and contact shadows -------------------------------------------------- */

#define FLOOR_SIDE 1.0f
#define FLOOR_G 32
#define EMITTER_SIDE 0.25f
#define EMITTER_H 0.5f
#define OCCLUDER_SIDE 0.2f

/* Exact irradiance at floor point (x, 0, z) from the unit-radiance emitter (centred, facing down)
   with the occluder (centred, at height ho) in between: E = ∫ h² / r⁴ V dA, Q x Q midpoints. */
static double exact_irradiance(float x, float z, float ho)
{
    const int Q = 96;
    double sum = 0.0, cell = EMITTER_SIDE / Q, h = EMITTER_H;
    for (int i = 0; i < Q; i++)
        for (int j = 0; j < Q; j++) {
            double px = -0.5 * EMITTER_SIDE + (i + 0.5) * cell, pz = -0.5 * EMITTER_SIDE + (j + 0.5) * cell;
            double t = ho / h, qx = x + t * (px - x), qz = z + t * (pz - z);
            if (fabs(qx) < 0.5 * OCCLUDER_SIDE && fabs(qz) < 0.5 * OCCLUDER_SIDE)
                continue;
            double dx = px - x, dz = pz - z, r2 = dx * dx + dz * dz + h * h;
            sum += h * h / (r2 * r2) * cell * cell;
        }
    return sum;
}

typedef struct shadow_errors {
    double penumbra_rmse;   /* over floor surfels where the exact E is 2%..98% of the unoccluded */
    double outline_rmse;    /* over floor surfels within 2 surfel spacings outside the occluder's outline */
    double mean_exact;      /* normaliser: the unoccluded E below the emitter's centre */
} shadow_errors;

static shadow_errors shadow_case(int n_face, float ho)
{
    square sq[3] = {
        {.centre = v3(0, 0, 0), .normal = v3(0, 1, 0), .tu = v3(1, 0, 0), .side = FLOOR_SIDE, .g = FLOOR_G},
        {.centre = v3(0, EMITTER_H, 0), .normal = v3(0, -1, 0), .tu = v3(1, 0, 0), .side = EMITTER_SIDE, .g = 8},
        {.centre = v3(0, ho, 0), .normal = v3(0, -1, 0), .tu = v3(1, 0, 0), .side = OCCLUDER_SIDE, .g = 8},
    };
    rad_mesh m;
    squares_mesh(&m, sq, 3);
    rad_tree t;
    rad_links L;
    gk_err e = {0};
    assert_int_equal(rad_tree_build(&t, &m, &e), 0);
    assert_int_equal(rad_links_build(&L, &t, n_face, RAD_WEIGHT_SPILL, &e), 0);
    double open = exact_irradiance(0.0f, 0.0f, -1.0f); /* ho < 0: no occluder on the way */
    double pen = 0, pen_n = 0, out = 0, out_n = 0, spacing = FLOOR_SIDE / FLOOR_G;
    for (int i = 0; i < FLOOR_G * FLOOR_G; i++) {
        double E = 0.0;
        for (uint32_t k = L.offset[i]; k < L.offset[i + 1]; k++)
            if (t.node_chart[L.target[k]] == 1)
                E += L.weight[k];
        vec3 p = t.pos[i];
        double ex = exact_irradiance(p.x, p.z, ho), open_here = exact_irradiance(p.x, p.z, -1.0f);
        double d = (E - ex) / open;
        if (ex > 0.02 * open_here && ex < 0.98 * open_here)
            pen += d * d, pen_n++;
        double outside = fmax(fabs(p.x), fabs(p.z)) - 0.5 * OCCLUDER_SIDE;
        if (outside > 0.0 && outside < 2.0 * spacing)
            out += d * d, out_n++;
    }
    rad_links_free(&L);
    rad_tree_free(&t);
    rad_mesh_free(&m);
    return (shadow_errors){.penumbra_rmse = sqrt(pen / fmax(pen_n, 1)), .outline_rmse = sqrt(out / fmax(out_n, 1)),
                           .mean_exact = open};
}

static void test_block_artefacts_at_coarse_bins(void **state)
{
    (void)state;
    const int res[] = {8, 12, 16, 24};
    double err[4];
    for (int r = 0; r < 4; r++) {
        shadow_errors se = shadow_case(res[r], 0.25f);
        err[r] = se.penumbra_rmse;
        printf("# shadow of a 0.2 m square at 0.25 m under a 0.25 m emitter at 0.5 m, 6x%d²: penumbra RMSE %.4f of the unoccluded E\n",
               res[r], err[r]);
    }
    /* measured 0.499 / 0.199 / 0.162 / 0.186 at 6x8² / 12² / 16² / 24²: at 6x8² a bin is wider
       than the emitter's leaves and the occluder's outline falls in whole bins (the blocks); finer
       bins more than halve it, and past 6x16² the leaves (1/8 of the emitter) are coarser than the
       bins, so 24² gains nothing (the error is the elements' then). Bounds: 6x8² over twice each
       finer one, and every one under 0.6 */
    for (int r = 1; r < 4; r++)
        assert_true(err[0] > 2.0 * err[r]);
    for (int r = 0; r < 4; r++)
        assert_true(err[r] < 0.6);
}

static void test_contact_shadow_error(void **state)
{
    (void)state;
    shadow_errors high = shadow_case(12, 0.25f), contact = shadow_case(12, 0.02f);
    printf("# 6x12²: floor error along the occluder's outline: occluder at 0.25 m %.4f, at 0.02 m (contact) %.4f\n",
           high.outline_rmse, contact.outline_rmse);
    /* measured 0.205 high, 0.344 at contact (1.68x): the floor surfels beside a contact see the
       occluder's near elements at grazing angles, each taking whole bins of the emitter that it
       covers only in part (assumption 3). Bound: contact above 1.3x high */
    assert_true(contact.outline_rmse > 1.3 * high.outline_rmse);
}

/* ---- world-fixed bins under rotation ------------------------------------------------------- */

/* area-weighted mean over the surfels of (max - min) / mean of the irradiance over the rotation */
static double rotation_variation(int n_face, int *surfels, double *worst_out)
{
    gk_scene *s = load("cornell");
    for (int i = 0; i < s->n_nodes; i++)
        s->nodes[i].animated = true; /* the whole room turns */
    rad_geometry g;
    gk_err e = {0};
    assert_int_equal(rad_geometry_build(&g, s, 0.1f, 60000, n_face, RAD_WEIGHT_SPILL, &e), 0);
    int nl = g.tree.n_leaves, nn = g.tree.n_nodes;
    /* B0 per chart, fixed to the surfaces: 1 nit, the short block's and the back wall's charts 4 */
    float *b0 = malloc(sizeof *b0 * 3 * (size_t)nn), *ind = malloc(sizeof *ind * 3 * (size_t)nl);
    for (int i = 0; i < nl; i++)
        for (int c = 0; c < 3; c++)
            b0[3 * i + c] = g.mesh.chart[i] % 3 == 0 ? 4.0f : 1.0f;
    rad_pullup(&g.tree, b0);
    enum { STEPS = 21 };
    double *lo = malloc(sizeof *lo * (size_t)nl), *hi = malloc(sizeof *hi * (size_t)nl), *sum = calloc((size_t)nl, sizeof *sum);
    mat4 *w = malloc(sizeof *w * (size_t)s->n_nodes);
    vec3 c = v3(0.278f, 0.0f, 0.2796f);
    for (int k = 0; k < STEPS; k++) {
        float h = 0.5f * (0.5f * (float)k) * (float)M_PI / 180.0f;
        mat4 to = m4_trs(v3_scale(c, -1.0f), (quat){0, 0, 0, 1}, v3(1, 1, 1)), back = m4_trs(c, (quat){0, 0, 0, 1}, v3(1, 1, 1));
        mat4 R = m4_mul(back, m4_mul(m4_trs(v3(0, 0, 0), (quat){0, sinf(h), 0, cosf(h)}, v3(1, 1, 1)), to));
        for (int i = 0; i < s->n_nodes; i++)
            w[i] = m4_mul(R, s->nodes[i].world);
        rad_geometry_refit(&g, w, s->n_nodes);
        assert_int_equal(rad_geometry_relink(&g, NULL, &e), 0);
        assert_int_equal(rad_solve_cpu(&g, b0, 1, ind), 0);
        for (int i = 0; i < nl; i++) {
            double E = ind[3 * i];
            lo[i] = k ? fmin(lo[i], E) : E, hi[i] = k ? fmax(hi[i], E) : E, sum[i] += E / STEPS;
        }
    }
    double var = 0, area = 0, worst = 0;
    for (int i = 0; i < nl; i++) {
        double r = sum[i] > 0 ? (hi[i] - lo[i]) / sum[i] : 0;
        var += r * g.tree.area[i], area += g.tree.area[i];
        worst = fmax(worst, r);
    }
    var /= area;
    *surfels = nl, *worst_out = worst;
    free(b0), free(ind), free(lo), free(hi), free(sum), free(w);
    rad_geometry_free(&g);
    gk_scene_free(s);
    return var;
}

static void test_bin_aliasing_under_rotation(void **state)
{
    (void)state;
    const int res[] = {8, 16};
    double v[2];
    for (int r = 0; r < 2; r++) {
        int nl;
        double worst;
        v[r] = rotation_variation(res[r], &nl, &worst);
        printf("# cornell (%d surfels, 6x%d²) turned 0..10° in 0.5° steps: per-surfel irradiance range / mean, area-weighted mean %.4f, worst %.4f (correct: 0)\n",
               nl, res[r], v[r], worst);
    }
    /* measured 0.103 (worst surfel 0.313) at 6x8², 0.059 (0.219) at 6x16²: the bins stay with the
       world while the room turns, so links jump between elements as directions cross bin borders.
       Bounds: the aliasing is there at both (above 2%), and finer bins alias less */
    assert_true(v[0] > 0.02 && v[1] > 0.02);
    assert_true(v[1] < v[0]);
}

/* ---- link count and memory against vertex count ------------------------------------------ */

/* least squares y = a x + b; returns a, *b, *rms the residual's root mean square */
static double fit_line(const double *x, const double *y, int n, double *b, double *rms)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < n; i++)
        sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
    double a = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    *b = (sy - a * sx) / n;
    double r = 0;
    for (int i = 0; i < n; i++)
        r += (y[i] - a * x[i] - *b) * (y[i] - a * x[i] - *b);
    *rms = sqrt(r / n);
    return a;
}

static void test_links_and_memory_vs_vertices(void **state)
{
    (void)state;
    gk_scene *s = load("furnace");
    /* n = ceil(0.707 / edge) segments a cell's diagonal: 6 (4n + 1)² vertices, n = 2, 3, 4, 5, 6, 8 */
    const float edges[] = {0.5f, 0.3f, 0.2f, 0.16f, 0.125f, 0.09f};
    enum { K = 6 };
    double lx[K], ly[K], lm[K], lnlogn[K];
    for (int k = 0; k < K; k++) {
        rad_mesh m;
        rad_tree t;
        rad_links L;
        gk_err e = {0};
        assert_int_equal(rad_mesh_build(&m, s, edges[k], 100000, &e), 0);
        assert_int_equal(rad_tree_build(&t, &m, &e), 0);
        assert_int_equal(rad_links_build(&L, &t, 12, RAD_WEIGHT_SPILL, &e), 0);
        double n = m.n_verts, mem = (double)L.bin_bytes + 8.0 * (double)L.leaf_links;
        printf("# furnace %d vertices, 6x12²: %ld links created, %ld leaf links, memory %.1f MB (bins %.1f MB)\n",
               m.n_verts, L.created, L.leaf_links, mem / 1e6, (double)L.bin_bytes / 1e6);
        lx[k] = log(n), ly[k] = log((double)L.created), lm[k] = log(mem), lnlogn[k] = log(n * log(n));
        rad_links_free(&L);
        rad_tree_free(&t);
        rad_mesh_free(&m);
    }
    double c, rms_p, rms_nlogn, rms_mem, c2;
    double p = fit_line(lx, ly, K, &c, &rms_p);
    /* N log N with a free constant: the slope against log(N log N) fixed at 1 */
    double mean = 0;
    for (int k = 0; k < K; k++)
        mean += ly[k] - lnlogn[k];
    mean /= K;
    rms_nlogn = 0;
    for (int k = 0; k < K; k++)
        rms_nlogn += (ly[k] - lnlogn[k] - mean) * (ly[k] - lnlogn[k] - mean);
    rms_nlogn = sqrt(rms_nlogn / K);
    double pm = fit_line(lx, lm, K, &c2, &rms_mem);
    printf("# links created ~ N^%.3f (residual %.4f in log); as c N log N: residual %.4f; memory ~ N^%.3f (residual %.4f)\n",
           p, rms_p, rms_nlogn, pm, rms_mem);
    /* measured: links ~ N^1.13 (residual 0.119), c N log N residual 0.112 (N log N's own log-log
       slope over 486..6,534 vertices is 1.13), memory ~ N^1.03 (the bins, n_nodes x 6N² x 8 bytes,
       dominate: linear; leaf lists 14-24% of it). Bounds: the exponent in 1.0..1.3 (above linear,
       not quadratic as all-pairs links would be), the N log N fit's residual under 0.15, memory's
       exponent in 0.95..1.1 */
    assert_true(p > 1.0 && p < 1.3);
    assert_true(rms_nlogn < 0.15);
    assert_true(pm > 0.95 && pm < 1.1);
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_leak_coarse_vs_fine),
        cmocka_unit_test(test_block_artefacts_at_coarse_bins),
        cmocka_unit_test(test_contact_shadow_error),
        cmocka_unit_test(test_bin_aliasing_under_rotation),
        cmocka_unit_test(test_links_and_memory_vs_vertices),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
