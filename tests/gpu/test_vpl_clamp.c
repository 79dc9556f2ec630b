/* F13 (dong-001.md §10): the VPL singularity. The thesis clamps nothing; near the corner a VPL a
 * few millimetres from a receiver on the neighbouring wall adds cosθ·cosθ'/d² without bound. Scene:
 * the T5 box without cuboids (convex, so every wall point sees every other one and the reference
 * needs no visibility), spot aimed at the corner. Reference: the one-bounce integral computed on the
 * CPU by integrating the analytic direct irradiance over the walls (48² cells per wall, cells close
 * to the receiver subdivided 8×8): no VPLs, no singularity. Visibility is switched off in the method
 * (vis_override = none) so only the clamp differs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "test_vpl_harness.h"

static vpl_h H;
#define W 64
#define HH 64
#define GRID 48

typedef struct wall { vec3 o, a, b, n; int mat; } wall;
static const wall walls[5] = {
    {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}, 0},  {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}, 0},
    {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0},  {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}, 1},
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, 2},
};

static vec3 albedo(int mat)
{
    const float *c = H.box.mats[mat].base_color;
    return v3(c[0], c[1], c[2]);
}

/* Direct irradiance from the harness's spot at y (normal n), brdf_spec.md falloff. */
static float e_direct(vec3 y, vec3 n)
{
    vec3 L = v3_sub(H.gl_light.position, y);
    float d2 = v3_dot(L, L), d = sqrtf(d2);
    vec3 l = v3_scale(L, 1.0f / d);
    float c = -v3_dot(l, H.gl_light.direction);
    float I = H.box.lights[0].intensity;
    if (H.box.lights[0].shape == GK_SHAPE_RECT) { /* one-sided Lambertian emitter: I·cos */
        I *= fmaxf(c, 0.0f);
    } else if (H.box.lights[0].type == GK_LIGHT_SPOT) {
        float ci = cosf(H.box.lights[0].inner_cone), co = cosf(H.box.lights[0].outer_cone);
        float t = fminf(fmaxf((c - co) / (ci - co), 0.0f), 1.0f);
        I *= t * t;
    }
    return I * fmaxf(v3_dot(n, l), 0.0f) / d2;
}

static vec3 ref_pixel(vec3 x, vec3 nx, int mat_x)
{
    vec3 E = v3(0, 0, 0);
    float cell = 1.0f / GRID;
    for (int w = 0; w < 5; w++) {
        if (v3_dot(walls[w].n, nx) > 0.999f) /* same plane: cos at x is 0 */
            continue;
        vec3 rho = albedo(walls[w].mat);
        for (int j = 0; j < GRID; j++)
            for (int i = 0; i < GRID; i++) {
                vec3 yc = v3_add(walls[w].o, v3_add(v3_scale(walls[w].a, (i + 0.5f) * cell),
                                                     v3_scale(walls[w].b, (j + 0.5f) * cell)));
                int sub = v3_len(v3_sub(yc, x)) < 3.0f * cell ? 8 : 1;
                float sc = cell / sub;
                for (int q = 0; q < sub; q++)
                    for (int p = 0; p < sub; p++) {
                        vec3 y = v3_add(walls[w].o, v3_add(v3_scale(walls[w].a, i * cell + (p + 0.5f) * sc),
                                                            v3_scale(walls[w].b, j * cell + (q + 0.5f) * sc)));
                        vec3 v = v3_sub(y, x);
                        float r2 = v3_dot(v, v);
                        if (r2 < 1e-10f)
                            continue;
                        vec3 u = v3_scale(v, 1.0f / sqrtf(r2));
                        float g = fmaxf(v3_dot(nx, u), 0.0f) * fmaxf(-v3_dot(walls[w].n, u), 0.0f) / r2;
                        float rad = e_direct(y, walls[w].n) / 3.14159265f * g * sc * sc;
                        E = v3_add(E, v3_scale(rho, rad));
                    }
            }
    }
    return v3_scale(v3_mul(albedo(mat_x), E), 1.0f / 3.14159265f);
}

