/* ispm on the shipped scene config/scenes/caustic-ring.gltf at the references' 160×120, against the
 * path-traced caustic references and their masks (pixels above ¼ of the reference's peak, written by
 * `make references`): the seed's single specular bounce against caustic-ring-caustics1.exr (the
 * light tracer's paths with one mirror vertex, L S D E), the specular chains (ispm_bounces=3)
 * against the full caustic caustic-ring-caustics.exr (L7: what the single bounce misses on this
 * concave mirror), rel. RMSE inside the mask per budget level; the specular chains' landing points
 * against the reference tracer's (the shape operator's normal at the hit against the node's own);
 * and the failure modes L9
 * (self-intersection), L13 (flicker under a shuffled compaction order) and L19 (the trace's work
 * against photons × trace resolution). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <unistd.h>

#include <cmocka.h>

#include "io/image_io.h"
#include "metrics/metrics.h"
#include "ref/materials.h"
#include "ref/ref_scene.h"
#include "ref/trace.h"
#include "test_ispm_harness.h"

#define W 160
#define HH 120
#define REF_PATH "tests/references/caustic-ring-caustics.exr"
#define MASK_PATH "tests/references/caustic-ring-caustics-mask.png"
#define REF1_PATH "tests/references/caustic-ring-caustics1.exr"
#define MASK1_PATH "tests/references/caustic-ring-caustics1-mask.png"
/* The richest budget of the caustic: every specular RSM texel a photon (16,666 on caustic-ring),
   the trace at 256², the splats at full resolution. */
#define RICH "ispm_photons=65536,ispm_trace=256,ispm_splat=1"

static gk_scene *S;
static ispm_h H;

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
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    ih_close(&H);
    gk_scene_free(S);
    return 0;
}

static void set_debug(bool caustics_only)
{
    gk_ispm_debug d;
    gk_ispm_default_debug(&d);
    d.measure = true, d.caustics_only = caustics_only;
    gk_ispm_set_debug(H.self, &d);
}

static void flat_mirror_normal(gk_ispm_debug *d) { d->flat_mirror_normal = true; }

/* What ispm's caustic gives against a reference inside its mask, as `gikiosk compare --mask`
   measures it (app/metrics), plus the energy ratio and mask IoU. */
typedef struct ruler {
    double energy;      /* Σ luminance inside the reference mask, ispm / reference */
    double iou;         /* ispm's own mask (above ¼ of its peak) against the reference's */
    double rel_in;      /* rel. RMSE inside the mask */
    double rel_all;     /* rel. RMSE over the whole image */
} ruler;

