/* Unit tests of the vpl method's pure C part (app/gi/vpl/vpl_cluster.c): Halton, the k-means
 * distance, nested seeds, determinism, the VAL area, and the clustering failure modes F9 (cluster
 * loss with warm start), F10 (popping), F12 (mixed-normal clusters) of dong-001.md §10 on VPLs
 * generated analytically: a spot light inside the unit Cornell box [0,1]³ (scene T5 of §9.2,
 * walls only), rays at Halton directions in the cone, one VPL where each ray leaves the box. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "gi/vpl/vpl_cluster.h"

#define PI_F 3.14159265f
#define DIAM 1.7320508f /* unit box diagonal */

static vec3 any_perp(vec3 d)
{
    vec3 a = fabsf(d.x) < 0.9f ? v3(1, 0, 0) : v3(0, 1, 0);
    return v3_norm(v3_cross(a, d));
}

/* n VPLs from a spot at pos aimed at target (cone half-angle 30°); rot shifts the Halton pattern
   (Cranley–Patterson rotation: a different random pattern per frame when it changes). */
static void cornell_vpls_rot(gk_vpl *out, int n, vec3 pos, vec3 target, float rot_a, float rot_b)
{
    vec3 d = v3_norm(v3_sub(target, pos)), u = any_perp(d), w = v3_cross(d, u);
    float cos_outer = cosf(30.0f * PI_F / 180.0f);
    for (int i = 0; i < n; i++) {
        float a = fmodf(gk_halton((uint32_t)i + 1, 2) + rot_a, 1.0f);
        float b = fmodf(gk_halton((uint32_t)i + 1, 3) + rot_b, 1.0f);
        float ct = 1.0f - a * (1.0f - cos_outer), st = sqrtf(1.0f - ct * ct), ph = 2.0f * PI_F * b;
        vec3 r = v3_add(v3_scale(d, ct), v3_add(v3_scale(u, st * cosf(ph)), v3_scale(w, st * sinf(ph))));
        float t = INFINITY;
        vec3 nrm = v3(0, 0, 0);
        float rc[3] = {r.x, r.y, r.z}, pc[3] = {pos.x, pos.y, pos.z};
        for (int k = 0; k < 3; k++) {
            if (fabsf(rc[k]) < 1e-9f)
                continue;
            float wall = rc[k] > 0 ? 1.0f : 0.0f;
            float tk = (wall - pc[k]) / rc[k];
            if (tk > 0 && tk < t) {
                t = tk;
                float nn[3] = {0, 0, 0};
                nn[k] = rc[k] > 0 ? -1.0f : 1.0f;
                nrm = v3(nn[0], nn[1], nn[2]);
            }
        }
        out[i].pos = v3_add(pos, v3_scale(r, t));
        out[i].nrm = nrm;
        out[i].flux = v3(0.01f, 0.01f, 0.01f);
        out[i].area = 0.001f;
    }
}

static void cornell_vpls(gk_vpl *out, int n, vec3 pos, vec3 target)
{
    cornell_vpls_rot(out, n, pos, target, 0.0f, 0.0f);
}

static gk_kmeans_opts thesis_opts(void)
{
    gk_kmeans_opts o = {0.7f, 0.3f, DIAM, 16, false};
    return o;
}

static void test_halton_values(void **state)
{
    (void)state;
    assert_float_equal(gk_halton(1, 2), 0.5f, 1e-7);
    assert_float_equal(gk_halton(2, 2), 0.25f, 1e-7);
    assert_float_equal(gk_halton(3, 2), 0.75f, 1e-7);
    assert_float_equal(gk_halton(1, 3), 1.0f / 3.0f, 1e-7);
    assert_float_equal(gk_halton(3, 3), 1.0f / 9.0f, 1e-7);
    assert_float_equal(gk_halton(5, 3), 7.0f / 9.0f, 1e-6);
    /* Stratification: 256 points (2,3) over an 8×8 grid. Measured 3..5 per cell (mean 4); 20
       seeded uniform random patterns gave max 8–12 and min 0–1, so [2, 6] separates the two. */
    int cells[64] = {0};
    for (uint32_t i = 1; i <= 256; i++)
        cells[(int)(gk_halton(i, 2) * 8) + 8 * (int)(gk_halton(i, 3) * 8)]++;
    int mx = 0, mn = 999;
    for (int c = 0; c < 64; c++)
        mx = cells[c] > mx ? cells[c] : mx, mn = cells[c] < mn ? cells[c] : mn;
    assert_true(mx <= 6);
    assert_true(mn >= 2);
}

