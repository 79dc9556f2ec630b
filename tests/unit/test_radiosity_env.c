/* The environment through empty leaf bins (app/gi/radiosity/rad_env.h):
 *  - a bin's direction set: rad_bin_direction inverts rad_cube_bin;
 *  - the bin means of a uniform map are the map's radiance; of the studio map, RAD_ENV_SUBSAMPLES²
 *    directions a bin against 32² (the convergence its comment states);
 *  - closed forms under a uniform environment L: a lone Lambert quad receives π L at every surfel
 *    (no links: every bin is empty); the floor of a box open at the top receives π L F(x), F the
 *    form factor from the floor point x to the opening (the walls fill the rest of its bins);
 *  - env-studio: what the empty bins gather at the surfels against shadow rays towards the map
 *    (rad_direct.h, the `rays` switch), area-weighted. */
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
#include "gi/radiosity/rad_env.h"
#include "gi/radiosity/rad_solve.h"
#include "scene/environment.h"

/* Bounds, each the worst of the three bin resolutions as measured (this file's output) with room:
 * studio map, bin means at 16² vs 64² directions, worst bin (a panel's edge) 0.038 / 0.093 / 0.087
 *   at 6x8² / 6x12² / 6x16² (the totals agree to 5e-4); */
#define RAD_ENV_SUBSAMPLE_BOUND 0.12
/* lone quad, |E / π L - 1|: 0.0086 / 0.0038 / 0.0021 (the midpoint rule over the bins); */
#define RAD_LONE_QUAD_ERR 0.011
/* open box floor, mean E / π L against the mean form factor 0.1999: bins +0.38 / +0.92 / +1.23 (the
 *   walls' unlinked bins: asserted, so a change that closes them shows here), rest -0.21 / -0.05 /
 *   -0.12, its worst surfel |E / π L - F| 0.093 / 0.061 / 0.047; */
#define RAD_OPEN_BOX_BINS_EXCESS 0.3
#define RAD_OPEN_BOX_REST_MEAN_ERR 0.25
#define RAD_OPEN_BOX_REST_WORST 0.11
/* env-studio against shadow rays, area-weighted mean ratio: bins 1.001 / 1.012 / 1.019, rest 0.982 /
 *   0.990 / 0.994; relative L1 0.056-0.062 (both). */
#define RAD_STUDIO_RATIO_ERR 0.025
#define RAD_STUDIO_L1 0.075

static gk_environment uniform_env(float r, float g, float b)
{
    gk_environment env = {.present = true, .intensity = 1.0f, .width = 16, .height = 8};
    env.rgb = malloc(sizeof *env.rgb * 3 * 16 * 8);
    for (int i = 0; i < 16 * 8; i++)
        env.rgb[3 * i] = r, env.rgb[3 * i + 1] = g, env.rgb[3 * i + 2] = b;
    return env;
}

static void bin_direction_inverts_cube_bin(void **state)
{
    (void)state;
    const int res[] = {8, 12, 16};
    for (int r = 0; r < 3; r++) {
        int n = res[r];
        for (int k = 0; k < 6 * n * n; k++) {
            assert_int_equal(rad_cube_bin(rad_bin_direction(k, n, 0.5f, 0.5f), n), k);
            assert_int_equal(rad_cube_bin(rad_bin_direction(k, n, 0.05f, 0.95f), n), k);
            assert_int_equal(rad_cube_bin(rad_bin_direction(k, n, 0.95f, 0.05f), n), k);
        }
    }
}

static void bin_means(void **state)
{
    (void)state;
    gk_environment env = uniform_env(1.0f, 2.0f, 3.0f);
    int n = 12, bins = 6 * n * n;
    /* room for the finest resolution below (6 x 16²) */
    float *m = malloc(sizeof *m * 3 * 6 * 16 * 16), *fine = malloc(sizeof *fine * 3 * 6 * 16 * 16);
    rad_env_bin_radiance(&env, n, RAD_ENV_SUBSAMPLES, m);
    for (int k = 0; k < bins; k++)
        for (int c = 0; c < 3; c++)
            assert_float_equal(m[3 * k + c], (float)(c + 1), 1e-5f);
    free(env.rgb);
    /* without an environment: zeros */
    gk_environment none = {0};
    rad_env_bin_radiance(&none, n, RAD_ENV_SUBSAMPLES, m);
    for (int k = 0; k < 3 * bins; k++)
        assert_true(m[k] == 0.0f);
    /* the studio map: RAD_ENV_SUBSAMPLES² directions a bin against 32² */
    gk_err e = {0};
    gk_environment studio = {0};
    assert_int_equal(gk_env_make_studio(&studio, GK_ENV_STUDIO_HEIGHT, 1.0f, &e), 0);
    const int res[] = {8, 12, 16};
    for (int r = 0; r < 3; r++) {
        n = res[r], bins = 6 * n * n;
        rad_env_bin_radiance(&studio, n, RAD_ENV_SUBSAMPLES, m);
        rad_env_bin_radiance(&studio, n, 64, fine);
        double worst = 0.0, sum = 0.0, fsum = 0.0;
        for (int k = 0; k < bins; k++)
            for (int c = 0; c < 3; c++) {
                double d = fabs((double)m[3 * k + c] - fine[3 * k + c]);
                worst = fmax(worst, d / fmax(fine[3 * k + c], 1e-3));
                sum += m[3 * k + c] * rad_bin_solid_angle(k, n), fsum += fine[3 * k + c] * rad_bin_solid_angle(k, n);
            }
        printf("# studio map, 6x%d^2: bin means at %d^2 vs 64^2 directions: worst relative %.4f, total %.5f\n", n,
               RAD_ENV_SUBSAMPLES, worst, sum / fsum - 1.0);
        assert_true(worst < RAD_ENV_SUBSAMPLE_BOUND);
    }
    gk_env_free(&studio);
    free(m), free(fine);
}

