/* ispm's failure modes of research A.4 on the shipped caustic-ring (160×120, the references' size)
 * that the ring tests do not cover: L8 (tracing through 4 depth-peeled layers against the lists),
 * L11 (a list pool too small: overflow counted, the frame still drawn), L12 (the ring tilted
 * frame by frame under the light: the photon count jumps ×4 when the mask level changes, the
 * caustic's energy must not) and L14 (splat-radius singularities at the ring's foot and at grazing
 * incidence: fireflies without the clamps). Each prints its number; the bounds say where they come
 * from. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "io/image_io.h"
#include "test_ispm_harness.h"

#define W 160
#define HH 120
#define REF_PATH "tests/references/caustic-ring-caustics1.exr"
#define MASK_PATH "tests/references/caustic-ring-caustics1-mask.png"

static gk_scene *S;
static ispm_h H;
static int ring_node = -1;

static int setup(void **state)
{
    (void)state;
    gk_err e = {0};
    S = gk_scene_load("config/scenes/caustic-ring.gltf", &e);
    if (!S) {
        fprintf(stderr, "%s\n", e.msg);
        return -1;
    }
    for (int i = 0; i < S->n_nodes; i++)
        if (!strcmp(S->nodes[i].name, "ring"))
            ring_node = i;
    gk_scene_evaluate(S, 0.0f);
    if (ring_node < 0 || ih_open(&H, S, W, HH))
        return -1;
    ih_debug(&H, NULL);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    ih_close(&H);
    gk_scene_free(S);
    return 0;
}

static void debug_with(void (*edit)(gk_ispm_debug *)) { ih_debug(&H, edit); }

/* Σ luminance of what ispm added (the caustic; receivers of one albedo, so ∝ its power in view). */
static double caustic_sum(void)
{
    double s = 0;
    for (int i = 0; i < W * HH; i++)
        s += ih_lum(&H.img[i * 4]);
    return s;
}

static double caustic_max(void)
{
    double m = 0;
    for (int i = 0; i < W * HH; i++)
        m = fmax(m, ih_lum(&H.img[i * 4]));
    return m;
}

/* Σ luminance inside the single-bounce reference's caustic mask, ispm / reference. */
static double mask_energy(void)
{
    gk_err e = {0};
    gk_image ref = {0}, mask = {0};
    assert_int_equal(gk_image_read(REF_PATH, &ref, &e), 0);
    assert_int_equal(gk_image_read(MASK_PATH, &mask, &e), 0);
    double eo = 0, er = 0;
    for (int y = 0; y < HH; y++)
        for (int x = 0; x < W; x++) {
            int ri = (HH - 1 - y) * W + x;   /* references top row first, GL bottom row first */
            if (mask.pixels[ri * mask.channels] > 0.5f)
                eo += ih_lum(&H.img[(y * W + x) * 4]), er += ih_lum(&ref.pixels[ri * ref.channels]);
        }
    gk_image_free(&ref);
    gk_image_free(&mask);
    return eo / er;
}

/* L8: caustic-ring's pixels hold up to 6 fragments (the ring's four walls, its rim, the floor);
   4 peeled layers drop what lies behind, so photons pass where the lists stop them. */
static void test_l8_layers_against_lists(void **state)
{
    (void)state;
    double energy[2];
    unsigned hits[2];
    int longest = 0, over4 = 0;
    for (int tier = 0; tier < 2; tier++) {
        assert_int_equal(ih_budget(&H, tier == GK_ISPM_TIER_PEEL ? "ispm_photons=65536,ispm_trace=256,ispm_splat=1,ispm_tier=peel"
                                                                 : "ispm_photons=65536,ispm_trace=256,ispm_splat=1,ispm_tier=lists"),
                         0);
        assert_int_equal(ih_frame(&H), 0);
        const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
        assert_int_equal(st->tier, tier);
        energy[tier] = mask_energy(), hits[tier] = st->hits;
        if (tier == GK_ISPM_TIER_LISTS) {
            int n = st->trace_res * st->trace_res;
            gk_ispm_pixel *px = calloc((size_t)n, sizeof *px);
            assert_int_equal(gk_ispm_read_pixels(H.self, px, n), n);
            for (int i = 0; i < n; i++)
                longest = px[i].count > (unsigned)longest ? (int)px[i].count : longest, over4 += px[i].count > 4;
            free(px);
        }
    }
    printf("# L8 lists: longest list %d fragments, %d trace pixels with more than 4; hits lists %u / 4 layers %u; "
           "energy in the one-bounce mask lists %.3f / 4 layers %.3f\n", longest, over4, hits[1], hits[0], energy[1],
           energy[0]);
    /* measured: longest 5, 92 pixels; 12965 / 10162 hits; energy 0.973 / 1.081 (photons stopped by
       the lists' fifth fragment go on through the layers onto the floor) */
    assert_true(longest > 4);
    assert_true(over4 > 0);
    assert_true(hits[0] < hits[1]);
    assert_true(fabs(energy[1] - 1.0) < fabs(energy[0] - 1.0));
}

