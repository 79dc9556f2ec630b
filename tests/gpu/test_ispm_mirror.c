/* ispm on a scene whose caustic is known exactly: a square plane mirror (0.4 m, white metal,
 * roughness 0, facing down at y = 1) over a grey floor, a 10 cd point light below it at
 * (-0.6, 0.5, 0). The mirror image of the light is at (-0.6, 1.5, 0); every reflected ray lands on
 * the floor in x ∈ [0.6, 1.8], z ∈ [-0.6, 0.6]. A camera 2 m above (1.2, 0, 0) looks straight down
 * (40° vertical field, 160×120): the floor maps linearly to pixels and the mirror is off-screen.
 * What the light sends into the mirror, Φ = I ∫ cosθ/r² dA, is integrated on the CPU (400² cells);
 * the mirror reflects all of it (F0 = 1) onto the floor.
 * Tests: photon power = Φ; every photon lands; L15 kernel energy (Σ E·area of one frame's splats
 * against the power its hits carry); end-to-end energy of the composed image; L12 continuity over
 * the photon budget; L3 energy at the screen edge against the analytic in-view fraction; L2 an
 * off-screen blocker (the failure: it is absent from the lists) and an on-screen one (caught). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "test_ispm_harness.h"

#define W 160
#define HH 120
#define FOV_DEG 40.0f
#define CAM_H 2.0f
static const float I_CD = 10.0f, MIRROR_Y = 1.0f, MIRROR_HALF = 0.2f;
static const vec3 LIGHT = {-0.6f, 0.5f, 0.0f};

static gkt_scene T;
static ispm_h H;
static int plate_node = -1;

/* Φ = I ∫_mirror cosθ / r² dA (cosθ at the mirror, whose normal is -y). */
static double mirror_power(void)
{
    const int n = 400;
    double cell = 2.0 * MIRROR_HALF / n, sum = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double x = -MIRROR_HALF + (i + 0.5) * cell, z = -MIRROR_HALF + (j + 0.5) * cell;
            double dx = x - LIGHT.x, dy = MIRROR_Y - LIGHT.y, dz = z - LIGHT.z, r2 = dx * dx + dy * dy + dz * dz;
            sum += dy / sqrt(r2) / r2 * cell * cell;
        }
    return I_CD * sum;
}

/* The fraction of Φ whose reflected ray lands on the floor inside the camera's view at offset dx. */
static double in_view_fraction(float cam_x)
{
    const int n = 400;
    double cell = 2.0 * MIRROR_HALF / n, in = 0, all = 0;
    double hw = CAM_H * tan(FOV_DEG * M_PI / 360.0) * W / HH, hz = CAM_H * tan(FOV_DEG * M_PI / 360.0);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double x = -MIRROR_HALF + (i + 0.5) * cell, z = -MIRROR_HALF + (j + 0.5) * cell;
            double dx = x - LIGHT.x, dy = MIRROR_Y - LIGHT.y, dz = z - LIGHT.z, r2 = dx * dx + dy * dy + dz * dz;
            double w = dy / sqrt(r2) / r2;
            /* from the image light (-0.6, 1.5, 0) through (x, 1, z) down to y = 0: 3× the offset */
            double fx = LIGHT.x + (x - LIGHT.x) * 3.0, fz = z * 3.0;
            all += w;
            if (fabs(fx - cam_x) < hw && fabs(fz) < hz)
                in += w;
        }
    return in / all;
}

static void build(gkt_scene *t, int plate) /* plate: 0 none, 1 off-screen, 2 on-screen */
{
    gkt_scene_init(t, "ispm-mirror");
    /* Lambertian receivers (specularFactor 0): the energy checks below divide by rho/pi */
    int grey = gkt_material_lambert(t, v3(0.75f, 0.75f, 0.75f)), mirror = gkt_material(t, v3(1, 1, 1), 1, 0),
        dark = gkt_material_lambert(t, v3(0.5f, 0.1f, 0.1f));
    gkt_quad(t, v3(-3, 0, -3), v3(3, 0, -3), v3(3, 0, 3), v3(-3, 0, 3), v3(0, 1, 0), grey);
    float m = MIRROR_HALF;
    gkt_quad(t, v3(-m, MIRROR_Y, -m), v3(m, MIRROR_Y, -m), v3(m, MIRROR_Y, m), v3(-m, MIRROR_Y, m), v3(0, -1, 0), mirror);
    /* off-screen: at y = 0.8 every reflected ray crosses x ∈ [-0.04, 0.52] (the view starts at
       x = 0.62 there) and every incoming one x ≤ -0.12; on-screen: at y = 0.3 they cross
       x ∈ [0.36, 1.32], the view starts at 0.38 */
    plate_node = -1;
    if (plate == 1)
        plate_node = gkt_quad(t, v3(-0.05f, 0.8f, -0.5f), v3(0.6f, 0.8f, -0.5f), v3(0.6f, 0.8f, 0.5f), v3(-0.05f, 0.8f, 0.5f),
                              v3(0, 1, 0), dark);
    if (plate == 2)
        plate_node = gkt_quad(t, v3(0.3f, 0.3f, -0.6f), v3(1.4f, 0.3f, -0.6f), v3(1.4f, 0.3f, 0.6f), v3(0.3f, 0.3f, 0.6f),
                              v3(0, 1, 0), dark);
    gkt_light(t, GK_LIGHT_POINT, GK_SHAPE_POINT, I_CD, LIGHT, v3(1, 1, 0));
    gkt_camera(t, v3(1.2f, CAM_H, 0), v3(1.2f, 0, 0), FOV_DEG * (float)M_PI / 180.0f);
    gkt_scene_bounds(t);
}

