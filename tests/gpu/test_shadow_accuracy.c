/* Soft shadows of every method against the exact visibility of the analytic scenes T1
 * "plane-over-plane" and T2 "stacked blockers" (dong-001.md §9.2), and the failure tests F1 (VSM
 * light bleeding: VSSM vs the no-subdivision SAVSM mode) and F4 (umbra underestimation) of §10.
 * Scenes: receiver y = 0, light square of side S at y = 4 facing down, blocker 2x2 at y = 1
 * centred at the origin (T2: plus 2x2 at y = 2 offset by (1, 0, 0.5)); camera (0, 6, 6) looking
 * at the origin, 60 degree FOV; 128x128 pixels, shadow map 512. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gpu/test_shadow_util.h"

SX_SESSION_GROUP(128)



static sx_setup t1(float S)
{
    sx_setup st = {.S = S, .light = v3(0, SX_LIGHT_Y, 0), .n_rects = 1, .eye = v3(0, 6, 6), .target = v3(0, 0, 0),
                   .yfov = 1.0471976f};
    st.rect[0] = (sx_rect){-1, 1, -1, 1, 1};
    return st;
}

static sx_setup t2(float S)
{
    sx_setup st = t1(S);
    st.n_rects = 2;
    st.rect[1] = (sx_rect){0, 2, -0.5f, 1.5f, 2};
    return st;
}

/* Renders every method in `methods` for one set-up; stats[i] per method. */
static void measure(const sx_setup *st, const char *what, const char *const *methods, int n, sx_stats *stats,
                    double *umbra_ratio)
{
    fx_scene with, without;
    sx_build(&with, st, true);
    sx_build(&without, st, false);
    sx_truth t;
    sx_truth_build(&t, &with, st, W, H);
    float *a = malloc(sizeof(float) * W * H), *b = malloc(sizeof(float) * W * H), *v = malloc(sizeof(float) * W * H);
    gk_err e = {0};
    if (gk_renderer_set_scene(ses.r, &without.s, &e) != 0 || sx_draw(&ses, "shadow=hard,shadow_map=512", b) != 0)
        fail_msg("render without blockers: %s", e.msg);
    if (gk_renderer_set_scene(ses.r, &with.s, &e) != 0)
        fail_msg("set_scene: %s", e.msg);
    for (int m = 0; m < n; m++) {
        char pins[96];
        snprintf(pins, sizeof pins, "shadow=%s,shadow_map=512", methods[m]);
        if (sx_draw(&ses, pins, a) != 0)
            fail_msg("render %s", methods[m]);
        sx_ratio(a, b, &t, v);
        stats[m] = sx_compare(v, &t);
        sx_print(what, methods[m], &stats[m]);
        if (umbra_ratio) { /* F4: pixels the method calls umbra (V < 0.02) over the exact umbra */
            int got = 0, want = 0;
            for (int i = 0; i < W * H; i++)
                if (t.valid[i] && !isnan(v[i])) {
                    got += v[i] < 0.02f;
                    want += t.v[i] < 0.02f;
                }
            umbra_ratio[m] = want ? (double)got / want : 0;
            printf("#   F4 %s %s: umbra area ratio %.3f (%d / %d pixels)\n", what, methods[m], umbra_ratio[m], got, want);
        }
    }
    gk_renderer_set_scene(ses.r, NULL, &e);
    free(a);
    free(b);
    free(v);
    sx_truth_free(&t);
    gkt_scene_free(&with);
    gkt_scene_free(&without);
}

/* The truth is received light: the closed form (sx_exact_v) against brute-force numeric
 * integration of cos_r cos_l / r^2 over the light (N x N midpoint samples, each tested against the
 * occluder squares) at points across T1's and T2's penumbrae; and it differs from the visible
 * area fraction the tests compared with before #11, so the change is visible. CPU only. */
static double numeric_v(const sx_setup *st, vec3 p, int n)
{
    double S = st->S, hy = st->light.y - p.y, lit = 0, all = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double lx = st->light.x - S / 2 + S * (i + 0.5) / n, lz = st->light.z - S / 2 + S * (j + 0.5) / n;
            double dx = lx - p.x, dz = lz - p.z, r2 = dx * dx + hy * hy + dz * dz;
            double w = hy * hy / (r2 * r2); /* cos_r cos_l / r^2 = (hy / r)^2 / r^2 */
            bool blocked = false;
            for (int k = 0; k < st->n_rects && !blocked; k++) {
                double t = (st->rect[k].y - p.y) / hy, x = p.x + t * dx, z = p.z + t * dz;
                blocked = x >= st->rect[k].x0 && x <= st->rect[k].x1 && z >= st->rect[k].z0 && z <= st->rect[k].z1;
            }
            all += w;
            lit += blocked ? 0 : w;
        }
    return lit / all;
}