/* E_env at every leaf of the square charts sq under env at N = n (tree and links built here). */
static float *env_at_leaves(const square *sq, int n_sq, const gk_environment *env, int n, bool rest, rad_tree *t,
                            rad_mesh *m)
{
    squares_mesh(m, sq, n_sq);
    rad_links L;
    gk_err e = {0};
    assert_int_equal(rad_tree_build(t, m, &e), 0);
    assert_int_equal(rad_links_build(&L, t, n, RAD_WEIGHT_SPILL, &e), 0);
    float *bins = malloc(sizeof *bins * 3 * 6 * (size_t)n * (size_t)n);
    float *E = malloc(sizeof *E * 3 * (size_t)t->n_leaves);
    rad_env_bin_radiance(env, n, RAD_ENV_SUBSAMPLES, bins);
    rad_env_irradiance(t, &L, bins, rest, E);
    free(bins);
    rad_links_free(&L);
    return E;
}

/* A lone quad facing up under a uniform environment: E = π L at every surfel. The bins sum
   cos × solid angle at their centres, a midpoint rule over the hemisphere; measured
   (E / π L - 1, every surfel alike): RAD_LONE_QUAD_ERR below. */
static void lone_quad(void **state)
{
    (void)state;
    gk_environment env = uniform_env(0.5f, 1.0f, 2.0f);
    const square sq[] = {{.centre = v3(0, 0, 0), .normal = v3(0, 1, 0), .tu = v3(1, 0, 0), .side = 1.0f, .g = 8}};
    const int res[] = {8, 12, 16};
    for (int r = 0; r < 3; r++) {
        rad_tree t;
        rad_mesh m;
        float *E = env_at_leaves(sq, 1, &env, res[r], false, &t, &m);
        double worst = 0.0;
        for (int i = 0; i < t.n_leaves; i++)
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fabs(E[3 * i + c] / (M_PI * env.rgb[c]) - 1.0));
        printf("# lone quad, 6x%d^2: E / (pi L) - 1 at most %.5f over %d surfels\n", res[r], worst, t.n_leaves);
        assert_true(worst < RAD_LONE_QUAD_ERR);
        free(E);
        rad_tree_free(&t);
        rad_mesh_free(&m);
    }
    free(env.rgb);
}

/* Form factor from a floor point to a parallel rectangle at height h with a corner straight above
   it, sides a and b (the standard differential-area-to-rectangle formula). */
static double ff_corner(double a, double b, double h)
{
    double A = a / h, B = b / h, sa = sqrt(1.0 + A * A), sb = sqrt(1.0 + B * B);
    return (A / sa * atan(B / sa) + B / sb * atan(A / sb)) / (2.0 * M_PI);
}

/* The floor (1 x 1) of a unit box open at the top, under a uniform environment L: every floor
   point x receives π L F(x), F its form factor to the opening (the walls cover the rest of its
   hemisphere with links). Reported: the area-weighted mean of E / (π L) against the mean of F, and
   the worst surfel's |E / (π L) - F|. */
