/* Direct light of the deferred renderer against closed forms, on Mesa llvmpipe (EGL surfaceless):
 * a point light and a rectangular area light over a plane, and the --gles 3.1 path against the
 * default path. The diffuse part is isolated exactly by rendering the plane twice, with base
 * colour rho and with base colour 0: for a dielectric (metallic 0) the specular term does not
 * depend on the base colour, so L(rho) - L(0) = (1 - Fd(v.h)) rho / pi * E (brdf_spec.md's
 * fresnel_mix, the default material: specular weight 1, c0 = 0.04). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gpu/test_render_fixture.h"

#define W 64
#define H 64
#define RHO 0.8f /* exactly 204/255, so the RGBA8 G-buffer stores it without rounding */

static fx_gl gl;

static int setup(void **state)
{
    (void)state;
    return fx_gl_open(&gl, W, H);
}

static int teardown(void **state)
{
    (void)state;
    fx_gl_close(&gl);
    return 0;
}

static void plane_scene(fx_scene *f, float rho)
{
    fx_init(f, v3(0, 2.0f, 2.6f), v3(0, 0, -0.2f), 0.9f);
    fx_quad(f, -4, 4, -4, 4, 0, fx_material(f, rho, 0, 0.6f));
}

static void render_pair(fx_scene *lit, fx_scene *black, const char *budget, gk_image *a, gk_image *b)
{
    gk_err e = {0};
    int rc = fx_render(&gl, lit, 32, budget, a, &e);
    if (rc != 0)
        fail_msg("render: %s", e.msg);
    rc = fx_render(&gl, black, 32, budget, b, &e);
    if (rc != 0)
        fail_msg("render: %s", e.msg);
}

/* Point light, I = 10 cd: L(rho) - L(0) = (1 - Fd) rho I cos / (pi d^2) per pixel;
 * L(0) = F D V I cos / d^2. */
static void point_light_over_plane(void **state)
{
    (void)state;
    fx_scene lit, black;
    const vec3 lp = v3(0.3f, 1.2f, -0.2f);
    plane_scene(&lit, RHO);
    plane_scene(&black, 0);
    gkt_light(&lit, GK_LIGHT_POINT, GK_SHAPE_POINT, 10, lp, v3(0, -1, 0));
    gkt_light(&black, GK_LIGHT_POINT, GK_SHAPE_POINT, 10, lp, v3(0, -1, 0));
    gk_image a, b;
    render_pair(&lit, &black, "shadow=hard,shadow_map=1024", &a, &b);
    double max_diff = 0, max_spec = 0;
    int n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            vec3 p, eye;
            if (fx_pixel_on_plane(&lit, W, H, x, y, 0, &p, &eye) != 0)
                continue;
            vec3 to_l = v3_sub(lp, p), nrm = v3(0, 1, 0);
            double d2 = v3_dot(to_l, to_l);
            vec3 l = v3_norm(to_l), v = v3_norm(v3_sub(eye, p));
            double e_irr = 10.0 * v3_dot(nrm, l) / d2;
            double want_diff = fx_diffuse_share(v, l) * RHO / FX_PI * e_irr;
            double want_spec = fx_spec(nrm, v, l, 0.04, 0.6) * e_irr;
            size_t i = ((size_t)y * W + x) * 4;
            double got_diff = a.pixels[i + 1] - b.pixels[i + 1], got_spec = b.pixels[i + 1];
            max_diff = fmax(max_diff, fabs(got_diff - want_diff) / want_diff);
            max_spec = fmax(max_spec, fabs(got_spec - want_spec) / (want_spec + 0.01 * want_diff));
            n++;
        }
    printf("# point light: %d pixels, max relative error diffuse %.2e, specular %.2e\n", n, max_diff, max_spec);
    gk_image_free(&a);
    gk_image_free(&b);
    /* Measured 1.3e-3 (diffuse) and 2.6e-3 (specular), every pixel slightly LOW: the HDR target
       and the G-buffer roughness are RGBA16F, which llvmpipe fills by truncation (up to one ulp,
       2^-10 = 9.8e-4 relative, per stored value), and roughness 0.6 stored as 0.5996 narrows the
       lobe by ~1e-3. Bounds at 2x the measurement: still far below what a wrong cosine, a 1/pi or
       a light 1 cm off (2% at 1 m) would give. */
    assert_true(n > W * H / 2);
    assert_true(max_diff < 3e-3);
    assert_true(max_spec < 5e-3);
    gkt_scene_free(&lit);
    gkt_scene_free(&black);
}

/* Rect light W x H = 0.8 x 0.5 m at 1 m, facing down, I = 5 cd: L_e = I / (W H).
 * Diffuse vs the closed-form polygon irradiance times fresnel_mix's share (1 - Fd) at the
 * representative direction, and vs a quadrature with (1 - Fd) taken per direction; specular
 * (linearly transformed cosines) vs a 64x64 midpoint quadrature of F D V L cos cos / r^2 over the rectangle. */