static void move_camera(float x)
{
    T.nodes[T.s.camera_node].translation = v3(x, CAM_H, 0);
    assert_int_equal(ih_gbuffer(&H), 0);
}

static int setup(void **state)
{
    (void)state;
    build(&T, 0);
    return ih_open_built(&H, &T, W, HH);
}

static int teardown(void **state)
{
    (void)state;
    ih_close_built(&H, &T);
    return 0;
}

/* floor area of one splat pixel: the camera looks straight down, so pixels map linearly */
static double splat_pixel_area(void)
{
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    double hz = CAM_H * tan(FOV_DEG * M_PI / 360.0);
    double px = 2.0 * hz / st->splat_h;
    return px * px;
}

static double splat_energy(void)
{
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    int n = st->splat_w * st->splat_h;
    float *e = malloc((size_t)n * 4 * sizeof(float));
    assert_int_equal(gk_ispm_read_splat(H.self, e, n * 4), n * 4);
    double sum = 0;
    for (int i = 0; i < n; i++)
        sum += e[i * 4 + 1];   /* white light, white mirror: the channels agree */
    free(e);
    return sum * splat_pixel_area();
}

/* Σ of the power the valid hits carry (green), those on the floor (y < 0.1: the plates are at 0.3
   and 0.8) when floor_only */
static double hit_power(bool floor_only, int *count)
{
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    gk_ispm_hit *h = malloc((size_t)st->capacity * sizeof *h);
    int n = gk_ispm_read_hits(H.self, h, st->capacity);
    double sum = 0;
    int c = 0;
    for (int i = 0; i < n; i++)
        if (h[i].pos_valid[3] > 0.5f && (!floor_only || h[i].pos_valid[1] < 0.1f))
            sum += h[i].pow_dist[1], c++;
    free(h);
    if (count)
        *count = c;
    return sum;
}

static void test_photon_power(void **state)
{
    (void)state;
    assert_int_equal(ih_budget(&H, "ispm_photons=16384"), 0);
    assert_int_equal(ih_frame(&H), 0);
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    gk_ispm_photon *p = malloc((size_t)st->capacity * sizeof *p);
    int n = gk_ispm_read_photons(H.self, p, st->capacity);
    double sum = 0;
    for (int i = 0; i < n; i++)
        if (p[i].org[3] > 0.5f)
            sum += p[i].pow_d1[1];
    free(p);
    double phi = mirror_power();
    printf("# mirror: M = %u specular texels, level %u, %u photons, %u reflected, Σ power %.5f W vs Φ = %.5f W "
           "(ratio %.4f)\n", st->specular_texels, st->level, st->photons, st->reflected, sum, phi, sum / phi);
    /* The mirror is a full rectangle in the RSM; texels on its outline count whole when their centre
       is on it. Measured ratio 1.0009 at 16384 photons (level 1, 4764 photons); bound 1%. */
    assert_true(fabs(sum / phi - 1.0) < 0.01);
    assert_int_equal(st->reflected, st->photons);   /* white mirror: P_s = 1, nothing absorbed */
    /* every reflected ray meets the floor in view */
    int c = 0;
    double landed = hit_power(true, &c);
    printf("# hits on the floor: %d of %u, power %.5f W (%.4f of the emitted)\n", c, st->reflected, landed, landed / sum);
    assert_int_equal(c, (int)st->reflected);
}

