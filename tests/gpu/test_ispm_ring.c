/* ispm on the shipped scene config/scenes/caustic-ring.gltf at the references' 160×120: the caustic
 * is there (inside the ring, where the near wall's shadow leaves only indirect light, against vpl's
 * indirect and against the path-traced caustic reference's mean in the same region), the reference
 * caustic mask when the reference tracer has written it, and the failure modes L9 (self-
 * intersection), L13 (flicker under a shuffled compaction order) and L19 (the
 * trace's work against photons × trace resolution). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <unistd.h>

#include <cmocka.h>

#include "io/image_io.h"
#include "test_ispm_harness.h"

#define W 160
#define HH 120
#define MASK_PATH "tests/references/caustic-ring-caustics-mask.png"
#define REF_PATH "tests/references/caustic-ring-caustics.exr"

static gk_scene *S;
static ispm_h H;
static bool inside[W * HH];   /* floor pixels inside the ring (radius 0.5) */
static int n_inside;

static int setup(void **state)
{
    (void)state;
    gk_err e = {0};
    S = gk_scene_load("config/scenes/caustic-ring.gltf", &e);
    if (!S) {
        fprintf(stderr, "%s\n", e.msg);
        return -1;
    }
    gk_scene_evaluate(S, 0.0f);
    if (ih_open(&H, S, W, HH))
        return -1;
    ih_debug(&H, NULL);
    for (int y = 0; y < HH; y++)
        for (int x = 0; x < W; x++) {
            vec3 p;
            int i = y * W + x;
            inside[i] = ih_floor_pixel(&H, i) && ih_on_plane_y(&H, x, y, 0.0f, &p) && p.x * p.x + p.z * p.z < 0.48f * 0.48f;
            n_inside += inside[i];
        }
    return n_inside > 0 ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    ih_close(&H);
    gk_scene_free(S);
    return 0;
}

static double region_mean(const float *img, int stride)
{
    double s = 0;
    for (int i = 0; i < W * HH; i++)
        if (inside[i])
            s += ih_lum(&img[i * stride]);
    return s / n_inside;
}

static void set_debug(bool caustics_only)
{
    gk_ispm_debug d;
    gk_ispm_default_debug(&d);
    d.measure = true, d.caustics_only = caustics_only;
    gk_ispm_set_debug(H.self, &d);
}

static void test_caustic_visible(void **state)
{
    (void)state;
    assert_int_equal(ih_budget(&H, NULL), 0);
    set_debug(false);
    assert_int_equal(ih_frame(&H), 0);
    double full = region_mean(H.img, 4);
    set_debug(true);
    assert_int_equal(ih_frame(&H), 0);
    double caustic = region_mean(H.img, 4), vpl = full - caustic;
    gk_err e = {0};
    gk_image ref = {0};
    assert_int_equal(gk_image_read(REF_PATH, &ref, &e), 0);
    assert_int_equal(ref.width, W);
    /* the reference is stored top row first, the GL image bottom row first */
    double rs = 0;
    for (int y = 0; y < HH; y++)
        for (int x = 0; x < W; x++)
            if (inside[y * W + x])
                rs += ih_lum(&ref.pixels[((HH - 1 - y) * W + x) * ref.channels]);
    double ref_mean = rs / n_inside;
    gk_image_free(&ref);
    printf("# inside the ring (%d floor pixels, in the near wall's shadow: no direct light): caustic %.4f, "
           "vpl's indirect %.4f (caustic/indirect %.2f), reference caustic %.4f (ispm/reference %.3f)\n", n_inside,
           caustic, vpl, caustic / vpl, ref_mean, caustic / ref_mean);
    /* A KNOWN GAP, asserted as measured so it cannot get worse unnoticed (not the target):
       inside the ring ispm gives 0.1095, 0.21 of the light-traced reference's region mean 0.5232
       and 0.13 of vpl's indirect there. Part is the seed's single specular bounce (L7: the concave
       ring sends much light through two bounces), the rest is not yet explained. Bounds: caustic
       > 0.15 of the reference mean and > 0.1 of the indirect. */
    assert_true(caustic > 0.15 * ref_mean);
    assert_true(caustic > 0.1 * vpl);
}

