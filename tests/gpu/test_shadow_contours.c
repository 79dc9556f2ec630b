/* Contour lines of VSSM on the walls of a Cornell room (#11). The room of the cornell scene
 * (0.556 x 0.549 x 0.559 m, white), its ceiling light (a 0.13 x 0.105 m rect POINT light just under
 * the ceiling: cube-face maps, the walls' lower halves in the downward face, where a wall is
 * parallel to the face's axis, so seen at grazing angles), and no boxes: every wall point sees
 * the whole light, so the exact visibility is 1 everywhere on the walls. A method's V = L /
 * L(hard shadows) on the wall pixels; a wall pixel is "dark" when V < 0.97, and a contour line is
 * a run of dark pixels along an image row: the test counts runs (lines crossed, summed over the
 * rows) and dark pixels.
 * The cause (found with a shader that painted each code path): with one receiver depth d for the
 * whole kernel, the wall's own texels nearer the light lie in front of d, so the blocker search
 * and the subdivided kernels found "blockers" on the lit wall; the bands follow where the
 * kernel's integer width and the code path (Chebyshev on the whole kernel, adaptive subdivision,
 * no blocker) switch. Not the SAT's precision: the integer SATs are exact (F7 in
 * test_shadow_failures2.c), and the bands go with the receiver plane on the same 16-bit SATs
 * (map 1024; 15 bits at 2048 gives the same counts). The fix is the
 * receiver plane of every sub-kernel (VSSM_RECEIVER_PLANE, shaders_gles/shadow/vssm.glsl);
 * vssm_thesis is the baseline without it. The line it left along the wall-floor corners (106
 * runs) was not the contact PCF (without it, vssm_nocontact's shader, the same 106 runs and 288
 * dark pixels) but the blocker search's kernel: the light's footprint on the near plane, clamped
 * to a quarter of the map, took in the other walls' texels beside the light's footprint, so lit
 * corner pixels got a blocker depth and a penumbra kernel across the corner. #21's search bound
 * (VSSM_SEARCH_BOUND: the footprint on the plane of the HSM's nearest depth, z_occ bounded by
 * that depth) removes it; vssm_thesis keeps the near-plane kernel.
 * The same walls for CSSM (cssm_thesis the baseline).
 * 256x256 pixels, map 1024 (the default). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gpu/test_shadow_util.h"

#define W 256
#define H 256
#define RX 0.556f
#define RY 0.5488f
#define RZ 0.559f
#define DARK 0.97f

static const gk_knob_def knob_contours = {
    .name = "shadow", .owner = "test", .n_values = 8,
    .values = {"hard", "pcss", "vssm", "cssm", "vssm_thesis", "cssm_sat", "cssm_thesis", "cssm_plane"},
    .cost = {1, 1, 1, 1, 1, 1, 1, 1}, .default_level = 0,
};

static sx_session ses;

static int setup(void **state)
{
    (void)state;
    return sx_open_knob(&ses, W, H, &knob_contours);
}

static int teardown(void **state)
{
    (void)state;
    sx_close(&ses);
    return 0;
}

static void room(fx_scene *f)
{
    fx_init(f, v3(0.278f, 0.273f, -0.8f), v3(0.278f, 0.273f, 0.2795f), 0.69f);
    f->s.bmin = v3(0, 0, 0);
    f->s.bmax = v3(RX, RY, RZ);
    int white = fx_material(f, 0.8f, 0, 0.9f);
    gkt_quad(f, v3(0, 0, 0), v3(RX, 0, 0), v3(RX, 0, RZ), v3(0, 0, RZ), v3(0, 1, 0), white);          /* floor */
    gkt_quad(f, v3(0, RY, 0), v3(RX, RY, 0), v3(RX, RY, RZ), v3(0, RY, RZ), v3(0, -1, 0), white);     /* ceiling */
    gkt_quad(f, v3(0, 0, 0), v3(0, RY, 0), v3(0, RY, RZ), v3(0, 0, RZ), v3(1, 0, 0), white);          /* left */
    gkt_quad(f, v3(RX, 0, 0), v3(RX, RY, 0), v3(RX, RY, RZ), v3(RX, 0, RZ), v3(-1, 0, 0), white);     /* right */
    gkt_quad(f, v3(0, 0, RZ), v3(RX, 0, RZ), v3(RX, RY, RZ), v3(0, RY, RZ), v3(0, 0, -1), white);     /* back */
    gk_light *l = gkt_light(f, GK_LIGHT_POINT, GK_SHAPE_RECT, 0.23f, v3(0.278f, 0.5487f, 0.2795f), v3(0, -1, 0));
    l->size[0] = 0.13f;
    l->size[1] = 0.105f;
}

/* Which wall the camera ray of pixel (x, y) hits first: 1 left, 2 right, 3 back, 0 floor, ceiling
   or a wall hit within 1 cm of another surface (the corners, where pixels mix surfaces). */