static void test_l15_kernel_energy(void **state)
{
    (void)state;
    assert_int_equal(ih_budget(&H, "ispm_photons=4096"), 0);
    double ratio[2];
    for (int faithful = 0; faithful < 2; faithful++) {
        gk_ispm_debug d;
        gk_ispm_default_debug(&d);
        d.caustics_only = d.measure = true, d.faithful_kernel = faithful;
        gk_ispm_set_debug(H.self, &d);
        assert_int_equal(ih_frame(&H), 0);
        ratio[faithful] = splat_energy() / hit_power(false, NULL);
    }
    ih_debug(&H, NULL);
    double seed = 2 * 0.25 * (1 - exp(-1 / (2 * 0.25)));
    printf("# L15 Σ E·area / Σ Φ: normalised kernel %.4f, the seed's 1/(πh²) %.4f (analytic %.4f)\n", ratio[0], ratio[1],
           seed);
    /* the bound: a splat deposits Φ ± 2% (measured 1.0029 on this view at splat 0.5; the
       seed's normalisation 0.4336 against the analytic 0.4323) */
    assert_true(fabs(ratio[0] - 1.0) < 0.02);
    assert_true(fabs(ratio[1] / seed - 1.0) < 0.02);
    /* ispm_radius=footprint: its ellipses, and the same shrunk to their least size (C0 = 0.05: every
       semi-axis h_pixels kernel samples, 0.375 splat pixels as the camera sees it), which deposit
       their Φ only because the kernel is averaged over the pixel (4x4 points); point-sampled at the
       pixel centre (pixel_samples = 1, h_pixels 0.375 for the same size) such splats fall between
       the centres or on them. Measured 1.0001 and 0.9963 (bound 2%); point-sampled 1.2130. */
    assert_int_equal(ih_budget(&H, "ispm_photons=4096,ispm_radius=footprint"), 0);
    const float c0[3] = {1.5f, 0.05f, 0.05f};
    const int samples[3] = {4, 4, 1};
    const float least[3] = {1.5f, 1.5f, 0.375f};
    double foot[3];
    for (int k = 0; k < 3; k++) {
        gk_ispm_debug d;
        gk_ispm_default_debug(&d);
        d.caustics_only = d.measure = true, d.c0 = c0[k], d.pixel_samples = samples[k], d.h_pixels = least[k];
        gk_ispm_set_debug(H.self, &d);
        assert_int_equal(ih_frame(&H), 0);
        foot[k] = splat_energy() / hit_power(false, NULL);
    }
    ih_debug(&H, NULL);
    printf("# L15 footprint ellipses Σ E·area / Σ Φ: %.4f; least size, kernel averaged over 4x4 points %.4f, at the "
           "pixel centre %.4f\n", foot[0], foot[1], foot[2]);
    assert_true(fabs(foot[0] - 1.0) < 0.02 && fabs(foot[1] - 1.0) < 0.02);
    assert_true(fabs(foot[2] - 1.0) > 0.02);
}

/* The composed image: L = ρ/π·E on the floor, so Σ L·π/ρ·area is the power that reached the view. */
static void test_end_to_end_energy(void **state)
{
    (void)state;
    /* the seed's splat radius, the radius from the hits' density and the ellipses from the photons'
       neighbours (ispm_radius=density, footprint: other splat shapes, each still normalised to
       deposit its Φ) */
    const char *budget[3] = {"ispm_photons=16384", "ispm_photons=16384,ispm_radius=density",
                             "ispm_photons=16384,ispm_radius=footprint"};
    for (int k = 0; k < 3; k++) {
        assert_int_equal(ih_budget(&H, budget[k]), 0);
        assert_int_equal(ih_frame(&H), 0);
        double hz = CAM_H * tan(FOV_DEG * M_PI / 360.0), px = 2.0 * hz / HH, sum = 0;
        for (int i = 0; i < W * HH; i++)
            sum += H.img[i * 4 + 1] * M_PI / 0.75;
        sum *= px * px;
        double phi = mirror_power();
        printf("# end to end, %s: Σ L·π/ρ·area %.5f W vs Φ %.5f W (ratio %.4f)\n", budget[k], sum, phi, sum / phi);
        /* bilateral upsampling renormalises its weights, so energy moves but is not created;
           measured ratio 0.9955 (seed radius), 0.9992 (density radius) and 0.9988 (footprint), bound 2% */
        assert_true(fabs(sum / phi - 1.0) < 0.02);
    }
}