static void open_box_floor(bool rest)
{
    gk_environment env = uniform_env(1.0f, 1.0f, 1.0f);
    const square sq[] = {
        {.centre = v3(0, 0, 0), .normal = v3(0, 1, 0), .tu = v3(1, 0, 0), .side = 1.0f, .g = 16},
        {.centre = v3(-0.5f, 0.5f, 0), .normal = v3(1, 0, 0), .tu = v3(0, 0, 1), .side = 1.0f, .g = 16},
        {.centre = v3(0.5f, 0.5f, 0), .normal = v3(-1, 0, 0), .tu = v3(0, 0, 1), .side = 1.0f, .g = 16},
        {.centre = v3(0, 0.5f, -0.5f), .normal = v3(0, 0, 1), .tu = v3(1, 0, 0), .side = 1.0f, .g = 16},
        {.centre = v3(0, 0.5f, 0.5f), .normal = v3(0, 0, -1), .tu = v3(1, 0, 0), .side = 1.0f, .g = 16},
    };
    const int res[] = {8, 12, 16};
    double mean_err[3];
    for (int r = 0; r < 3; r++) {
        rad_tree t;
        rad_mesh m;
        float *E = env_at_leaves(sq, 5, &env, res[r], rest, &t, &m);
        double sE = 0.0, sF = 0.0, a = 0.0, worst = 0.0;
        for (int i = 0; i < t.n_leaves; i++) {
            if (m.chart[i] != 0)
                continue; /* the floor's surfels (leaves are the vertices, chart by chart) */
            vec3 p = t.pos[i];
            double F = ff_corner(0.5 + p.x, 0.5 + p.z, 1.0) + ff_corner(0.5 - p.x, 0.5 + p.z, 1.0) +
                       ff_corner(0.5 + p.x, 0.5 - p.z, 1.0) + ff_corner(0.5 - p.x, 0.5 - p.z, 1.0);
            double got = E[3 * i] / M_PI;
            sE += got * t.area[i], sF += F * t.area[i], a += t.area[i];
            worst = fmax(worst, fabs(got - F));
        }
        mean_err[r] = sE / sF - 1.0;
        printf("# open box floor, %s, 6x%d^2: mean E/(pi L) %.4f vs mean form factor %.4f (%+.4f), worst surfel |E/(pi L) - F| %.4f\n",
               rest ? "rest" : "bins", res[r], sE / a, sF / a, mean_err[r], worst);
        if (rest) {
            assert_true(fabs(mean_err[r]) < RAD_OPEN_BOX_REST_MEAN_ERR);
            assert_true(worst < RAD_OPEN_BOX_REST_WORST);
        } else {
            /* the seed's empty bins see the environment through the walls' unlinked bins */
            assert_true(mean_err[r] > RAD_OPEN_BOX_BINS_EXCESS);
        }
        free(E);
        rad_tree_free(&t);
        rad_mesh_free(&m);
    }
    free(env.rgb);
}
static void open_box_floor_bins(void **state) { (void)state, open_box_floor(false); }
static void open_box_floor_rest(void **state) { (void)state, open_box_floor(true); }

/* env-studio (lit only by its environment): what the empty bins gather at the surfels against shadow
   rays towards the map (the `rays` switch, 256 samples a surfel), per bin resolution: the
   area-weighted ratio of the means and the area-weighted relative L1 difference. The bins see
   through what their links miss (an element is linked in the one bin of its centre's direction,
   research 2.6's "entirely visible or occluded"), so they gather more. */
static void env_studio_bins_vs_rays(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_scene *s = gk_scene_load("config/scenes/env-studio.gltf", &e);
    if (!s)
        fail_msg("%s", e.msg);
    gk_scene_evaluate(s, 0.0f);
    gk_ref_scene rs;
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 0), 1, 1, &e), 0);
    assert_true(rs.env_light >= 0);
    vec3 ext = v3_sub(s->bmax, s->bmin);
    const int res[] = {8, 12, 16};
    for (int r = 0; r < 3; r++) {
        rad_geometry g;
        assert_int_equal(rad_geometry_build(&g, s, v3_len(ext) / 24.0f, 60000, res[r], RAD_WEIGHT_SPILL, &e), 0);
        int nl = g.tree.n_leaves;
        float *rays = malloc(sizeof *rays * 3 * (size_t)nl), *bins = malloc(sizeof *bins * 3 * (size_t)nl);
        float *table = malloc(sizeof *table * 3 * 6 * (size_t)res[r] * (size_t)res[r]);
        rad_direct_irradiance(&rs, &g.tree, 256, 0, nl, rays);
        rad_direct_irradiance_except(&rs, &g.tree, 256, rs.env_light, 0, nl, bins);
        for (int i = 0; i < 3 * nl; i++)
            assert_true(bins[i] == 0.0f); /* the environment is the scene's only light */
        rad_env_bin_radiance(&s->environment, res[r], RAD_ENV_SUBSAMPLES, table);
        for (int rest = 0; rest < 2; rest++) {
            rad_env_irradiance(&g.tree, &g.links, table, rest, bins);
            double sb = 0.0, sr = 0.0, l1 = 0.0;
            for (int i = 0; i < nl; i++) {
                double a = g.tree.area[i];
                for (int c = 0; c < 3; c++)
                    sb += a * bins[3 * i + c], sr += a * rays[3 * i + c], l1 += a * fabs(bins[3 * i + c] - rays[3 * i + c]);
            }
            printf("# env-studio, %d surfels, 6x%d^2: %s / shadow rays, area-weighted mean ratio %.4f, relative L1 %.4f\n",
                   nl, res[r], rest ? "rest" : "bins", sb / sr, l1 / sr);
            assert_true(fabs(sb / sr - 1.0) < RAD_STUDIO_RATIO_ERR);
            assert_true(l1 / sr < RAD_STUDIO_L1);
        }
        free(rays), free(bins), free(table);
        rad_geometry_free(&g);
    }
    gk_ref_scene_free(&rs);
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bin_direction_inverts_cube_bin),
        cmocka_unit_test(bin_means),
        cmocka_unit_test(lone_quad),
        cmocka_unit_test(open_box_floor_bins),
        cmocka_unit_test(open_box_floor_rest),
        cmocka_unit_test(env_studio_bins_vs_rays),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
