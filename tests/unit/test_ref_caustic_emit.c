/* Caustic photons aimed at the delta surfaces (app/ref/caustic_emit.h) against exact answers:
 *   - a small flat mirror over a point light: the floor's caustic is the mirror-image light seen
 *     through the mirror's aperture, in closed form per pixel, and its total power on the floor is
 *     I x (solid angle of the mirror from the light) x reflectance, from geometry alone;
 *   - the guided and the light's own emission agree within noise (both unbiased), and guided is
 *     less noisy for the same photon count;
 *   - a spot light's cone: partly over the mirror both agree; turned away, no caustic photon at all;
 *   - the target spheres hold every delta vertex; 1 and 2 threads give identical images;
 *   - the noise floor restricted to a mask that selects everything is the whole image's. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "ref/caustic_emit.h"
#include "ref/render.h"
#include "test_ref_scenes.h"

#define W 64
#define MIRROR_Y 2.0f
#define HALF 0.25f   /* the mirror is 2 HALF x 2 HALF, centred over the light */
#define I_CD 10.0f
#define F0 0.8f      /* mirror reflectance: Schlick's (1 - cos)^5 term is < 1e-6 at these angles */

static void render_seeded(const gk_ref_scene *rs, int spp, int emit, int threads, uint64_t seed, gk_ref_result *r)
{
    gk_ref_options o;
    gk_ref_options_default(&o);
    o.spp = spp;
    o.paths = GK_PATH_CAUSTICS;
    o.seed = seed;
    o.threads = threads;
    o.caustic_emit = emit;
    gk_err e = {0};
    assert_int_equal(gk_ref_render(rs, &o, r, &e), 0);
}

static void render_with(const gk_ref_scene *rs, int spp, int emit, int threads, gk_ref_result *r)
{
    render_seeded(rs, spp, emit, threads, 3, r);
}

/* Point light at (0, 1, 0) under a 0.5 m square mirror at y = 2 facing down; a large floor. The
   mirror-image light is at (0, 3, 0); it lights the floor square |x|, |z| <= 0.75. */
static gk_light *build_small_mirror(test_scene *t, vec3 lp, enum gk_light_type type, vec3 axis)
{
    ts_init(t);
    int floor_m = ts_material(t, 0.5f, 0.5f, 0.5f, 0.0f, 0.6f);
    int mirror = ts_material(t, F0, F0, F0, 1.0f, 0.0f);
    ts_quad(t, v3(-10, 0, -10), v3(0, 0, 20), v3(20, 0, 0), floor_m);
    ts_quad(t, v3(-HALF, MIRROR_Y, -HALF), v3(2 * HALF, 0, 0), v3(0, 0, 2 * HALF), mirror);
    t->eye = v3(0, 1.5f, 2.5f);
    t->target = v3(0, 0, 0);
    return ts_light(t, type, lp, axis, v3(1, 0, 0), I_CD);
}

typedef struct pixel_geom {
    vec3 p;          /* floor point seen through the pixel centre */
    double area;     /* floor area of the pixel's footprint */
    double expect;   /* closed-form caustic radiance (0 outside the lit square) */
    double f;        /* BRDF towards the image light (for the power) */
    int margin_ok;   /* farther than 2 footprints from the lit square's edge */
} pixel_geom;

static void pixel_geometry(const gk_ref_scene *rs, int x, int y, vec3 img, pixel_geom *g)
{
    vec3 d = gk_ref_camera_dir(rs, x + 0.5f, y + 0.5f);
    float t = -rs->eye.y / d.y;
    g->p = v3_add(rs->eye, v3_scale(d, t));
    float cos_cam = v3_dot(d, rs->fwd), cos_x = fabsf(d.y);
    double a_pix = (2.0 * rs->tan_x / rs->width) * (2.0 * rs->tan_y / rs->height);
    g->area = a_pix * (double)t * t * cos_cam * cos_cam * cos_cam / cos_x; /* inverse pinhole Jacobian */
    vec3 wo = v3_norm(v3_sub(rs->eye, g->p)), wi = v3_sub(img, g->p);
    float d2 = v3_dot(wi, wi);
    wi = v3_norm(wi);
    g->f = ts_brdf_spec(0.5f, 0.0f, 0.6f, v3(0, 1, 0), wo, wi);
    /* The reflected ray crosses the mirror plane at 1/3 of the way from the image light (y = 3) to
       the floor, so the lit square has half side 3 HALF. */
    double lim = 3.0 * HALF, ax = fabs(g->p.x), az = fabs(g->p.z);
    int inside = ax < lim && az < lim;
    double foot = sqrt(g->area), dist = fmin(fabs(ax - lim), fabs(az - lim));
    if (!inside)
        dist = fmax(ax > lim ? ax - lim : 0.0, az > lim ? az - lim : 0.0);
    g->margin_ok = dist > 2.0 * foot;
    g->expect = inside ? g->f * I_CD * F0 * wi.y / d2 : 0.0;
}