static void test_l12_budget_continuity(void **state)
{
    (void)state;
    const char *b[4] = {"ispm_photons=1024", "ispm_photons=4096", "ispm_photons=16384", "ispm_photons=65536"};
    double e[2][4];
    unsigned n[2][4];
    for (int faithful = 0; faithful < 2; faithful++)
        for (int i = 0; i < 4; i++) {
            gk_ispm_debug d;
            gk_ispm_default_debug(&d);
            d.caustics_only = d.measure = true, d.faithful_blocks = faithful;
            gk_ispm_set_debug(H.self, &d);
            assert_int_equal(ih_budget(&H, b[i]), 0);
            assert_int_equal(ih_frame(&H), 0);
            e[faithful][i] = splat_energy();
            n[faithful][i] = gk_ispm_get_stats(H.self)->photons;
        }
    ih_debug(&H, NULL);
    double phi = mirror_power();
    for (int faithful = 0; faithful < 2; faithful++)
        printf("# L12 %s: photons %u/%u/%u/%u, energy/Φ %.4f %.4f %.4f %.4f\n", faithful ? "seed's full blocks" : "block power",
               n[faithful][0], n[faithful][1], n[faithful][2], n[faithful][3], e[faithful][0] / phi, e[faithful][1] / phi,
               e[faithful][2] / phi, e[faithful][3] / phi);
    for (int i = 0; i < 3; i++) {
        /* the count steps ~×4 with the level */
        double r = (double)n[0][i + 1] / n[0][i];
        assert_true(r > 3.0 && r < 5.0);
        /* research A.6 item 4 asks 5%; measured steps ≤ 0.8% (energy/Φ 1.0003 1.0038 0.9975
           1.0011), bound 2% */
        assert_true(fabs(e[0][i + 1] / e[0][i] - 1.0) < 0.02);
    }
    /* the seed's full-block rule drops the partly covered blocks of the mirror's outline: measured
       0.9045 of Φ at 1024 photons; the signature asserted is a loss over 5% there */
    assert_true(e[1][0] / phi < 0.95);
}

/* L3: the camera pans so the caustic leaves the image; the splatted energy should follow the part of
   the caustic still in view (computed from the geometry), not fall off before it. */
static void test_l3_edge_energy(void **state)
{
    (void)state;
    assert_int_equal(ih_budget(&H, "ispm_photons=16384"), 0);
    const float pans[5] = {0.0f, 0.5f, 1.0f, 1.5f, 2.0f};
    double worst = 0;
    for (int i = 0; i < 5; i++) {
        move_camera(1.2f + pans[i]);
        assert_int_equal(ih_frame(&H), 0);
        double got = splat_energy() / mirror_power(), want = in_view_fraction(1.2f + pans[i]);
        printf("# L3 pan %.1f m: splatted %.4f of Φ, in view %.4f\n", pans[i], got, want);
        worst = fmax(worst, fabs(got - want));
    }
    move_camera(1.2f);
    /* disks at the edge lose their off-screen part, hits off-screen are lost whole; measured worst
       difference 0.0047 of Φ (0.0086 with the depth hit test) (splats reaching in from just off-screen hits), bound 0.02 */
    printf("# L3 worst |splatted - in view| = %.4f of Φ\n", worst);
    assert_true(worst < 0.02);
}

/* L2: the lists hold only what is in the camera's frustum. */
static void test_l2_offscreen_blocker(void **state)
{
    (void)state;
    assert_int_equal(ih_budget(&H, "ispm_photons=16384"), 0);
    double base = 0, with[3] = {0};
    for (int plate = 0; plate < 3; plate++) {
        ih_close(&H);
        gkt_scene_free(&T);
        build(&T, plate);
        assert_int_equal(ih_open(&H, &T.s, W, HH), 0);
        ih_debug(&H, NULL);
        assert_int_equal(ih_budget(&H, "ispm_photons=16384"), 0);
        assert_int_equal(ih_frame(&H), 0);
        with[plate] = hit_power(true, NULL);
        if (plate == 0)
            base = with[0];
    }
    printf("# L2 floor caustic power: no plate %.5f W, off-screen plate %.5f W (%.3f; the reference: 0), "
           "on-screen plate %.5f W (%.3f)\n", base, with[1], with[1] / base, with[2], with[2] / base);
    /* the failure as the research describes it: the off-screen plate is missing from the lists and
       the caustic comes through whole (measured 1.000) */
    assert_true(with[1] / base > 0.95);
    /* on screen the plate catches it (measured 0.000; rays through its off-screen sliver x < 0.38
       meet the plate's on-screen part first), bound 0.02 */
    assert_true(with[2] / base < 0.02);
    ih_close(&H);
    gkt_scene_free(&T);
    build(&T, 0);
    assert_int_equal(ih_open(&H, &T.s, W, HH), 0);
    ih_debug(&H, NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_photon_power),
        cmocka_unit_test(test_l15_kernel_energy),
        cmocka_unit_test(test_end_to_end_energy),
        cmocka_unit_test(test_l12_budget_continuity),
        cmocka_unit_test(test_l3_edge_energy),
        cmocka_unit_test(test_l2_offscreen_blocker),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