/* The reference tracer's caustic mask (pixels above ¼ of the reference caustic's peak, written by
   `make references` beside caustic-ring-caustics.exr). The target -- energy inside it within
   ±15% of the reference and IoU ≥ 0.7 -- is NOT met: measured on llvmpipe, energy ratio 0.423 and
   IoU 0.090 (ispm's brightest pixels are a thin arc where the reference's cardioid is wide; see the
   inside-ring gap above: the reference has the ring's multi-bounce paths, the seed's method one
   specular bounce). A KNOWN GAP, asserted as measured (measured 0.436 and 0.096 after the BRDF merge; bounds 0.35 and 0.06, below the measurement
   by more than the frame-to-frame change of L13) so it cannot get worse unnoticed; issue 14 stays
   open on it. */
static void test_reference_mask(void **state)
{
    (void)state;
    assert_int_equal(access(MASK_PATH, R_OK), 0); /* committed beside the reference */
    gk_err e = {0};
    gk_image mask = {0}, ref = {0};
    assert_int_equal(gk_image_read(MASK_PATH, &mask, &e), 0);
    assert_int_equal(gk_image_read(REF_PATH, &ref, &e), 0);
    assert_int_equal(ih_budget(&H, "ispm_photons=65536,ispm_trace=256"), 0);
    set_debug(true);
    assert_int_equal(ih_frame(&H), 0);
    double peak = 0;
    for (int i = 0; i < W * HH; i++)
        peak = fmax(peak, ih_lum(&H.img[i * 4]));
    double e_ours = 0, e_ref = 0;
    int inter = 0, uni = 0;
    for (int y = 0; y < HH; y++)
        for (int x = 0; x < W; x++) {
            int gi = y * W + x, ri = (HH - 1 - y) * W + x;
            bool m = mask.pixels[ri * mask.channels] > 0.5f, ours = ih_lum(&H.img[gi * 4]) > 0.25 * peak;
            inter += m && ours, uni += m || ours;
            if (m)
                e_ours += ih_lum(&H.img[gi * 4]), e_ref += ih_lum(&ref.pixels[ri * ref.channels]);
        }
    printf("# reference mask: energy ratio %.3f, IoU %.3f\n", e_ours / e_ref, (double)inter / uni);
    gk_image_free(&mask);
    gk_image_free(&ref);
    printf("# the issue's target (energy within 0.85..1.15, IoU >= 0.7): %s\n",
           fabs(e_ours / e_ref - 1.0) < 0.15 && (double)inter / uni >= 0.7 ? "met" : "NOT met (known gap)");
    assert_true(e_ours / e_ref > 0.35);
    assert_true((double)inter / uni > 0.06);
}

/* L9: hits on the ring itself within 2 trace pixels of their photon's origin, with and without the
   back-face rule. */
static void test_l9_self_intersection(void **state)
{
    (void)state;
    assert_int_equal(ih_budget(&H, "ispm_photons=16384"), 0);
    double frac[2];
    for (int rule_off = 0; rule_off < 2; rule_off++) {
        gk_ispm_debug d;
        gk_ispm_default_debug(&d);
        d.measure = d.caustics_only = true, d.no_backface_rule = rule_off;
        gk_ispm_set_debug(H.self, &d);
        assert_int_equal(ih_frame(&H), 0);
        const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
        gk_ispm_photon *p = calloc((size_t)st->capacity, sizeof *p);
        gk_ispm_hit *h = calloc((size_t)st->capacity, sizeof *h);
        int np = gk_ispm_read_photons(H.self, p, st->capacity);
        gk_ispm_read_hits(H.self, h, st->capacity);
        int hits = 0, near = 0;
        for (int i = 0; i < np; i++) {
            if (h[i].pos_valid[3] < 0.5f)
                continue;
            float a[2], b[2];
            hits++;
            if (gk_ispm_trace_pixel(H.self, v3(p[i].org[0], p[i].org[1], p[i].org[2]), a) &&
                gk_ispm_trace_pixel(H.self, v3(h[i].pos_valid[0], h[i].pos_valid[1], h[i].pos_valid[2]), b) &&
                hypotf(a[0] - b[0], a[1] - b[1]) < 2.0f && h[i].pos_valid[1] > 0.01f &&
                fabsf(hypotf(h[i].pos_valid[0], h[i].pos_valid[2]) - 0.51f) < 0.03f)
                near++;   /* on the ring itself, next to where the photon left it */
        }
        frac[rule_off] = hits ? (double)near / hits : 0;
        printf("# L9 %s: %d hits, %.4f on the ring within 2 trace pixels of their origin\n", rule_off ? "without the rule" : "with the rule",
               hits, frac[rule_off]);
        free(p);
        free(h);
    }
    /* research A.6 item 6: < 1% with the rule (measured 0.0069), a large fraction without it
       (measured 0.36: the photon's own wall is hit at once) */
    assert_true(frac[0] < 0.01);
    assert_true(frac[1] > 0.2);
}