/* L11: a pool too small for the frustum's fragments. */
static void shrink_pool(gk_ispm_debug *d) { d->pool_nodes = 20000; }

static void test_l11_list_overflow(void **state)
{
    (void)state;
    assert_int_equal(ih_budget(&H, "ispm_photons=16384,ispm_trace=256,ispm_pool=20,ispm_tier=lists"), 0);
    assert_int_equal(ih_frame(&H), 0);
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    unsigned frags = st->fragments, ovf = st->list_overflow, hits = st->hits;
    double e_full = mask_energy();
    debug_with(shrink_pool);
    assert_int_equal(ih_frame(&H), 0);
    st = gk_ispm_get_stats(H.self);
    unsigned small_ovf = st->list_overflow, small_hits = st->hits;
    double e_small = mask_energy();
    debug_with(NULL);
    printf("# L11 20 MB pool at 256²: %u fragments, %u dropped, %u hits, energy in the one-bounce mask %.3f; "
           "a 20000-node pool: %u dropped, %u hits, energy %.3f\n", frags, ovf, hits, e_full, small_ovf, small_hits, e_small);
    /* measured: 81730 fragments, 0 dropped; 61730 dropped, 3327 -> 755 hits, energy 0.970 -> 0.394 */
    assert_int_equal(ovf, 0);                      /* the configured budget holds the frame */
    assert_int_equal(small_ovf, frags - 20000);    /* every fragment beyond the pool is counted */
    assert_true(small_hits < hits);                /* missing geometry: photons lost or leaked */
}

/* L14: the radius clamps (cosθ ≥ cos_min, h in [h_min, h_max], at least h_pixels splat pixels) off.
   Here d is the whole path light→mirror→receiver (≥ the lamp's 3 m), so the d → 0 singularity of
   the last-segment reading cannot occur at the ring's foot; what is left is grazing incidence,
   cosθ → 0, whose disks would grow without bound: blur, not fireflies. On caustic-ring no photon
   lands grazing enough for cos_min or h_max to engage (largest disk 3.7 cm, h_max 22 cm); only the
   least radius of h_pixels splat pixels acts, and its peaks stay the reference's. */
static void no_clamps(gk_ispm_debug *d) { d->cos_min = 1e-4f, d->h_min_rel = 0.0f, d->h_max_rel = 1e3f, d->h_pixels = 0.0f; }

static double largest_radius(void)
{
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    gk_ispm_hit *h = calloc((size_t)st->capacity, sizeof *h);
    int n = gk_ispm_read_hits(H.self, h, st->capacity);
    double m = 0;
    for (int i = 0; i < n; i++)
        if (h[i].pos_valid[3] > 0.5f)
            m = fmax(m, h[i].nrm_h[3]);
    free(h);
    return m;
}