static void truth_is_received_light(void **state)
{
    (void)state;
    const sx_setup sets[2] = {t1(1.0f), t2(1.0f)};
    double max_err = 0, max_err_coarse = 0, max_area_diff = 0, sum_area_diff = 0;
    int n_pen = 0;
    for (int s = 0; s < 2; s++)
        for (int k = 0; k <= 40; k++) {
            /* a line along the penumbra of the x = 1 edge into the corner region (steps not commensurate
               with the sample grid, so edges cut cells) */
            vec3 p = v3(1.15f + 0.0093f * (float)k, 0, 0.9f + 0.0141f * (float)k);
            double exact = sx_exact_v(&sets[s], p), area = sx_area_v(&sets[s], p);
            max_err = fmax(max_err, fabs(exact - numeric_v(&sets[s], p, 2000)));
            max_err_coarse = fmax(max_err_coarse, fabs(exact - numeric_v(&sets[s], p, 500)));
            if (exact > 1e-6 && exact < 1 - 1e-6) {
                max_area_diff = fmax(max_area_diff, fabs(area - exact));
                sum_area_diff += area - exact;
                n_pen++;
            }
        }
    printf("# truth: closed form vs numeric max |dV| %.2e (500^2 samples), %.2e (2000^2); area fraction - received "
           "light over %d penumbra points: mean %+.4f, max |.| %.4f\n",
           max_err_coarse, max_err, n_pen, sum_area_diff / n_pen, max_area_diff);
    assert_true(n_pen > 30);
    /* The midpoint rule cut by an occluder edge errs by up to a row of cells per edge, O(1/N): the
       numeric value must converge on the closed form (4x finer: measured 1.07e-3 -> 2.2e-4, bound a
       2x gain) and be within 1e-3 at N = 2000 (two edges x 1/2000 x the weight's 1.2x spread). */
    assert_true(max_err < 1e-3);
    assert_true(max_err < 0.5 * max_err_coarse);
    /* The two quantities really differ in the penumbra (measured max 0.035, mean -0.021): a truth
       that was still the area fraction would fail this. */
    assert_true(max_area_diff > 0.01);
}

static const char *const all_methods[] = {"hard", "pcss", "vssm", "cssm", "cssm_sat", "savsm"};
enum { M_HARD, M_PCSS, M_VSSM, M_CSSM, M_CSSM_SAT, M_SAVSM, M_N };

static void t1_every_method_matches_analytic(void **state)
{
    (void)state;
    sx_stats s[M_N];
    sx_setup st = t1(1.0f);
    measure(&st, "T1 S=1", all_methods, M_N, s, NULL);
    assert_true(s[M_PCSS].n[SX_PENUMBRA] > 300 && s[M_PCSS].n[SX_UMBRA] > 300 && s[M_PCSS].n[SX_LIT] > 3000);
    /* Measured (llvmpipe, 128^2, map 512) against the received light (sx_exact_v), mean |dV|
       umbra / penumbra / lit (before #11, against the area fraction, the penumbra column read
       0.248 / 0.030 / 0.011 / 0.113 / 0.116: the area fraction is 0.021 lower on average, which
       flattered VSSM and hurt CSSM):
         hard     0      / 0.245 / 0        (a step where the truth is a ramp)
         pcss     0      / 0.029 / 0        (12x12 PCF steps + per-pixel jitter)
         vssm     0      / 0.016 / 0        (bias -0.013: the kernel's box average is the area
                                            fraction, a few hundredths below the received light;
                                            before #21's search bound, VSSM_SEARCH_BOUND in
                                            shaders_gles/shadow/vssm.glsl: 0.0002 / 0.018 / 0.0001)
         cssm     0.049  / 0.088 / 0.0003   (K = 4, alpha = 1.12: the series saturates 0.064 of the
         cssm_sat 0.0001 / 0.062 / 0        normalised depth past the shifted receiver; normalised
                                            per map layer to the depths it holds (#11) the 1 m gap
                                            is most of the range. Over [near, far] as the thesis
                                            (cssm_thesis) it was 0.105 of it, and the umbra kept
                                            0.217 / 0.195 of the light, penumbra 0.092 / 0.092.
                                            The mipmap path's residual is its coarse levels
                                            mixing lit texels into the umbra's kernel.)
       Bounds: about 1.5x each measurement (absolute floors 0.005 where it is ~0); the CSSM umbra
       at #11's target, 0.05. */
    assert_true(s[M_PCSS].mean[SX_PENUMBRA] < 0.043 && s[M_PCSS].mean[SX_UMBRA] < 0.005);
    assert_true(s[M_VSSM].mean[SX_PENUMBRA] < 0.027 && s[M_VSSM].mean[SX_UMBRA] < 0.005 && s[M_VSSM].mean[SX_LIT] < 0.005);
    assert_true(s[M_VSSM].mean[SX_PENUMBRA] < s[M_PCSS].mean[SX_PENUMBRA]);
    assert_true(s[M_CSSM].mean[SX_PENUMBRA] < 0.13 && s[M_CSSM].mean[SX_UMBRA] <= 0.05 && s[M_CSSM].mean[SX_LIT] < 0.005);
    assert_true(s[M_CSSM_SAT].mean[SX_PENUMBRA] < 0.093 && s[M_CSSM_SAT].mean[SX_UMBRA] < 0.005);
    /* every soft method beats hard shadows in the penumbra at least 1.4x */
    for (int m = M_PCSS; m < M_N; m++)
        assert_true(s[m].mean[SX_PENUMBRA] * 1.4 < s[M_HARD].mean[SX_PENUMBRA]);
}