static void measure(const char *budget, void (*edit)(gk_ispm_debug *), const char *ref_path, const char *mask_path,
                    ruler *r)
{
    gk_err e = {0};
    gk_image ref = {0}, mimg = {0}, ours = {0};
    assert_int_equal(gk_image_read(ref_path, &ref, &e), 0);
    assert_int_equal(gk_image_read(mask_path, &mimg, &e), 0);
    assert_int_equal(ref.width, W);
    assert_int_equal(ih_budget(&H, budget), 0);
    ih_debug(&H, edit);
    assert_int_equal(ih_frame(&H), 0);
    /* the GL image is bottom row first, the references top row first */
    assert_int_equal(gk_image_alloc(&ours, W, HH, 3), 0);
    for (int y = 0; y < HH; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                ours.pixels[((HH - 1 - y) * W + x) * 3 + c] = H.img[(y * W + x) * 4 + c];
    unsigned char *mask = gk_mask_from_image(&mimg);
    float peak;
    unsigned char *mine = gk_mask_above_peak(&ours, 0.25, &peak);
    assert_non_null(mask);
    assert_non_null(mine);
    double eo = 0, er = 0;
    long inter = 0, uni = 0;
    for (int i = 0; i < W * HH; i++) {
        inter += mask[i] && mine[i], uni += mask[i] || mine[i];
        if (mask[i])
            eo += ih_lum(&ours.pixels[i * 3]), er += ih_lum(&ref.pixels[i * ref.channels]);
    }
    r->energy = eo / er, r->iou = (double)inter / (double)uni;
    gk_metrics m;
    double exposure = gk_metrics_auto_exposure(&ref);
    assert_int_equal(gk_metrics_compute_masked(&ref, &ours, exposure, mask, &m, &e), 0);
    r->rel_in = m.rel_rmse;
    assert_int_equal(gk_metrics_compute(&ref, &ours, exposure, &m, &e), 0);
    r->rel_all = m.rel_rmse;
    free(mask);
    free(mine);
    gk_image_free(&ref);
    gk_image_free(&mimg);
    gk_image_free(&ours);
}

/* The seed's method (one specular bounce) against the caustic of one specular bounce: the issue's
   targets, energy inside the mask within ±15% and mask IoU ≥ 0.7. Measured on llvmpipe: energy
   0.973, IoU 0.791, rel. RMSE 0.133 inside the mask (before the plane hit test: 4.7% of the photon
   power went through the ring's wall). The reference's own floor inside its mask is in
   noise-regions.csv (caustic-ring-caustics1.exr), far below these margins. The footprint ellipses
   (ispm_radius=footprint, kernel averaged over 4x4 points per pixel): energy 0.975, IoU 0.801, rel.
   RMSE 0.128 inside / 0.255 whole (the seed's disks 0.312 whole). Under light moves of 0.5–3 mm
   (six positions, by hand) the IoU ranges over 0.801–0.815 (seed 0.790–0.810: no difference
   asserted), rel. RMSE inside over 0.126–0.129 (seed 0.131–0.133). */
static void test_single_bounce_against_its_reference(void **state)
{
    (void)state;
    ruler r, foot;
    measure(RICH, NULL, REF1_PATH, MASK1_PATH, &r);
    measure(RICH ",ispm_radius=footprint", NULL, REF1_PATH, MASK1_PATH, &foot);
    const ruler *row[2] = {&r, &foot};
    const char *name[2] = {"seed radius", "ispm_radius=footprint"};
    for (int i = 0; i < 2; i++)
        printf("# one bounce vs caustic-ring-caustics1 (L S D E), %s: energy in its mask %.3f, IoU %.3f, rel. RMSE "
               "inside %.3f, whole image %.3f\n", name[i], row[i]->energy, row[i]->iou, row[i]->rel_in, row[i]->rel_all);
    for (int i = 0; i < 2; i++) {
        assert_true(fabs(row[i]->energy - 1.0) < 0.15);
        assert_true(row[i]->iou >= 0.7);
    }
    /* less error in and out of the mask, the energy the same within 0.5% */
    assert_true(foot.rel_in < r.rel_in && foot.rel_all < r.rel_all);
    assert_true(fabs(foot.energy - r.energy) < 0.005);
}

/* Against the full caustic (every specular chain, L S+ D E): the seed's single bounce (L7: the
   concave ring focuses much of its light through two and more mirror bounces, measured energy
   0.526 in the mask, IoU 0.146) and the specular chains of ispm_bounces=3, with the seed's splat
   radius and with ispm_radius=density, each also with the chains reflecting about the node's own
   normal (flat_mirror_normal, the previous default) instead of the normal at the hit.
   Measured on llvmpipe (shape operator / flat normal):
     ispm_bounces=3:                     energy 0.922 / 0.916, IoU 0.549 / 0.517, rel. RMSE inside 0.200 / 0.261
     ispm_bounces=3, ispm_radius=density: energy 0.913 / 0.908, IoU 0.673 / 0.586, rel. RMSE inside 0.210 / 0.272
   The targets: energy ±15% is met; IoU ≥ 0.7 is NOT with disks (best 0.673; the footprint
   ellipses below meet it). The ruler's noise is far
   below both: an independent 512-spp render of the same caustic (seed 2) has energy 0.998 and IoU
   0.906 against this 2048-spp mask (the reference's floor inside it is 0.013, noise-regions.csv).
   Nor does the three-bounce limit forbid it: the tracer's own caustic cut at three specular vertices (--caustic-specular 3, 512 spp) has
   energy 0.974 and IoU 0.810 against this mask, so the three-bounce limit costs ~0.19 of IoU at
   most. What is left is ispm's: one photon per specular RSM texel (16,666 at the richest budget)
   splatted with disks a few pixels wide broadens the reference's one-to-two-pixel arcs and lowers
   the peak (2.54 against 2.86), so ¼ of it takes in more pixels; a 512² RSM (66,656 photons,
   tried) did not raise the IoU (0.578), nor did smaller least radii (h_pixels 0.75–1.5, h_min
   1–1.5 cm: 0.51–0.54); the IoU moves by ±0.05 under changes that should not matter (RSM normals
   in RGBA32F instead of RGB10_A2: 0.528 and 0.608), the ¼-of-peak cut of a photon image this
   sparse being that sensitive.
   Asserted: the energy target for both radii, the single bounce's loss (L7, < 0.7), the shape
   operator's gain in IoU and rel. RMSE over the flat normal for both radii, and the IoU as measured:
   bounds 0.5 (seed radius) and 0.62 (density): the measurements less the ±0.05 the IoU moves under
   immaterial changes (above; density k = 24/32 gave 0.634/0.671 with the shape operator in two halves).
   Moving the light by 0.5–3 mm (six positions, by hand) moves the density radius' IoU over
   0.622–0.684 and its peak over 2.44–2.69: the ¼-of-peak cut follows one pixel's value.
   ispm_radius=footprint (ellipses from the photons' neighbours, their kernel averaged over 4x4
   points of each splat pixel): energy 0.937, IoU 0.709, rel. RMSE inside 0.158, whole 0.317, peak
   2.71: better than both disks on every measure, and the IoU >= 0.7 met at this view, but
   narrowly: under the same light moves its IoU ranges over 0.696–0.711 (peak 2.64–2.71). Point-
   sampled at the pixel centre (pixel_samples = 1) the ellipses must be 1.5 pixels wide on screen
   to deposit their power (L15), and give 0.518 (peak 2.16); 2/3/6/8 samples per side give
   0.672/0.696/0.715/0.719. It is not the trace: within a pixel of the cusp ispm's hits carry the
   power the reference tracer's own paths of the same photons bring there
   (test_cusp_power_against_the_tracer); the peak is the splats' reconstruction of it. Bound for the
   footprint 0.69: 0.709 less the 0.015 its IoU moves under the light moves. */
static void test_reference_mask(void **state)
{
    (void)state;
    assert_int_equal(access(MASK_PATH, R_OK), 0); /* committed beside the reference */
    ruler one, chains, dens, chains_flat, dens_flat, foot;
    measure(RICH, NULL, REF_PATH, MASK_PATH, &one);
    measure(RICH ",ispm_bounces=3", NULL, REF_PATH, MASK_PATH, &chains);
    measure(RICH ",ispm_bounces=3,ispm_radius=density", NULL, REF_PATH, MASK_PATH, &dens);
    measure(RICH ",ispm_bounces=3", flat_mirror_normal, REF_PATH, MASK_PATH, &chains_flat);
    measure(RICH ",ispm_bounces=3,ispm_radius=density", flat_mirror_normal, REF_PATH, MASK_PATH, &dens_flat);
    measure(RICH ",ispm_bounces=3,ispm_radius=footprint", NULL, REF_PATH, MASK_PATH, &foot);
    const ruler *row[6] = {&one, &chains, &dens, &chains_flat, &dens_flat, &foot};
    const char *name[6] = {"one bounce", "ispm_bounces=3", "ispm_bounces=3, ispm_radius=density",
                           "ispm_bounces=3, flat mirror normal", "ispm_bounces=3, ispm_radius=density, flat mirror normal",
                           "ispm_bounces=3, ispm_radius=footprint"};
    for (int i = 0; i < 6; i++)
        printf("# vs caustic-ring-caustics (L S+ D E): %s: energy %.3f, IoU %.3f, rel. RMSE inside %.3f, whole %.3f\n",
               name[i], row[i]->energy, row[i]->iou, row[i]->rel_in, row[i]->rel_all);
    printf("# the issue's targets with ispm_bounces=3: energy within 0.85..1.15 %s, IoU >= 0.7 %s\n",
           fabs(dens.energy - 1.0) < 0.15 ? "met" : "NOT met",
           fmax(fmax(chains.iou, dens.iou), foot.iou) >= 0.7 ? "met" : "NOT met (known gap)");
    assert_true(one.energy < 0.7);
    assert_true(fabs(chains.energy - 1.0) < 0.15 && fabs(dens.energy - 1.0) < 0.15);
    assert_true(chains.rel_in < one.rel_in && chains.rel_all < one.rel_all);
    assert_true(chains.iou > chains_flat.iou && chains.rel_in < chains_flat.rel_in);
    assert_true(dens.iou > dens_flat.iou && dens.rel_in < dens_flat.rel_in);
    assert_true(chains.iou > 0.5 && dens.iou > 0.62 && foot.iou > 0.69);
    /* the footprint ellipses: the energy target, and the least error in and out of the mask */
    assert_true(fabs(foot.energy - 1.0) < 0.15);
    assert_true(foot.rel_in < fmin(chains.rel_in, dens.rel_in) && foot.rel_all < fmin(chains.rel_all, dens.rel_all));
    /* the density radius: sharper cusps and less noise where the ring spreads its light (whole
       image 0.365 against 0.392), the energy the same */
    assert_true(dens.iou > chains.iou && dens.rel_all < chains.rel_all);
}

/* rel. RMSE inside the mask at each budget level of the photons (trace 256², full-resolution
   splats, ispm_bounces=3; the seed's disks and the footprint ellipses) and of the splat resolution
   (65536 photons), against the full caustic. */
static void test_budget_error_table(void **state)
{
    (void)state;
    const char *photons[4] = {"1024", "4096", "16384", "65536"};
    const char *splat[3] = {"0.25", "0.5", "1"};
    double ep[4], ef[4], es[3];
    char b[160];
    for (int i = 0; i < 4; i++) {
        ruler r, foot;
        snprintf(b, sizeof b, "ispm_photons=%s,ispm_trace=256,ispm_splat=1,ispm_bounces=3", photons[i]);
        measure(b, NULL, REF_PATH, MASK_PATH, &r);
        const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
        printf("# budget ispm_photons=%-5s (%5u emitted, level %u): rel. RMSE inside the mask %.3f, whole image %.3f, energy %.3f\n",
               photons[i], st->photons, st->level, r.rel_in, r.rel_all, r.energy);
        ep[i] = r.rel_in;
        /* the same with the footprint ellipses */
        snprintf(b, sizeof b, "ispm_photons=%s,ispm_trace=256,ispm_splat=1,ispm_bounces=3,ispm_radius=footprint", photons[i]);
        measure(b, NULL, REF_PATH, MASK_PATH, &foot);
        printf("#   with ispm_radius=footprint: rel. RMSE inside the mask %.3f, whole image %.3f, energy %.3f\n", foot.rel_in,
               foot.rel_all, foot.energy);
        ef[i] = foot.rel_in;
    }
    for (int i = 0; i < 3; i++) {
        ruler r;
        snprintf(b, sizeof b, "ispm_photons=65536,ispm_trace=256,ispm_splat=%s,ispm_bounces=3", splat[i]);
        measure(b, NULL, REF_PATH, MASK_PATH, &r);
        printf("# budget ispm_splat=%-4s: rel. RMSE inside the mask %.3f, whole image %.3f, energy %.3f\n", splat[i], r.rel_in,
               r.rel_all, r.energy);
        es[i] = r.rel_in;
    }
    /* the error falls as photons rise and as the splats get finer (each step measured lower) */
    for (int i = 1; i < 4; i++)
        assert_true(ep[i] < ep[i - 1] && ef[i] < ef[i - 1]);
    for (int i = 1; i < 3; i++)
        assert_true(es[i] < es[i - 1]);
}

/* The last frame's photons and their hits (allocated; the caller frees both); the photon count. */
static int read_photons_and_hits(gk_ispm_photon **p, gk_ispm_hit **h)
{
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    *p = calloc((size_t)st->capacity, sizeof **p);
    *h = calloc((size_t)st->capacity, sizeof **h);
    int np = gk_ispm_read_photons(H.self, *p, st->capacity);
    assert_true(np > 0);
    gk_ispm_read_hits(H.self, *h, st->capacity);
    return np;
}

/* The trace against the reference tracer's own intersections (BVH, app/ref) of the same photons:
   where each photon's ray first meets the scene, and whether the trace found that. Fractions of
   the reflected photon power: hits over 3 cm from the true first hit on a diffuse surface; true
   first hit a mirror but the trace's over 3 cm away (through the wall); true first hit in the
   frustum but none found. */
static void trace_accuracy(const gk_ref_scene *rs, double frac[3])
{
    gk_ispm_photon *p;
    gk_ispm_hit *h;
    int np = read_photons_and_hits(&p, &h);
    double total = 0, bad[3] = {0, 0, 0};
    for (int i = 0; i < np; i++) {
        if (p[i].org[3] < 0.5f)
            continue;
        vec3 o = v3(p[i].org[0], p[i].org[1], p[i].org[2]), d = v3_norm(v3(p[i].dir[0], p[i].dir[1], p[i].dir[2]));
        double pw = p[i].pow_d1[0] + p[i].pow_d1[1] + p[i].pow_d1[2];
        total += pw;
        gk_scene_hit sh;
        if (!gk_scene_intersect(rs, v3_add(o, v3_scale(d, 1e-3f)), d, INFINITY, &sh))
            continue;
        vec3 a = v3_add(o, v3_scale(d, sh.t + 1e-3f));
        bool found = h[i].pos_valid[3] > 0.5f;
        bool off = found && v3_len(v3_sub(a, v3(h[i].pos_valid[0], h[i].pos_valid[1], h[i].pos_valid[2]))) > 0.03f;
        bool mirror = gk_ref_material_may_be_delta(&S->materials[rs->tris[sh.tri].material]);
        vec4 c = m4_vec4(H.vp, (vec4){a.x, a.y, a.z, 1.0f});
        bool in_view = c.w > 0 && fabsf(c.x) < c.w && fabsf(c.y) < c.w && fabsf(c.z) < c.w;
        if (off && !mirror)
            bad[0] += pw;
        else if (off && mirror)
            bad[1] += pw;
        else if (!found && in_view)
            bad[2] += pw;
    }
    for (int k = 0; k < 3; k++)
        frac[k] = bad[k] / total;
    free(p);
    free(h);
}

static void seed_hit_test(gk_ispm_debug *d) { d->faithful_hit = true; }

/* The specular chains (ispm_bounces=3) against the tracer's: each reflected photon followed through
   the reference scene (BVH, the mirror's shading normal, perfect reflection as the ring's roughness
   0 makes it) for at most three specular vertices in all, as trace.comp counts them, to its diffuse
   hit. off[k]: the fraction of the power of the photons whose true path has k specular vertices
   (k = 2, 3) that ispm lands over 3 cm from the tracer's point (or not at all while it lies in view). */
/* Where the tracer takes photon p: through the reference scene (BVH, the mirror's shading normal,
   perfect reflection as the ring's roughness 0 makes it) for at most three specular vertices in all,
   as trace.comp counts them; true when it ends on a diffuse surface in view, at *at after *k
   specular vertices. */
static bool true_landing(const gk_ref_scene *rs, const gk_ispm_photon *p, vec3 *at, int *k)
{
    vec3 o = v3(p->org[0], p->org[1], p->org[2]), d = v3_norm(v3(p->dir[0], p->dir[1], p->dir[2]));
    *k = 1;
    for (;;) {
        gk_scene_hit sh;
        if (!gk_scene_intersect(rs, v3_add(o, v3_scale(d, 1e-4f)), d, INFINITY, &sh))
            return false;
        const gk_ref_tri *t = &rs->tris[sh.tri];
        o = v3_add(o, v3_scale(d, sh.t + 1e-4f));
        if (!gk_ref_material_may_be_delta(&S->materials[t->material]))
            break;
        if (*k == 3)
            return false;   /* a fourth specular vertex: beyond ispm_bounces=3 */
        gk_surface sf;
        gk_surface_init(&sf, rs, t, sh.b1, sh.b2);
        d = v3_sub(d, v3_scale(sf.n, 2.0f * v3_dot(d, sf.n)));
        (*k)++;
    }
    *at = o;
    vec4 c = m4_vec4(H.vp, (vec4){o.x, o.y, o.z, 1.0f});
    return c.w > 0 && fabsf(c.x) < c.w && fabsf(c.y) < c.w && fabsf(c.z) < c.w;
}

/* The specular chains (ispm_bounces=3) against the tracer's: each reflected photon followed by
   true_landing to its diffuse hit. off[k]: the fraction of the power of the photons whose true path
   has k specular vertices (k = 2, 3) that ispm lands over 3 cm from the tracer's point (or not at
   all while it lies in view). */
static void chain_accuracy(const gk_ref_scene *rs, double off[4])
{
    gk_ispm_photon *p;
    gk_ispm_hit *h;
    int np = read_photons_and_hits(&p, &h);
    double total[4] = {0}, bad[4] = {0};
    for (int i = 0; i < np; i++) {
        vec3 o;
        int k;
        if (p[i].org[3] < 0.5f || !true_landing(rs, &p[i], &o, &k))
            continue;
        double pw = p[i].pow_d1[0] + p[i].pow_d1[1] + p[i].pow_d1[2];
        bool found = h[i].pos_valid[3] > 0.5f;
        total[k] += pw;
        if (!found || v3_len(v3_sub(o, v3(h[i].pos_valid[0], h[i].pos_valid[1], h[i].pos_valid[2]))) > 0.03f)
            bad[k] += pw;
    }
    for (int k = 0; k < 4; k++)
        off[k] = total[k] > 0 ? bad[k] / total[k] : 0;
    free(p);
    free(h);
}

/* Whether world point x lands within r pixels (Chebyshev) of pixel (px, py) of the references
   (top row first). */
static bool near_pixel(vec3 x, int px, int py, int r)
{
    vec4 c = m4_vec4(H.vp, (vec4){x.x, x.y, x.z, 1.0f});
    if (c.w <= 0)
        return false;
    double sx = (c.x / c.w * 0.5 + 0.5) * W, sy = (1.0 - (c.y / c.w * 0.5 + 0.5)) * HH;
    return fabs(sx - (px + 0.5)) <= r + 0.5 && fabs(sy - (py + 0.5)) <= r + 0.5;
}

/* The full caustic's peak (the cusp inside the ring, where the two-mirror chains focus) gets the
   photon power it should: the power of ispm's hits within 1 and 2 pixels of the reference's peak
   pixel against the power the tracer's own paths of the same photons (true_landing) bring there.
   Measured 0.987 and 0.994 (density radius, ispm_bounces=3): what the splats then make of that
   power decides the caustic's peak, and with it the mask IoU (test_reference_mask). Bound 3%. */
static void test_cusp_power_against_the_tracer(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_image ref = {0};
    assert_int_equal(gk_image_read(REF_PATH, &ref, &e), 0);
    int peak = 0;
    for (int i = 0; i < W * HH; i++)
        if (ih_lum(&ref.pixels[i * ref.channels]) > ih_lum(&ref.pixels[peak * ref.channels]))
            peak = i;
    gk_image_free(&ref);
    gk_ref_scene rs;
    assert_int_equal(gk_ref_scene_build(&rs, S, H.view, H.proj, H.eye, W, HH, &e), 0);
    assert_int_equal(ih_budget(&H, RICH ",ispm_bounces=3,ispm_radius=density"), 0);
    ih_debug(&H, NULL);
    assert_int_equal(ih_frame(&H), 0);
    gk_ispm_photon *p;
    gk_ispm_hit *h;
    int np = read_photons_and_hits(&p, &h);
    for (int r = 1; r <= 2; r++) {
        double traced = 0, ours = 0;
        for (int i = 0; i < np; i++) {
            if (p[i].org[3] < 0.5f)
                continue;
            vec3 o;
            int k;
            if (true_landing(&rs, &p[i], &o, &k) && near_pixel(o, peak % W, peak / W, r))
                traced += p[i].pow_d1[1];
            if (h[i].pos_valid[3] > 0.5f && near_pixel(v3(h[i].pos_valid[0], h[i].pos_valid[1], h[i].pos_valid[2]),
                                                       peak % W, peak / W, r))
                ours += p[i].pow_d1[1];
        }
        printf("# within %d px of the reference's peak (%d, %d): hit power %.5f, the tracer's paths %.5f (ratio %.3f)\n",
               r, peak % W, peak / W, ours, traced, ours / traced);
        assert_true(traced > 0 && fabs(ours / traced - 1.0) < 0.03);
    }
    free(p);
    free(h);
    gk_ref_scene_free(&rs);
}

/* The further specular bounces reflect about the normal at the hit (the node's normal turned by its
   shape operator), not about the normal at the node's pixel centre (flat_mirror_normal), at both
   trace resolutions that matter: the pixel footprint on the curved ring is what the flat normal
   gets wrong, so its error doubles as the resolution halves. */
static void test_chains_against_the_tracer(void **state)
{
    (void)state;
    gk_ref_scene rs;
    gk_err e = {0};
    assert_int_equal(gk_ref_scene_build(&rs, S, H.view, H.proj, H.eye, W, HH, &e), 0);
    double shape[2][4], flat[2][4];
    const char *budget[2] = {RICH ",ispm_bounces=3", "ispm_photons=65536,ispm_trace=128,ispm_splat=1,ispm_bounces=3"};
    for (int r = 0; r < 2; r++) {
        assert_int_equal(ih_budget(&H, budget[r]), 0);
        ih_debug(&H, NULL);
        assert_int_equal(ih_frame(&H), 0);
        chain_accuracy(&rs, shape[r]);
        ih_debug(&H, flat_mirror_normal);
        assert_int_equal(ih_frame(&H), 0);
        chain_accuracy(&rs, flat[r]);
        printf("# chains vs the tracer at ispm_trace=%d (power landing > 3 cm off or missed): 2 specular vertices %.3f "
               "(flat normal %.3f), 3: %.3f (flat %.3f)\n", r ? 128 : 256, shape[r][2], flat[r][2], shape[r][3], flat[r][3]);
    }
    /* tier B: the peeled layers carry the shape operator too, but four layers miss what lies deeper
       (L8), which the chains inside the ring need */
    double peel[4];
    assert_int_equal(ih_budget(&H, RICH ",ispm_bounces=3,ispm_tier=peel"), 0);
    ih_debug(&H, NULL);
    assert_int_equal(ih_frame(&H), 0);
    chain_accuracy(&rs, peel);
    printf("# chains vs the tracer, tier B (4 layers) at 256²: 2 specular vertices %.3f, 3: %.3f\n", peel[2], peel[3]);
    gk_ref_scene_free(&rs);
    /* measured at 256²: 0.045 (flat 0.151) and 0.094 (0.249); at 128²: 0.049 (0.300) and 0.110 (0.453);
       tier B 0.620 and 0.802 (flat normal 0.638, 0.823: by hand).
       Bounds: two vertices within 6% and three within 12% at both resolutions (what remains lands on
       another surface, 0.5 m off on average: an edge-on wall pixel's plane); the flat normal at
       least twice as far off in each; tier B worse than the lists (L8) */
    for (int r = 0; r < 2; r++) {
        assert_true(shape[r][2] < 0.06 && shape[r][3] < 0.12);
        assert_true(flat[r][2] > 2.0 * shape[r][2] && flat[r][3] > 2.0 * shape[r][3]);
    }
    assert_true(peel[2] > shape[0][2] && peel[3] > shape[0][3]);
}

static void test_trace_against_the_tracer(void **state)
{
    (void)state;
    gk_ref_scene rs;
    gk_err e = {0};
    assert_int_equal(gk_ref_scene_build(&rs, S, H.view, H.proj, H.eye, W, HH, &e), 0);
    assert_int_equal(ih_budget(&H, RICH), 0);
    double plane[3], seed[3];
    ih_debug(&H, NULL);
    assert_int_equal(ih_frame(&H), 0);
    trace_accuracy(&rs, plane);
    ih_debug(&H, seed_hit_test);
    assert_int_equal(ih_frame(&H), 0);
    trace_accuracy(&rs, seed);
    ih_debug(&H, NULL);
    gk_ref_scene_free(&rs);
    printf("# trace vs the tracer's intersections (fractions of the photon power): off > 3 cm %.4f, through a mirror "
           "%.4f, missed in view %.4f; the seed's depth test %.4f, %.4f, %.4f\n", plane[0], plane[1], plane[2], seed[0],
           seed[1], seed[2]);
    /* measured: plane test 0.0003, 0.0087, 0.0020; the seed's test alone 0.266 (it takes the ring's
       other wall and facets near the origin), 0.055, 0.009 (the previous default, the seed's test
       with a reach test: 0.021, 0.047, 0.078). Bounds: 1%, 2% and 1% for the plane test; the seed's
       test worse in each */
    assert_true(plane[0] < 0.01 && plane[1] < 0.02 && plane[2] < 0.01);
    for (int k = 0; k < 3; k++)
        assert_true(seed[k] > plane[k]);
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
    /* research A.6 item 6: < 1% with the rule (measured 0.0009 with the plane hit test, 0.0069 with the depth test), a large fraction without it
       (measured 0.61: the photon's own wall is hit at once) */
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
    /* by block only the order of the float additions changes (measured 2.2e-7); by index each
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
        assert_true(q > 1.6 && q < 2.6);   /* the research's bound (the seed: ×1.9–2.5); measured 1.82–1.85, R² 0.9979 (1.90–1.93 with the depth test) */
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trace_against_the_tracer), cmocka_unit_test(test_chains_against_the_tracer),
        cmocka_unit_test(test_single_bounce_against_its_reference), cmocka_unit_test(test_reference_mask),
        cmocka_unit_test(test_cusp_power_against_the_tracer),
        cmocka_unit_test(test_budget_error_table),
        cmocka_unit_test(test_l9_self_intersection), cmocka_unit_test(test_l13_flicker),
        cmocka_unit_test(test_l19_cost_fit),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