/* Sum over the image of L / f x footprint area = the power arriving on the floor through the mirror. */
static double floor_power(const gk_ref_scene *rs, const float *rgb, vec3 img)
{
    double power = 0.0;
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            pixel_geom g;
            pixel_geometry(rs, x, y, img, &g);
            if (g.f > 0.0)
                power += rgb[3 * (y * W + x)] / g.f * g.area;
        }
    return power;
}

/* Solid angle of a 2a x 2b rectangle seen on its axis from distance h. */
static double rect_solid_angle(double a, double b, double h) { return 4.0 * atan(a * b / (h * sqrt(a * a + b * b + h * h))); }

static void flat_mirror_closed_form_and_power(void **state)
{
    (void)state;
    static test_scene t;
    vec3 lp = v3(0, 1, 0), img = v3(0, 2 * MIRROR_Y - 1, 0);
    build_small_mirror(&t, lp, GK_LIGHT_POINT, v3(0, -1, 0));
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, W, W), 0);
    gk_ref_result r;
    render_with(&rs, 64, GK_CAUSTIC_EMIT_GUIDED, 2, &r);
    double blk_r[4][4] = {{0}}, blk_e[4][4] = {{0}}, outside_max = 0.0;
    int blk_n[4][4] = {{0}};
    int lit = 0, dark = 0;
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            pixel_geom g;
            pixel_geometry(&rs, x, y, img, &g);
            if (!g.margin_ok)
                continue;
            double v = r.rgb[3 * (y * W + x)];
            if (g.expect > 0.0) {
                blk_r[y / 16][x / 16] += v;
                blk_e[y / 16][x / 16] += g.expect;
                blk_n[y / 16][x / 16]++;
                lit++;
            } else {
                outside_max = fmax(outside_max, v);
                dark++;
            }
        }
    double worst_block = 0.0;
    int blocks = 0;
    for (int by = 0; by < 4; by++)
        for (int bx = 0; bx < 4; bx++)
            if (blk_n[by][bx] >= 16) {
                worst_block = fmax(worst_block, fabs(blk_r[by][bx] / blk_e[by][bx] - 1.0));
                blocks++;
            }
    double omega = rect_solid_angle(HALF, HALF, MIRROR_Y - lp.y);
    double power = floor_power(&rs, r.rgb, img), exact = I_CD * F0 * omega;
    printf("# flat mirror (guided): %d lit / %d dark pixels, worst of %d blocks %.4f, dark max %g; power %.5f "
           "W vs I R Omega = %.5f W (ratio %.4f), floor %.4f\n",
           lit, dark, blocks, worst_block, outside_max, power, exact, power / exact, r.noise_floor);
    assert_true(lit > 500 && dark > 500 && blocks >= 4);
    /* Outside the lit square no caustic path exists: exactly black. */
    assert_true(outside_max == 0.0);
    /* Per-pixel noise inside the lit square ~7% at 64 spp (the whole-image floor 0.18 printed above
       x sqrt(lit share 0.155)): a block of >= 16 lit pixels has sigma <= 1.8%, the power over ~630
       lit pixels ~0.3%. Bounds 4-5 sigma (measured: worst block 3.2%, power ratio 1.0014). */
    assert_true(worst_block < 0.08);
    assert_true(fabs(power / exact - 1.0) < 0.015);
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
}

static void guided_and_light_emission_agree(void **state)
{
    (void)state;
    static test_scene t;
    vec3 img = v3(0, 2 * MIRROR_Y - 1, 0);
    build_small_mirror(&t, v3(0, 1, 0), GK_LIGHT_POINT, v3(0, -1, 0));
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, W, W), 0);
    gk_ref_result g, l, l_same;
    render_with(&rs, 32, GK_CAUSTIC_EMIT_GUIDED, 2, &g);
    render_with(&rs, 32, GK_CAUSTIC_EMIT_LIGHT, 2, &l_same);
    render_with(&rs, 512, GK_CAUSTIC_EMIT_LIGHT, 2, &l);
    double pg = floor_power(&rs, g.rgb, img), pl = floor_power(&rs, l.rgb, img);
    double exact = I_CD * F0 * rect_solid_angle(HALF, HALF, MIRROR_Y - 1.0);
    printf("# guided vs light emission: power %.5f / %.5f W (exact %.5f); floor at 32 spp %.4f guided, %.4f light "
           "(%.1fx)\n",
           pg, pl, exact, g.noise_floor, l_same.noise_floor, l_same.noise_floor / g.noise_floor);
    /* Light emission at 512 spp: 1.9% of 2.1M photons reach the mirror; its floor (1.40 at 32 spp ->
       0.35) is ~14% per lit pixel, so sigma of the power ~0.55%; guided at 32 spp ~0.4%. Bounds
       ~3.6 sigma (measured: 0.9996 and 1.0018). */
    assert_true(fabs(pl / exact - 1.0) < 0.02);
    assert_true(fabs(pg / pl - 1.0) < 0.025);
    /* The mirror's bounding cone is 1/31 of the sphere and 58% of it is the mirror: at equal photon
       counts the guided floor is ~sqrt(31 x 0.58) ~ 4x lower (measured 5.5x: the guided photons'
       flux is also constant, the light's reach the mirror one by one). */
    assert_true(l_same.noise_floor > 3.0 * g.noise_floor);
    gk_ref_result_free(&g);
    gk_ref_result_free(&l);
    gk_ref_result_free(&l_same);
    gk_ref_scene_free(&rs);
}