static void test_l14_radius_singularities(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_image ref = {0};
    assert_int_equal(gk_image_read(REF_PATH, &ref, &e), 0);
    double ref_max = 0;
    for (int i = 0; i < W * HH; i++)
        ref_max = fmax(ref_max, ih_lum(&ref.pixels[i * ref.channels]));
    gk_image_free(&ref);
    assert_int_equal(ih_budget(&H, "ispm_photons=65536,ispm_trace=256,ispm_splat=1"), 0);
    assert_int_equal(ih_frame(&H), 0);
    double clamped = caustic_max(), e_clamped = caustic_sum(), h_clamped = largest_radius();
    debug_with(no_clamps);
    assert_int_equal(ih_frame(&H), 0);
    double bare = caustic_max(), e_bare = caustic_sum(), h_bare = largest_radius();
    debug_with(NULL);
    printf("# L14 max caustic / the one-bounce reference's max %.3f: clamped %.2f, unclamped %.2f; largest disk %.3f m "
           "clamped, %.3f m unclamped; Σ caustic unclamped / clamped %.3f\n", ref_max, clamped / ref_max, bare / ref_max,
           h_clamped, h_bare, e_bare / e_clamped);
    /* measured 1.10 and 1.19 of the reference's max: no fireflies either way (bound 2); the caustic's
       sum 1.004 (normalised kernels: the radius moves light, never makes it; bound 2%); the
       largest disk 0.036 / 0.037 m, below h_max = 0.03 · the scene's diameter */
    assert_true(clamped / ref_max < 2.0 && bare / ref_max < 2.0);
    assert_true(fabs(e_bare / e_clamped - 1.0) < 0.02);
    assert_true(h_bare < 0.03 * v3_len(v3_sub(S->bmax, S->bmin)));
}

/* L12: the ring tilted about the axis across the light's direction, 1° a frame; photon budget 4096,
   so the mask level changes as the ring's specular texels change. The caustic's energy against
   the richest budget (every specular texel a photon) at the same tilt, block power (the default)
   and the seed's full blocks. */
static void seed_blocks(gk_ispm_debug *d) { d->faithful_blocks = true; }

static void tilt_ring(float deg)
{
    float a = deg * (float)M_PI / 180.0f;
    S->nodes[ring_node].rotation = (quat){sinf(a / 2), 0, 0, cosf(a / 2)};   /* about x, across the light's xz-plane */
    gk_scene_evaluate(S, 0.0f);
    assert_int_equal(ih_gbuffer(&H), 0);
}

static void test_l12_rotating_ring(void **state)
{
    (void)state;
    enum { STEPS = 13 };
    double ratio[2][STEPS];
    unsigned level[STEPS], n[STEPS];
    int changes = 0;
    for (int k = 0; k < STEPS; k++) {
        tilt_ring((float)k);
        double rich, e[2];
        debug_with(NULL);
        assert_int_equal(ih_budget(&H, "ispm_photons=65536"), 0);
        assert_int_equal(ih_frame(&H), 0);
        rich = caustic_sum();
        for (int seed = 0; seed < 2; seed++) {
            debug_with(seed ? seed_blocks : NULL);
            assert_int_equal(ih_budget(&H, "ispm_photons=4096"), 0);
            assert_int_equal(ih_frame(&H), 0);
            e[seed] = caustic_sum();
            if (!seed)
                level[k] = gk_ispm_get_stats(H.self)->level, n[k] = gk_ispm_get_stats(H.self)->photons;
        }
        ratio[0][k] = e[0] / rich, ratio[1][k] = e[1] / rich;
        changes += k > 0 && level[k] != level[k - 1];
        printf("# L12 tilt %2d°: level %u, %5u photons, energy / richest: block power %.3f, the seed's full blocks %.3f\n", k,
               level[k], n[k], ratio[0][k], ratio[1][k]);
    }
    tilt_ring(0.0f);
    debug_with(NULL);
    double worst[2] = {0, 0};
    for (int k = 0; k < STEPS; k++)
        for (int m = 0; m < 2; m++)
            worst[m] = fmax(worst[m], fabs(ratio[m][k] - 1.0));
    printf("# L12 %d level changes; worst |energy/richest − 1|: block power %.3f, the seed's full blocks %.3f\n", changes,
           worst[0], worst[1]);
    /* measured: one change (level 2 -> 1, 1077 -> 4096 photons, between 1° and 2°), worst 0.014 with
       block power, 0.042 with the seed's full blocks (the mirror test's L12 bound: 2%) */
    assert_true(changes > 0);
    assert_true(worst[0] < 0.02);
    assert_true(worst[1] > worst[0]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_l8_layers_against_lists),
        cmocka_unit_test(test_l11_list_overflow),
        cmocka_unit_test(test_l14_radius_singularities),
        cmocka_unit_test(test_l12_rotating_ring),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