static void test_distance_metric(void **state)
{
    (void)state;
    gk_kmeans_opts o = thesis_opts();
    vec3 n = v3(0, 1, 0);
    assert_float_equal(gk_vpl_distance(&o, v3(0.2f, 0, 0.3f), n, v3(0.2f, 0, 0.3f), n), 0.0f, 1e-6);
    /* Δx term: 0.7 · |Δp| / diameter */
    assert_float_equal(gk_vpl_distance(&o, v3(0, 0, 0), n, v3(0.5f, 0, 0), n), 0.7f * 0.5f / DIAM, 1e-6);
    /* Δθ term: 0.3 · angle in radians; perpendicular normals = 0.3·π/2 */
    assert_float_equal(gk_vpl_distance(&o, v3(0, 0, 0), n, v3(0, 0, 0), v3(1, 0, 0)), 0.3f * PI_F / 2, 1e-5);
    /* opposite normals: the full π (acos clamped, no NaN) */
    assert_float_equal(gk_vpl_distance(&o, v3(0, 0, 0), n, v3(0, 0, 0), v3(0, -1, 0)), 0.3f * PI_F, 1e-4);
}

static void test_nested_seeds(void **state)
{
    (void)state;
    static gk_vpl v[256];
    cornell_vpls(v, 256, v3(0.5f, 0.95f, 0.9f), v3(0, 0, 0));
    int s4[4], s8[8], s32[32];
    assert_int_equal(gk_vpl_nested_seeds(v, 256, 4, s4), 4);
    assert_int_equal(gk_vpl_nested_seeds(v, 256, 8, s8), 8);
    assert_int_equal(gk_vpl_nested_seeds(v, 256, 32, s32), 32);
    for (int k = 0; k < 4; k++)
        assert_int_equal(s4[k], s8[k]);   /* prefix: M = 4 seeds are the first of M = 8 */
    for (int k = 0; k < 8; k++)
        assert_int_equal(s8[k], s32[k]);
    /* The thesis's set {k·N/M} for power-of-two M. */
    for (int k = 0; k < 8; k++) {
        bool found = false;
        for (int j = 0; j < 8; j++)
            found |= s8[j] == k * 256 / 8;
        assert_true(found);
    }
    /* Invalid (unlit) VPLs are skipped, keeping the order. */
    v[0].flux = v3(0, 0, 0);
    assert_int_equal(gk_vpl_nested_seeds(v, 256, 4, s4), 4);
    assert_int_equal(s4[0], 128);
}

static void test_kmeans_deterministic(void **state)
{
    (void)state;
    static gk_vpl v[512];
    static int la[512], lb[512];
    gk_val va[16], vb[16];
    cornell_vpls(v, 512, v3(0.5f, 0.95f, 0.9f), v3(0, 0, 0));
    gk_kmeans_opts o = thesis_opts();
    gk_kmeans_result ra = gk_vpl_kmeans(v, 512, 16, &o, la, va);
    gk_vpl_kmeans(v, 512, 16, &o, lb, vb);
    assert_int_equal(ra.m, 16);
    assert_memory_equal(la, lb, sizeof la);
    assert_memory_equal(&va[0].centre, &vb[0].centre, sizeof(vec3));
    assert_true(ra.iters >= 2 && ra.iters <= 16);
    /* Members sum to the valid VPLs; the error falls with M (more clusters never fit worse here). */
    int total = 0;
    for (int k = 0; k < ra.m; k++)
        total += va[k].count;
    assert_int_equal(total, 512);
    gk_kmeans_result r4 = gk_vpl_kmeans(v, 512, 4, &o, la, va);
    assert_true(ra.error < r4.error);
}