/* L13: a GPU's compaction order changes every frame; llvmpipe's does not, so shuffle it. */
static void test_l13_flicker(void **state)
{
    (void)state;
    assert_int_equal(ih_budget(&H, "ispm_photons=4096"), 0);
    double flicker[2];
    float *prev = malloc(W * HH * 4 * sizeof(float));
    for (int by_slot = 0; by_slot < 2; by_slot++) {
        double peak = 0, worst = 0;
        for (int f = 0; f < 6; f++) {
            gk_ispm_debug d;
            gk_ispm_default_debug(&d);
            d.measure = d.caustics_only = true, d.rng_by_slot = by_slot, d.shuffle = 7;
            gk_ispm_set_debug(H.self, &d);
            assert_int_equal(ih_frame(&H), 0);
            for (int i = 0; i < W * HH; i++) {
                double v = ih_lum(&H.img[i * 4]);
                peak = fmax(peak, v);
                if (f > 0)
                    worst = fmax(worst, fabs(v - ih_lum(&prev[i * 4])));
            }
            memcpy(prev, H.img, W * HH * 4 * sizeof(float));
        }
        flicker[by_slot] = worst / peak;
    }
    free(prev);
    printf("# L13 max frame-to-frame change / peak under a shuffled compaction: random numbers by RSM block %.2e, "
           "by compacted index %.3f\n", flicker[0], flicker[1]);
    /* by block only the order of the float additions changes (measured 1.5e-7); by index each
       surface point draws new numbers every frame (measured 0.35) */
    assert_true(flicker[0] < 1e-4);
    assert_true(flicker[1] > 0.05);
}

/* L19: the trace's work (march steps + list nodes visited, counted by trace.comp) against
   photons × trace resolution, fitted as T = a·N·R through the origin. */
static void test_l19_cost_fit(void **state)
{
    (void)state;
    set_debug(true);
    const int np[3] = {1024, 4096, 16384}, tr[2] = {64, 128};
    double n[6], r[6], t[6];
    int k = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 2; j++, k++) {
            char b[96];
            snprintf(b, sizeof b, "ispm_photons=%d,ispm_trace=%d", np[i], tr[j]);
            assert_int_equal(ih_budget(&H, b), 0);
            assert_int_equal(ih_frame(&H), 0);
            const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
            n[k] = st->reflected, r[k] = tr[j], t[k] = st->trace_work;
        }
    double sxy = 0, sxx = 0, sst = 0, mean = 0;
    for (k = 0; k < 6; k++)
        sxy += n[k] * r[k] * t[k], sxx += n[k] * r[k] * n[k] * r[k], mean += t[k] / 6;
    double a = sxy / sxx, sse = 0;
    for (k = 0; k < 6; k++)
        sse += pow(t[k] - a * n[k] * r[k], 2), sst += pow(t[k] - mean, 2);
    double r2 = 1 - sse / sst;
    printf("# L19 work = %.3f · N · R, R² = %.4f; 64 -> 128 ratios %.2f %.2f %.2f\n", a, r2, t[1] / t[0], t[3] / t[2],
           t[5] / t[4]);
    for (k = 0; k < 6; k++)
        printf("#   N %.0f R %.0f work %.0f\n", n[k], r[k], t[k]);
    assert_true(r2 > 0.9);
    for (int i = 0; i < 3; i++) {
        double q = t[2 * i + 1] / t[2 * i];
        assert_true(q > 1.6 && q < 2.6);   /* the research's bound (the seed: ×1.9–2.5); measured 1.90–1.93, R² 0.9991 */
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_caustic_visible),   cmocka_unit_test(test_reference_mask),
        cmocka_unit_test(test_l9_self_intersection), cmocka_unit_test(test_l13_flicker),
        cmocka_unit_test(test_l19_cost_fit),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
