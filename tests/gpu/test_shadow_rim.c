/* VSSM on the rim of the shadow-planes floor (#11): the scene of shadow-planes (T1 with the
 * scene's rect POINT light, so the floor's outer metre lies on the side faces of the cube map,
 * seen at grazing angles), receiver pixels within 0.1 m of the floor's edge, where the exact
 * received light (sx_exact_v) is the full light. The thesis's VSSM tests every sub-kernel against
 * the pixel's one depth: there the kernel is half floor nearer the light, half empty past the edge
 * (non-planar, so subdivided), and the nearer floor counted as blockers -- 0.78-0.90 of the light,
 * single pixels 0.62 (map 1024). vssm tests each sub-kernel against the receiver plane
 * (VSSM_RECEIVER_PLANE, shaders_gles/shadow/vssm.glsl); vssm_thesis keeps the thesis's test as the
 * baseline that shows the test can fail. Also every soft method's rim against the analytic value.
 * 256x256 pixels; maps 1024 (the default shadow_map) and 2048. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gpu/test_shadow_util.h"

#define W 256
#define H 256
#define RIM 0.1f

static const gk_knob_def knob_rim = {
    .name = "shadow", .owner = "test", .n_values = 5,
    .values = {"hard", "pcss", "vssm", "cssm", "vssm_thesis"},
    .cost = {1, 1, 1, 1, 1}, .default_level = 0,
};

static sx_session ses;

static int setup(void **state)
{
    (void)state;
    return sx_open_knob(&ses, W, H, &knob_rim);
}

static int teardown(void **state)
{
    (void)state;
    sx_close(&ses);
    return 0;
}

/* The shadow-planes scene (app/scene/build_analytic.c) as an sx_setup. */
static sx_setup planes(void)
{
    sx_setup st = {.S = 1, .light = v3(0, SX_LIGHT_Y, 0), .n_rects = 1, .eye = v3(0, 6, 6), .target = v3(0, 0, 0),
                   .yfov = 1.0471976f, .point = true};
    st.rect[0] = (sx_rect){-1, 1, -1, 1, 1};
    return st;
}

/* The floor point under pixel (x, y), when it is within `rim` of the floor's edge (|x|, |z| <= 5)
   and the camera sees it unobstructed. */
static bool rim_point(fx_scene *f, const sx_setup *st, int x, int y, float rim, vec3 *p)
{
    mat4 view, proj;
    vec3 eye;
    gk_scene_evaluate(&f->s, 0);
    gk_scene_camera(&f->s, (float)W / (float)H, &view, &proj, &eye);
    mat4 inv = m4_inverse(m4_mul(proj, view));
    float nx = ((float)x + 0.5f) / (float)W * 2 - 1, ny = 1 - ((float)y + 0.5f) / (float)H * 2;
    vec4 a = m4_vec4(inv, (vec4){nx, ny, -1, 1}), b = m4_vec4(inv, (vec4){nx, ny, 1, 1});
    vec3 pa = v3(a.x / a.w, a.y / a.w, a.z / a.w), pb = v3(b.x / b.w, b.y / b.w, b.z / b.w);
    vec3 d = v3_sub(pb, pa);
    if (fabsf(d.y) < 1e-9f)
        return false;
    float t = -pa.y / d.y;
    if (t <= 0)
        return false;
    *p = v3_add(pa, v3_scale(d, t));
    /* 5 mm inside the edge: the pixel's footprint must lie on the floor */
    float edge = 5 - fmaxf(fabsf(p->x), fabsf(p->z));
    return edge > 0.005f && edge < rim && !sx_ray_blocked(st, eye, *p);
}

typedef struct rim_stats {
    double mean, min;
    int n;
} rim_stats;

/* V / V_exact over the rim pixels, V = L(method) / L(no occluder, hard shadows). */
static rim_stats rim_measure(const char *method, int map)
{
    sx_setup st = planes();
    fx_scene with, without;
    sx_build(&with, &st, true);
    sx_build(&without, &st, false);
    static float a[W * H], b[W * H];
    char pins[96];
    gk_err e = {0};
    snprintf(pins, sizeof pins, "shadow=%s,shadow_map=%d", method, map);
    if (gk_renderer_set_scene(ses.r, &without.s, &e) != 0 || sx_draw(&ses, "shadow=hard,shadow_map=1024", b) != 0 ||
        gk_renderer_set_scene(ses.r, &with.s, &e) != 0 || sx_draw(&ses, pins, a) != 0)
        fail_msg("render %s: %s", pins, e.msg);
    gk_renderer_set_scene(ses.r, NULL, &e);
    rim_stats r = {.min = 1e9};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            vec3 p;
            int i = y * W + x;
            if (!rim_point(&with, &st, x, y, RIM, &p) || b[i] < 1e-4f)
                continue;
            double ratio = a[i] / b[i] / sx_exact_v(&st, p);
            r.mean += ratio;
            r.min = fmin(r.min, ratio);
            r.n++;
        }
    r.mean /= r.n > 0 ? r.n : 1;
    printf("# rim (%.2f m, %d pixels) %-12s map %4d: V / V_exact mean %.4f min %.4f\n", RIM, r.n, method, map, r.mean,
           r.min);
    gkt_scene_free(&with);
    gkt_scene_free(&without);
    return r;
}

static void vssm_rim_matches_analytic(void **state)
{
    (void)state;
    rim_stats thesis = rim_measure("vssm_thesis", 1024), v1 = rim_measure("vssm", 1024),
              v2 = rim_measure("vssm", 2048), pcss = rim_measure("pcss", 1024), cssm = rim_measure("cssm", 1024);
    assert_true(v1.n > 300);
    /* Measured (llvmpipe, 446 rim pixels): vssm_thesis mean 0.924 min 0.618 at map 1024 (the
       defect); vssm 1.0000 / 1.0000 at 1024 and 2048; pcss and cssm 1.0000. Bounds: the baseline
       must show the defect (so the test can fail), the fixed one within 0.5% on average and 3% on
       any pixel (the one-texel tolerance of the point tests is the only slack left). */
    assert_true(thesis.mean < 0.97 && thesis.min < 0.8);
    assert_true(v1.mean > 0.995 && v1.min > 0.97);
    assert_true(v2.mean > 0.995 && v2.min > 0.97);
    assert_true(pcss.mean > 0.995 && cssm.mean > 0.995);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(vssm_rim_matches_analytic),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