static void test_val_area(void **state)
{
    (void)state;
    /* A 5×3 grid of VPLs on the floor spanning 0.4 × 0.2 m: the bounding rectangle on the plane
       perpendicular to the mean normal is exactly that, whatever tangent frame is chosen
       (it is axis-aligned here because the frame of (0,1,0) is x/z). */
    gk_vpl v[15];
    int labels[15];
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 5; i++) {
            gk_vpl *p = &v[j * 5 + i];
            p->pos = v3(0.3f + 0.1f * i, 0, 0.5f + 0.1f * j);
            p->nrm = v3(0, 1, 0);
            p->flux = v3(1, 1, 1);
            labels[j * 5 + i] = 0;
        }
    gk_val val = {0};
    val.centre = v3(0.5f, 0, 0.6f);
    val.normal = v3(0, 1, 0);
    gk_val_frame_area(v, 15, labels, 0, &val);
    assert_int_equal(val.count, 15);
    assert_float_equal(val.area, 0.08f, 1e-5);
    assert_float_equal(val.size, 0.4f, 1e-5);
    assert_float_equal(val.flux.x, 15.0f, 1e-5);
    assert_float_equal(v3_dot(val.t, val.normal), 0.0f, 1e-6);
}

/* F9: the spot sweeps from the left wall (0, .5, .5) to the ceiling (.5, 1, .5) over 60 frames. */
static void sweep_nonempty(bool warm, int *min_nonempty, int *last_nonempty)
{
    static gk_vpl v[256];
    static int labels[256];
    gk_val vals[8];
    gk_kmeans_opts o = thesis_opts();
    *min_nonempty = 99;
    for (int f = 0; f <= 60; f++) {
        float t = (float)f / 60.0f;
        cornell_vpls(v, 256, v3(0.5f, 0.6f, 0.5f), v3_lerp(v3(0, 0.5f, 0.5f), v3(0.5f, 1, 0.5f), t));
        o.warm_start = warm && f > 0;
        gk_kmeans_result r = gk_vpl_kmeans(v, 256, 8, &o, labels, vals);
        int ne = r.m - r.empty;
        *min_nonempty = ne < *min_nonempty ? ne : *min_nonempty;
        *last_nonempty = ne;
    }
}

static void test_f9_cluster_loss(void **state)
{
    (void)state;
    int mn_restart, last_restart, mn_warm, last_warm;
    sweep_nonempty(false, &mn_restart, &last_restart);
    sweep_nonempty(true, &mn_warm, &last_warm);
    print_message("# F9: non-empty of 8: restart min %d end %d; warm start min %d end %d\n", mn_restart,
                  last_restart, mn_warm, last_warm);
    /* Measured: restart min 6 (two clusters briefly empty mid-sweep, when the spot straddles the
       wall/ceiling edge), 8 at the end; warm start (thesis Fig. 6.7) ends with 1 of 8. The bounds:
       restart never below 6 and all 8 at the end; warm start at most 2 at the end, so the oracle
       still shows the loss if someone "optimises" to warm start. */
    assert_true(mn_restart >= 6);
    assert_int_equal(last_restart, 8);
    assert_true(last_warm <= 2);
}

/* F10: a smooth light path; per frame, the largest centroid move (relative to the scene diameter)
   of the cluster matched by index, and the fraction of VPLs whose label changes. */
static void popping(bool random_pattern, float *worst_jump_out, float *worst_change_out)
{
    static gk_vpl v[256];
    static int labels[256], prev[256];
    gk_val vals[8], pv[8];
    gk_kmeans_opts o = thesis_opts();
    float worst_jump = 0.0f, worst_change = 0.0f;
    for (int f = 0; f <= 40; f++) {
        /* 0.25° of spot rotation per frame around the corner aim point */
        float a = (float)f * 0.25f * PI_F / 180.0f;
        vec3 target = v3(0.1f + 0.3f * sinf(a), 0.1f, 0.1f + 0.3f * (1.0f - cosf(a)));
        float ra = random_pattern ? gk_halton((uint32_t)f + 1, 5) : 0.0f;
        float rb = random_pattern ? gk_halton((uint32_t)f + 1, 7) : 0.0f;
        cornell_vpls_rot(v, 256, v3(0.5f, 0.95f, 0.9f), target, ra, rb);
        gk_kmeans_result r = gk_vpl_kmeans(v, 256, 8, &o, labels, vals);
        if (f > 0) {
            int changed = 0;
            for (int i = 0; i < 256; i++)
                changed += labels[i] != prev[i];
            float ch = (float)changed / 256.0f;
            worst_change = ch > worst_change ? ch : worst_change;
            for (int k = 0; k < r.m; k++) {
                float j = v3_len(v3_sub(vals[k].centre, pv[k].centre)) / DIAM;
                worst_jump = j > worst_jump ? j : worst_jump;
            }
        }
        memcpy(prev, labels, sizeof prev);
        memcpy(pv, vals, sizeof pv);
    }
    *worst_jump_out = worst_jump;
    *worst_change_out = worst_change;
}