static int wall_of(fx_scene *f, int x, int y)
{
    mat4 view, proj;
    vec3 eye;
    gk_scene_evaluate(&f->s, 0);
    gk_scene_camera(&f->s, (float)W / (float)H, &view, &proj, &eye);
    mat4 inv = m4_inverse(m4_mul(proj, view));
    float nx = ((float)x + 0.5f) / (float)W * 2 - 1, ny = 1 - ((float)y + 0.5f) / (float)H * 2;
    vec4 a = m4_vec4(inv, (vec4){nx, ny, -1, 1}), b = m4_vec4(inv, (vec4){nx, ny, 1, 1});
    vec3 pa = v3(a.x / a.w, a.y / a.w, a.z / a.w), d = v3_sub(v3(b.x / b.w, b.y / b.w, b.z / b.w), pa);
    const float m = 0.01f;
    float t[3] = {fabsf(d.x) > 1e-9f ? -pa.x / d.x : -1, fabsf(d.x) > 1e-9f ? (RX - pa.x) / d.x : -1,
                  fabsf(d.z) > 1e-9f ? (RZ - pa.z) / d.z : -1};
    for (int k = 0; k < 3; k++) {
        if (t[k] <= 0)
            continue;
        vec3 p = v3_add(pa, v3_scale(d, t[k]));
        bool in = p.y > m && p.y < RY - m && (k < 2 ? p.z > m && p.z < RZ - m : p.x > m && p.x < RX - m);
        if (in)
            return k + 1;
    }
    return 0;
}

typedef struct contour_count {
    int lines, dark, wall;
    double mean_v;          /* mean V over the wall pixels (exact: 1) */
} contour_count;

static contour_count count_contours(const char *method, int map)
{
    fx_scene f;
    room(&f);
    static float a[W * H], b[W * H];
    static unsigned char wall[W * H];
    char pins[96];
    gk_err e = {0};
    snprintf(pins, sizeof pins, "shadow=%s,shadow_map=%d", method, map);
    if (gk_renderer_set_scene(ses.r, &f.s, &e) != 0 || sx_draw(&ses, "shadow=hard,shadow_map=1024", b) != 0 ||
        sx_draw(&ses, pins, a) != 0)
        fail_msg("render %s: %s", pins, e.msg);
    gk_renderer_set_scene(ses.r, NULL, &e);
    contour_count c = {0};
    for (int y = 0; y < H; y++) {
        bool prev = false;
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            wall[i] = (unsigned char)wall_of(&f, x, y);
            bool dark = false;
            if (wall[i] && b[i] > 1e-4f) {
                c.wall++;
                dark = a[i] / b[i] < DARK;
                c.mean_v += a[i] / b[i];
                c.dark += dark;
            }
            c.lines += dark && !prev;
            prev = dark;
        }
    }
    c.mean_v /= c.wall > 0 ? c.wall : 1;
    printf("# %-12s map %4d: %d contour runs, %d dark pixels (V < %.2f) of %d wall pixels, mean V %.4f\n", method,
           map, c.lines, c.dark, DARK, c.wall, c.mean_v);
    gkt_scene_free(&f);
    return c;
}

static void vssm_walls_have_no_contours(void **state)
{
    (void)state;
    contour_count thesis = count_contours("vssm_thesis", 1024), v1 = count_contours("vssm", 1024),
                  v2 = count_contours("vssm", 2048), pcss = count_contours("pcss", 1024),
                  cssm = count_contours("cssm", 1024), csat = count_contours("cssm_sat", 1024),
                  cthesis = count_contours("cssm_thesis", 1024), cplane = count_contours("cssm_plane", 1024);
    assert_true(v1.wall > W * H / 4);
    /* Measured (llvmpipe, 37630 wall pixels): contour runs / dark pixels, mean V
         vssm_thesis 1024: 667 / 10615, 0.918   (bands over the walls' lower halves)
         vssm        1024:   0 / 0,     1.0000  (before #21's search bound: 106 / 288, 0.9989,
         vssm        2048:  12 / 12,    1.0000   110 / 398, 0.9986: a line one or two pixels
                                                 high along the wall-floor corners)
         pcss        1024:   2 / 2
         cssm        1024: 376 / 12900   (the K = 4 series' own error, #11's CSSM item)
       Bounds: vssm as clean as pcss's bound at map 1024 (5), at 2048 1.5x its measurement (18);
       a fiftieth of the baseline's dark pixels; the baseline above 100 runs (the test can fail). */
    assert_true(v1.lines <= 5 && v2.lines <= 18);
    assert_true(v1.dark <= 5 && v2.dark <= 18 && v1.dark * 50 < thesis.dark && v2.dark * 50 < thesis.dark);
    assert_true(v1.mean_v > 0.9995 && v2.mean_v > 0.9995);
    assert_true(thesis.lines > 100);
    assert_true(pcss.lines <= 5);
    /* CSSM on the same walls (#11: 5.3% too dark on the Cornell walls against the path tracer):
       measured mean V cssm 0.986, cssm_sat 0.986 (234 runs, 9190 dark pixels: a faint uniform
       step on the upper side walls, V ~ 0.96), cssm_thesis 0.910 (376 runs, 12900 dark pixels:
       bands on the lower halves, where the walls are inclined to the downward face and their own
       samples spread past the series' 0.064 transition; the slope-scaled shift CSSM_SLOPE and
       the per-layer depth range fix them). Bounds: cssm and cssm_sat within 2% of the light on
       average, the baseline below 0.95. */
    assert_true(cssm.mean_v > 0.98 && csat.mean_v > 0.98);
    assert_true(cthesis.mean_v < 0.95);
    /* cssm_plane (the environment's lights, #11) is no method for these walls: measured mean V
       0.883 (561 runs, 21028 dark pixels; 0.900 with its blocker search subdivided too). Its
       sub-kernels are at most 3 x 3, and the walls' lower halves lie almost along the downward
       face's axis, so each sub-kernel still spans far more depth than the series' shift; the cssm
       knob level keeps its slope-scaled shift for them. Bound: its measurement less 0.01, so a
       change that darkens it further shows here. */
    assert_true(cplane.mean_v > 0.873);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(vssm_walls_have_no_contours),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