static void spot_cone_respected(void **state)
{
    (void)state;
    static test_scene t;
    vec3 img = v3(0, 2 * MIRROR_Y - 1, 0);
    /* Up: the 0.3 rad outer cone ends inside the mirror's 0.34 rad corners (partly over it). */
    gk_light *spot = build_small_mirror(&t, v3(0, 1, 0), GK_LIGHT_SPOT, v3(0, 1, 0));
    spot->inner_cone = 0.1f;
    spot->outer_cone = 0.3f;
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, W, W), 0);
    gk_ref_result g, l;
    render_with(&rs, 32, GK_CAUSTIC_EMIT_GUIDED, 2, &g);
    render_with(&rs, 64, GK_CAUSTIC_EMIT_LIGHT, 2, &l);
    double pg = floor_power(&rs, g.rgb, img), pl = floor_power(&rs, l.rgb, img);
    printf("# spot up: power %.5f guided / %.5f light emission (ratio %.4f)\n", pg, pl, pg / pl);
    assert_true(pl > 0.1);
    /* The spot's own cone already aims at the mirror: both sigma ~0.5%, bound ~4 sigma of the ratio
       (measured 1.0025). A spot falloff applied twice or not at all moves it by > 20%. */
    assert_true(fabs(pg / pl - 1.0) < 0.03);
    gk_ref_result_free(&g);
    gk_ref_result_free(&l);
    gk_ref_scene_free(&rs);

    /* Turned down, away from the mirror: no cone survives, no caustic photon, a black image. */
    spot = build_small_mirror(&t, v3(0, 1, 0), GK_LIGHT_SPOT, v3(0, -1, 0));
    spot->inner_cone = 0.1f;
    spot->outer_cone = 0.3f;
    assert_int_equal(ts_build(&t, &rs, W, W), 0);
    gk_caustic_emitter em;
    gk_err e = {0};
    assert_int_equal(gk_caustic_emitter_build(&em, &rs, 1, &e), 0);
    assert_int_equal(em.n_targets, 1);
    assert_true(em.guided[0]);
    assert_int_equal(em.first_cone[1] - em.first_cone[0], 0);
    gk_caustic_emitter_free(&em);
    render_with(&rs, 8, GK_CAUSTIC_EMIT_GUIDED, 1, &g);
    render_with(&rs, 8, GK_CAUSTIC_EMIT_LIGHT, 1, &l);
    double mg = 0.0, ml = 0.0;
    for (int i = 0; i < W * W * 3; i++)
        mg = fmax(mg, g.rgb[i]), ml = fmax(ml, l.rgb[i]);
    assert_true(mg == 0.0 && ml == 0.0);
    gk_ref_result_free(&g);
    gk_ref_result_free(&l);
    gk_ref_scene_free(&rs);
}