static void test_f10_popping(void **state)
{
    (void)state;
    float jump, change, rjump, rchange;
    popping(false, &jump, &change);
    popping(true, &rjump, &rchange);
    print_message("# F10: worst centroid jump / diameter %.4f (random pattern %.4f), worst label change %.3f "
                  "(random %.3f)\n", jump, rjump, change, rchange);
    /* Measured with fixed Halton: jump 0.052 of the diameter, label change 0.059; with a random
       pattern per frame: 0.378 and 0.730. Bounds = the fixed-Halton values with ~1.5x margin; the
       random pattern is the sensitivity check (it must relabel over twice as many VPLs). */
    assert_true(jump < 0.08f);
    assert_true(change < 0.09f);
    assert_true(rchange > 2.0f * change);
}

/* F12 (clustering half): at a corner, w_n = 0 makes clusters that straddle two walls. */
static int mixed_clusters(float w_nrm)
{
    static gk_vpl v[512];
    static int labels[512];
    gk_val vals[16];
    cornell_vpls(v, 512, v3(0.5f, 0.95f, 0.9f), v3(0, 0, 0));
    gk_kmeans_opts o = thesis_opts();
    o.w_nrm = w_nrm;
    gk_kmeans_result r = gk_vpl_kmeans(v, 512, 16, &o, labels, vals);
    int mixed = 0;
    for (int k = 0; k < r.m; k++) {
        bool bad = false;
        for (int i = 0; i < 512; i++)
            if (labels[i] == k && v3_dot(v[i].nrm, vals[k].normal) < 0.7f)
                bad = true;
        mixed += bad;
    }
    return mixed;
}

static void test_f12_mixed_normals(void **state)
{
    (void)state;
    int with = mixed_clusters(0.3f), without = mixed_clusters(0.0f);
    print_message("# F12: clusters with a member > 45 deg off the mean normal: w_n=0.3: %d, w_n=0: %d\n", with,
                  without);
    /* Measured 0 vs 6 of 16: the normal term is what keeps clusters planar. */
    assert_int_equal(with, 0);
    assert_true(without >= 2);
}

static void test_adaptive_m(void **state)
{
    (void)state;
    static gk_vpl v[512];
    static int labels[512];
    gk_val vals[GK_VPL_MAX_M];
    gk_kmeans_opts o = thesis_opts();
    cornell_vpls(v, 512, v3(0.5f, 0.95f, 0.9f), v3(0, 0, 0));
    gk_kmeans_result corner = gk_vpl_kmeans_adaptive(v, 512, 2, 32, 0.35f, 0, &o, labels, vals);
    /* One flat patch: VPLs of a spot straight down onto the floor. */
    cornell_vpls(v, 512, v3(0.5f, 0.95f, 0.5f), v3(0.5f, 0, 0.5f));
    gk_kmeans_result flat = gk_vpl_kmeans_adaptive(v, 512, 2, 32, 0.35f, 0, &o, labels, vals);
    print_message("# adaptive M: corner (3 walls) %d, flat floor patch %d\n", corner.m, flat.m);
    /* Threshold 0.35: in-plane subdivision alone cuts the mean distance by 1 − 1/√2 ≈ 0.29 per
       doubling (measured 0.29–0.31 here), separating walls cuts it by 0.66 (corner, 2 -> 4).
       Measured: corner 4, flat patch 2. The corner needs more clusters than a single plane. */
    assert_true(corner.m > flat.m || corner.m == 32);
    assert_true(flat.m >= 2 && corner.m <= 32);
    /* Hysteresis: asking again with the chosen M as the previous one keeps it. */
    gk_kmeans_result again = gk_vpl_kmeans_adaptive(v, 512, 2, 32, 0.35f, flat.m, &o, labels, vals);
    assert_int_equal(again.m, flat.m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_halton_values),       cmocka_unit_test(test_distance_metric),
        cmocka_unit_test(test_nested_seeds),        cmocka_unit_test(test_kmeans_deterministic),
        cmocka_unit_test(test_val_area),            cmocka_unit_test(test_f9_cluster_loss),
        cmocka_unit_test(test_f10_popping),         cmocka_unit_test(test_f12_mixed_normals),
        cmocka_unit_test(test_adaptive_m),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