static void t2_stacked_blockers_and_f1_f4(void **state)
{
    (void)state;
    sx_stats s[M_N];
    double ratio[M_N];
    sx_setup st = t2(1.0f);
    measure(&st, "T2 S=1", all_methods, M_N, s, ratio);
    sx_setup st2 = t2(2.0f);
    sx_stats s2[M_N];
    double ratio2[M_N];
    measure(&st2, "T2 S=2", all_methods, M_N, s2, ratio2);
    /* F1 (light bleeding): mean positive error max(V - V_exact, 0) over umbra + penumbra is the
       bias's positive part; the penumbra bias stands for it. Measured at S = 1 against the
       received light: savsm +0.067, vssm -0.008, pcss -0.001 (against the area fraction before
       #11: +0.092, +0.091, +0.024). The thesis's subdivision (Alg. 2/3) only acts on NON-PLANAR
       kernels (E(z) >= d); on T2's flat receiver every kernel has E(z) < d, so the Chebyshev
       bleeding of two stacked blocker layers remains in SAVSM (dong-001.md §5.1's 0.2/0.6/1.0
       oracle: 0.100), and it was in VSSM (+0.066) until #21 cut the blocker search to the light's
       footprint at the nearest depth and bounded z_occ by it (VSSM_SEARCH_BOUND; savsm keeps the
       thesis's near-plane search): the near-plane kernel averaged blocker texels beside the
       footprint into z_occ, and the too-near z_occ widened the penumbra kernel over both layers.
       Asserted: the leak is there and measurable in SAVSM (> 0.05, the test can see it), VSSM is
       never worse than SAVSM and now within 0.013 of no bias (1.5x its measurement), and PCSS (no
       moments) leaks < half as much as SAVSM. */
    assert_true(s[M_SAVSM].bias[SX_PENUMBRA] > 0.05);
    assert_true(s[M_VSSM].bias[SX_PENUMBRA] <= s[M_SAVSM].bias[SX_PENUMBRA] + 0.002);
    assert_true(fabs(s[M_VSSM].bias[SX_PENUMBRA]) < 0.013);
    assert_true(s[M_PCSS].bias[SX_PENUMBRA] < 0.5 * s[M_SAVSM].bias[SX_PENUMBRA]);
    /* F4 (umbra underestimation, blocker flattening): umbra area ratio (V < 0.02) vs exact.
       Measured S = 1 / S = 2: vssm 0.933 / 0.791 (0.885 / 0.734 before #21's search bound), cssm 0.349 / 0.000, cssm_sat 0.984 / 0.977,
       pcss 1.00 / 0.98, hard 1.52 / 2.69 (before #11's per-layer CSSM depth range: cssm 0.905 /
       0.491, cssm_sat 1.03 / 1.21). The moment methods underestimate and get worse with the
       light size, as the thesis says; the mipmapped CSSM loses the umbra entirely at S = 2 (its
       coarse levels mix the lit floor into the umbra's kernel; umbra mean V 0.163), the SAT path
       keeps it. Bounds at the measurement +-0.1 so a change shows. */
    assert_true(ratio[M_VSSM] < 0.98 && ratio[M_VSSM] > 0.78);
    assert_true(ratio2[M_VSSM] < ratio[M_VSSM] && ratio2[M_VSSM] > 0.63);
    assert_true(ratio2[M_CSSM] < ratio[M_CSSM] && ratio[M_CSSM] > 0.25 && ratio[M_CSSM] < 0.45);
    assert_true(ratio[M_CSSM_SAT] > 0.88 && ratio2[M_CSSM_SAT] > 0.87);
    assert_true(ratio[M_PCSS] > 0.9 && ratio2[M_PCSS] > 0.88);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(truth_is_received_light),
        cmocka_unit_test(t1_every_method_matches_analytic),
        cmocka_unit_test(t2_stacked_blockers_and_f1_f4),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