static void rect_light_over_plane(void **state)
{
    (void)state;
    const float lw = 0.8f, lh = 0.5f, inten = 5.0f;
    const vec3 c = v3(0.1f, 1.0f, -0.3f);
    fx_scene lit, black;
    plane_scene(&lit, RHO);
    plane_scene(&black, 0);
    gk_light *l1 = gkt_light(&lit, GK_LIGHT_POINT, GK_SHAPE_RECT, inten, c, v3(0, -1, 0));
    gk_light *l2 = gkt_light(&black, GK_LIGHT_POINT, GK_SHAPE_RECT, inten, c, v3(0, -1, 0));
    l1->size[0] = l2->size[0] = lw;
    l1->size[1] = l2->size[1] = lh;
    gk_image a, b;
    render_pair(&lit, &black, "shadow=hard", &a, &b);
    /* The light's X axis is world x, its Y axis world -z (gkt_look_rotation of straight down). */
    const vec3 corners[4] = {v3(c.x - lw / 2, c.y, c.z - lh / 2), v3(c.x + lw / 2, c.y, c.z - lh / 2),
                             v3(c.x + lw / 2, c.y, c.z + lh / 2), v3(c.x - lw / 2, c.y, c.z + lh / 2)};
    const double le = inten / (lw * lh);
    double max_diff = 0, max_share = 0, sum_spec_err = 0, sum_spec = 0;
    int n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            vec3 p, eye;
            if (fx_pixel_on_plane(&lit, W, H, x, y, 0, &p, &eye) != 0)
                continue;
            vec3 nrm = v3(0, 1, 0), v = v3_norm(v3_sub(eye, p));
            double e_irr = le * fx_polygon_irradiance(p, nrm, corners, 4);
            double want_spec = 0, share = 0, e_quad = 0;
            const int q = 64;
            for (int j = 0; j < q; j++)
                for (int i = 0; i < q; i++) {
                    vec3 s = v3(c.x + lw * ((i + 0.5f) / q - 0.5f), c.y, c.z + lh * ((j + 0.5f) / q - 0.5f));
                    vec3 to = v3_sub(s, p);
                    double r2 = v3_dot(to, to);
                    vec3 dl = v3_norm(to);
                    double cos_l = dl.y; /* emitter normal is -y; -dl . (-y) */
                    want_spec += fx_spec(nrm, v, dl, 0.04, 0.6) * dl.y * cos_l / r2;
                    share += fx_diffuse_share(v, dl) * dl.y * cos_l / r2;
                    e_quad += dl.y * cos_l / r2;
                }
            want_spec *= le * (lw * lh) / (q * q);
            share /= e_quad; /* the irradiance-weighted mean of (1 - Fd) over the light */
            double want_diff = share * RHO / FX_PI * e_irr;
            size_t k = ((size_t)y * W + x) * 4;
            double got_diff = a.pixels[k + 1] - b.pixels[k + 1], got_spec = b.pixels[k + 1];
            max_diff = fmax(max_diff, fabs(got_diff - want_diff) / want_diff);
            max_share = fmax(max_share, fabs(share / fx_diffuse_share(v, v3_norm(v3_sub(c, p))) - 1.0));
            sum_spec_err += fabs(got_spec - want_spec);
            sum_spec += want_spec;
            n++;
        }
    double spec_rel = sum_spec_err / sum_spec;
    printf("# rect light: %d pixels, max relative error diffuse %.2e; specular mean |error| / mean %.3f\n", n, max_diff,
           spec_rel);
    printf("# rect light: (1 - Fd) over the light vs at its centre: max relative difference %.2e\n", max_share);
    gk_image_free(&a);
    gk_image_free(&b);
    /* Diffuse measured 1.4e-3 (RGBA16F truncation as above): the edge integral is exact. */
    assert_true(max_diff < 3e-3);
    /* Specular by linearly transformed cosines (common/ltc.glsl, tables fitted by tools/ltc_fit.c):
       measured 0.130 mean relative error at roughness 0.6 (the views here are about 30-70 degrees,
       where the fit is weakest: tests/unit/test_ltc_table.c). The representative point it
       replaced measured 0.171; the bound 0.15 fails a fallback to it, a missing lobe (1.0) or
       a lobe not normalised (several x). */
    assert_true(spec_rel < 0.15);
    gkt_scene_free(&lit);
    gkt_scene_free(&black);
}

/* --gles 3.1 (#version 310 es, 3.2 features masked) against the default path on a scene with
 * a rect light, an occluder and PCSS: the same image within RGBA16F rounding. */
static void gles31_matches_default(void **state)
{
    (void)state;
    fx_scene f;
    plane_scene(&f, RHO);
    fx_quad(&f, -1.5f, 0.0f, -1.5f, 1.5f, 0.5f, fx_material(&f, 0.5f, 0, 0.8f));
    gk_light *l = gkt_light(&f, GK_LIGHT_POINT, GK_SHAPE_RECT, 5, v3(0, 1.2f, 0), v3(0, -1, 0));
    l->size[0] = 0.6f;
    l->size[1] = 0.4f;
    gkt_light(&f, GK_LIGHT_SPOT, GK_SHAPE_POINT, 8, v3(1, 1.5f, 1), v3(-0.5f, -1, -0.5f));
    gk_image a, b;
    gk_err e = {0};
    if (fx_render(&gl, &f, 31, "shadow=pcss,shadow_map=512", &a, &e) != 0)
        fail_msg("gles 3.1: %s", e.msg);
    if (fx_render(&gl, &f, 32, "shadow=pcss,shadow_map=512", &b, &e) != 0)
        fail_msg("gles 3.2: %s", e.msg);
    double max_abs = 0, max_val = 0;
    for (int i = 0; i < W * H * 4; i++) {
        max_abs = fmax(max_abs, fabs(a.pixels[i] - b.pixels[i]));
        max_val = fmax(max_val, fabs(b.pixels[i]));
    }
    printf("# gles 3.1 vs default: max |difference| %.3e of max value %.3f\n", max_abs, max_val);
    gk_image_free(&a);
    gk_image_free(&b);
    /* Measured 0: both paths run the same arithmetic on llvmpipe. 1e-3 of the peak allows a
       driver that compiles 310 es and 320 es differently to round differently. */
    assert_true(max_val > 0.01);
    assert_true(max_abs <= 1e-3 * max_val);
    gkt_scene_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(point_light_over_plane),
        cmocka_unit_test(rect_light_over_plane),
        cmocka_unit_test(gles31_matches_default),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