/* The reference image (luminance in .x of each float4 cell), by ray casting the box. */
static void reference(float *out)
{
    for (int py = 0; py < HH; py++)
        for (int px = 0; px < W; px++) {
            float nx = (px + 0.5f) / W * 2 - 1, ny = (py + 0.5f) / HH * 2 - 1;
            vec4 a = m4_vec4(H.inv_vp, (vec4){nx, ny, -1, 1}), b = m4_vec4(H.inv_vp, (vec4){nx, ny, 1, 1});
            vec3 pa = v3_scale(v3(a.x, a.y, a.z), 1 / a.w), pb = v3_scale(v3(b.x, b.y, b.z), 1 / b.w);
            vec3 d = v3_norm(v3_sub(pb, pa));
            float best = INFINITY;
            int hit = -1;
            for (int w = 0; w < 5; w++) {
                float dn = v3_dot(d, walls[w].n);
                if (dn >= 0)
                    continue;
                float t = v3_dot(v3_sub(walls[w].o, H.eye), walls[w].n) / dn;
                if (t > 0 && t < best)
                    best = t, hit = w;
            }
            float *o = &out[(py * W + px) * 4];
            o[0] = o[1] = o[2] = o[3] = 0;
            if (hit < 0)
                continue;
            vec3 x = v3_add(H.eye, v3_scale(d, best));
            vec3 L = ref_pixel(x, walls[hit].n, walls[hit].mat);
            o[0] = L.x, o[1] = L.y, o[2] = L.z;
        }
}

static int setup(void **state)
{
    (void)state;
    return h_init(&H, false, W, HH);
}

static int teardown(void **state)
{
    (void)state;
    h_free(&H);
    return 0;
}

static double peak(const float *img)
{
    double m = 0;
    for (int i = 0; i < W * HH; i++)
        m = fmax(m, h_lum(&img[i * 4]));
    return m;
}

/* Largest per-pixel excess over the reference, in units of the reference's mean. */
static double max_excess(const float *img, const float *ref)
{
    double m = 0, mr = h_mean(ref, W * HH);
    for (int i = 0; i < W * HH; i++)
        m = fmax(m, (h_lum(&img[i * 4]) - h_lum(&ref[i * 4])) / mr);
    return m;
}

static void test_f13_clamp(void **state)
{
    (void)state;
    float *ref = malloc(sizeof(float) * W * HH * 4), *off = malloc(sizeof(float) * W * HH * 4);
    reference(ref);
    gk_vpl_debug d;
    gk_vpl_default_debug(&d);
    d.vis_override = GK_VPL_VIS_NONE;
    d.measure = true;
    d.fade_frames = 0;
    gk_vpl_set_debug(H.self, &d);
    /* Full-resolution indirect, no interleave, a small blur: the singularity is not averaged away. */
    assert_int_equal(h_budget(&H, "vpl_n=256,vpl_m=8,vpl_block=1,vpl_res=1,vpl_blur=2,vpl_clamp=off"), 0);
    assert_int_equal(h_frame(&H, 0), 0);
    memcpy(off, H.img, sizeof(float) * W * HH * 4);
    assert_int_equal(h_budget(&H, "vpl_n=256,vpl_m=8,vpl_block=1,vpl_res=1,vpl_blur=2,vpl_clamp=on"), 0);
    assert_int_equal(h_frame(&H, 0), 0);
    const gk_vpl_stats *st = gk_vpl_get_stats(H.self);
    double mref = h_mean(ref, W * HH);
    double ratio_off = h_mean(off, W * HH) / mref, ratio_on = h_mean(H.img, W * HH) / mref;
    double ex_off = max_excess(off, ref), ex_on = max_excess(H.img, ref);
    print_message("# F13: ref mean %.5f peak %.5f | clamp off: mean ratio %.3f, peak %.5f, max excess %.2f x mean | "
                  "clamp on (d_min %.4f m): mean ratio %.3f, peak %.5f, max excess %.2f x mean, removed %.2f%%\n",
                  mref, peak(ref), ratio_off, peak(off), ex_off, st->dmin, ratio_on, peak(H.img), ex_on,
                  100.0 * st->clamp_removed);
    /* Measured: unclamped mean ratio 1.012 (the VPL flux normalisation conserves energy against
       the analytic integral), peak 2.0x the reference's, worst pixel 3.62 reference-means above
       its reference; clamped (d_min = mean VPL spacing 0.083 m) mean ratio 0.978, peak equal to
       the reference's, worst pixel 0.43 means above, 4.29% of the gathered energy removed.
       Bounds: energy within ±10% unclamped; clamped no pixel more than 1 reference-mean above the
       reference (2.3x the measured margin); removed energy below the brief's 5%; and the
       unclamped run must show the singularity (> 2 means), or the test could not fail. */
    assert_true(ratio_off > 0.9 && ratio_off < 1.1);
    assert_true(ex_on < 1.0);
    assert_true(st->clamp_removed < 0.05);
    assert_true(ex_off > 2.0);
    free(ref);
    free(off);
}