static void targets_hold_every_delta_vertex(void **state)
{
    (void)state;
    static test_scene t;
    build_small_mirror(&t, v3(0, 1, 0), GK_LIGHT_POINT, v3(0, -1, 0));
    /* A second mirror far away, so the grid has several occupied cells. */
    ts_quad(&t, v3(3, 0.5f, -2), v3(0, 0, 1), v3(0, 1, 0), 1);
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, 16, 16), 0);
    gk_err e = {0};
    gk_caustic_emitter em;
    assert_int_equal(gk_caustic_emitter_build(&em, &rs, 0, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    int counts[3] = {0};
    const int grids[3] = {1, 2, 4};
    for (int gi = 0; gi < 3; gi++) {
        assert_int_equal(gk_caustic_emitter_build(&em, &rs, grids[gi], &e), 0);
        counts[gi] = em.n_targets;
        for (uint32_t i = 0; i < rs.n_tris; i++) {
            if (!gk_ref_material_may_be_delta(&rs.materials[rs.tris[i].material]))
                continue;
            for (int k = 0; k < 3; k++) {
                int held = 0;
                for (int s = 0; s < em.n_targets; s++)
                    held |= v3_len(v3_sub(rs.tris[i].p[k], em.target_centre[s])) <= em.target_radius[s];
                assert_true(held);
            }
        }
        /* The point light is guided, and its cones' solid angles are positive and ordered in the cdf. */
        assert_true(em.guided[0]);
        for (int c = em.first_cone[0]; c < em.first_cone[1]; c++)
            assert_true(em.cones[c].solid_angle > 0.0f && (c == 0 || em.cone_cdf[c] > em.cone_cdf[c - 1]));
        gk_caustic_emitter_free(&em);
    }
    printf("# targets: grid 1/2/4 -> %d/%d/%d spheres\n", counts[0], counts[1], counts[2]);
    assert_int_equal(counts[0], 1);
    assert_true(counts[1] >= 2);
    gk_ref_scene_free(&rs);
}

static void threads_identical_and_masked_floor(void **state)
{
    (void)state;
    static test_scene t;
    build_small_mirror(&t, v3(0, 1, 0), GK_LIGHT_POINT, v3(0, -1, 0));
    gk_ref_scene rs;
    assert_int_equal(ts_build(&t, &rs, W, W), 0);
    gk_ref_result a, b;
    render_with(&rs, 8, GK_CAUSTIC_EMIT_GUIDED, 1, &a);
    render_with(&rs, 8, GK_CAUSTIC_EMIT_GUIDED, 2, &b);
    for (int i = 0; i < W * W * 3; i++)
        assert_true(a.rgb[i] == b.rgb[i]);
    unsigned char all[W * W], none[W * W];
    for (int i = 0; i < W * W; i++)
        all[i] = 1, none[i] = 0;
    double in_all = gk_ref_noise_floor_masked(&a, W, W, all, true);
    printf("# masked floor: all %.6f, whole image %.6f\n", in_all, a.noise_floor);
    assert_true(fabs(in_all / a.noise_floor - 1.0) < 1e-9);
    assert_true(isnan(gk_ref_noise_floor_masked(&a, W, W, all, false)));
    assert_true(isnan(gk_ref_noise_floor_masked(&a, W, W, none, true)));
    gk_ref_result_free(&a);
    gk_ref_result_free(&b);

    /* Inside a mask (the lit square) the floor from the halves agrees with the one of two renders
       with different seeds: rel RMSE(c, d) / sqrt(2) over the same pixels (render.h). */
    gk_ref_result c, d;
    render_seeded(&rs, 16, GK_CAUSTIC_EMIT_GUIDED, 2, 11, &c);
    render_seeded(&rs, 16, GK_CAUSTIC_EMIT_GUIDED, 2, 12, &d);
    unsigned char lit[W * W], not_dark[W * W];
    double se = 0.0, sum = 0.0;
    long n = 0;
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            pixel_geom g;
            pixel_geometry(&rs, x, y, v3(0, 2 * MIRROR_Y - 1, 0), &g);
            lit[y * W + x] = g.expect > 0.0 && g.margin_ok;
            not_dark[y * W + x] = !(g.expect == 0.0 && g.margin_ok); /* lit, or near the square's edge */
            if (!lit[y * W + x])
                continue;
            for (int k = 0; k < 3; k++) {
                double diff = (double)c.rgb[3 * (y * W + x) + k] - d.rgb[3 * (y * W + x) + k];
                se += diff * diff;
                sum += c.rgb[3 * (y * W + x) + k];
            }
            n += 3;
        }
    double two_seeds = sqrt(se / (double)n) / (sum / (double)n) / sqrt(2.0);
    double halves = gk_ref_noise_floor_masked(&c, W, W, lit, true);
    double outside = gk_ref_noise_floor_masked(&c, W, W, not_dark, false);
    printf("# masked floor inside the lit square: halves %.4f, two seeds %.4f (ratio %.3f); far outside %.4f\n", halves,
           two_seeds, halves / two_seeds, outside);
    /* Each estimate averages ~1700 squared differences of nearly Gaussian noise (~60 photons a
       pixel): relative sigma ~ sqrt(2 / 1900) = 3% each, ~4.5% for the ratio; bound ~4 sigma. */
    assert_true(fabs(halves / two_seeds - 1.0) < 0.18);
    /* Far outside the lit square the caustic is black: no floor defined. */
    assert_true(isnan(outside));
    gk_ref_result_free(&c);
    gk_ref_result_free(&d);
    gk_ref_scene_free(&rs);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(flat_mirror_closed_form_and_power),
        cmocka_unit_test(guided_and_light_emission_agree),
        cmocka_unit_test(spot_cone_respected),
        cmocka_unit_test(targets_hold_every_delta_vertex),
        cmocka_unit_test(threads_identical_and_masked_floor),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