/* The other RSM layouts against the same analytic integral: a point light (6-face cube atlas) and
   a rectangular area light (5-face hemicube, I·cosθ), with and without the clamp. */
static double light_energy_ratio(enum gk_light_type type, enum gk_light_shape shape, const char *clamp)
{
    H.box.lights[0].type = type, H.box.lights[0].shape = shape;
    H.box.lights[0].size[0] = H.box.lights[0].size[1] = 0.1f;
    float *ref = malloc(sizeof(float) * W * HH * 4);
    reference(ref);
    gk_vpl_debug d;
    gk_vpl_default_debug(&d);
    d.vis_override = GK_VPL_VIS_NONE;
    d.fade_frames = 0;
    gk_vpl_set_debug(H.self, &d);
    char list[128];
    snprintf(list, sizeof list, "vpl_n=256,vpl_m=8,vpl_block=1,vpl_res=1,vpl_blur=2,vpl_clamp=%s", clamp);
    assert_int_equal(h_budget(&H, list), 0);
    assert_int_equal(h_frame(&H, 0), 0);
    double r = h_mean(H.img, W * HH) / h_mean(ref, W * HH);
    free(ref);
    H.box.lights[0].type = GK_LIGHT_SPOT, H.box.lights[0].shape = GK_SHAPE_POINT;
    return r;
}

static void test_rsm_layouts_energy(void **state)
{
    (void)state;
    double point = light_energy_ratio(GK_LIGHT_POINT, GK_SHAPE_POINT, "off");
    double rect = light_energy_ratio(GK_LIGHT_SPOT, GK_SHAPE_RECT, "off");
    double point_c = light_energy_ratio(GK_LIGHT_POINT, GK_SHAPE_POINT, "on");
    double rect_c = light_energy_ratio(GK_LIGHT_SPOT, GK_SHAPE_RECT, "on");
    print_message("# RSM energy vs analytic one-bounce: point light (cube) %.3f (clamped %.3f), rect light "
                  "(hemicube) %.3f (clamped %.3f)\n", point, point_c, rect, rect_c);
    /* Measured (N = 256, full-res indirect): point 1.016 unclamped / 0.970 clamped, rect 1.102 /
       0.975 (the unclamped excess is corner spikes, larger for the broad I·cos lobe; the spot gave
       1.012 / 0.978). Bound: clamped within ±10% of the analytic integral; a cube face counted
       twice or a lost cos or solid-angle factor is off by ≥ 1/6 or ×2. Unclamped below +20%. */
    assert_true(point_c > 0.9 && point_c < 1.1);
    assert_true(rect_c > 0.9 && rect_c < 1.1);
    assert_true(point < 1.2 && rect < 1.2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_f13_clamp),
        cmocka_unit_test(test_rsm_layouts_energy),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
