/* volcaustics' counted airlight and composite reads (app/gi/volcaustics/vc_work.c, #21) against hand
 * counts (the composite's: composite_reads_by_hand, below), on
 * glass-fog through vpl's harness (tests/gpu/test_vpl_harness.h: its loaded-scene set-up, G-buffer
 * and frame, with volcaustics in place of vpl): with its medium filling all of space (every
 * view ray marches through it: none is empty), its light made a point light (no spot cone skips a
 * step) and given a shadow map whose projection holds every point the march can reach, each march
 * pixel reads its G-buffer depth once and one shadow texel per step (VC_AIR_STEPS, 48) -- (1 + 48) x
 * the march pixels, whatever the surfaces are; without a shadow map it reads the G-buffer alone.
 * (With the scene's own medium, a box, the view rays that miss it before their surface read no
 * shadow texel: 44 a pixel on average at 32x24.) The other passes' counts (ray generation, lines,
 * splats) depend on the rays and are checked against each other and their bounds in
 * tests/e2e/efficiency.sh. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>

#include <cmocka.h>

#include "gi/volcaustics/vc_internal.h"
#include "gi/volcaustics/volcaustics.h"
#include "scene/scene.h"
#include "test_pass_work.h"
#include "test_vpl_harness.h"

extern const gk_gi_method gk_gi_volcaustics;

#define W 64
#define HH 48
#define AIR_STEPS 48 /* app/gi/volcaustics/vc_terms.c VC_AIR_STEPS */

static vpl_h H;
static gk_scene *S;

/* The harness on scene `sc` (its camera and first light), with volcaustics as its method. */
static int open_on(gk_scene *sc)
{
    gk_err e = {0};
    if (h_init_with(&H, false, W, HH, sc) != 0)
        return -1;
    /* the harness's method is vpl: volcaustics instead, on the same scene and G-buffer */
    H.m->destroy(H.self);
    H.self = NULL;
    H.m = &gk_gi_volcaustics;
    gk_gi_context ctx = {.programs = H.programs, .gles_version = H.gl.egl.gles_version};
    H.self = H.m->create(&ctx, &e);
    return H.self && H.m->set_scene(H.self, &H.scene, &e) == 0 ? 0 : -1;
}

static int setup(void **state)
{
    (void)state;
    gk_err e = {0};
    S = gk_scene_load("config/scenes/glass-fog.gltf", &e);
    return S ? open_on(S) : -1;
}

static int teardown(void **state)
{
    (void)state;
    h_free(&H);
    gk_scene_free(S);
    return 0;
}

/* One counting frame (the bench's) at `list`. */
static void counting_frame(const char *list)
{
    assert_int_equal(h_budget(&H, list), 0);
    H.count_work = true;
    assert_int_equal(h_frame(&H, 0.0), 0);
    H.count_work = false;
}

/* One counting frame at `list`; the airlight's counted reads (0 when none). */
static double airlight_reads(const char *list)
{
    counting_frame(list);
    double reads = tpw_fetches(H.m, H.self, "gi.vc_airlight", "tex2d_depth32f_nearest");
    return reads < 0.0 ? 0.0 : reads;
}

static void airlight_reads_by_hand(void **state)
{
    (void)state;
    H.scene.lights[H.gl_light.scene_light].type = GK_LIGHT_POINT;
    H.scene.medium.bounded = false;
    /* without a shadow map: the G-buffer's depth, once per march pixel */
    double none = airlight_reads("vc_march=0.5");
    const gk_volcaustics_stats *st = gk_volcaustics_get_stats(H.self);
    double pixels = (double)st->march_w * st->march_h;
    /* a 1x1 depth map whose orthographic projection spans +-2e6 m: the march's farthest points (1e6 m
       through an opening) still land in it */
    GLuint depth;
    glGenTextures(1, &depth);
    glBindTexture(GL_TEXTURE_2D, depth);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, 1, 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    H.gl_light.shadow_depth_tex = depth;
    H.gl_light.shadow_view_proj = m4_ortho(-2e6f, 2e6f, -2e6f, 2e6f, -2e6f, 2e6f);
    double shadowed = airlight_reads("vc_march=0.5");
    printf("# glass-fog, march %dx%d: %.0f reads without a shadow map, %.0f with one\n", st->march_w, st->march_h, none,
           shadowed);
    H.gl_light.shadow_depth_tex = 0;
    glDeleteTextures(1, &depth);
    assert_true(pixels > 0);
    assert_true(none == pixels);
    assert_true(shadowed == pixels * (1 + AIR_STEPS));
}

/* One counting frame at `list`: the composite's counted reads by kind (depth, airlight, caustic
   images; -1 where none). */
static void composite_reads(const char *list, double r[3])
{
    static const char *const kinds[3] = {"tex2d_depth32f_nearest", "tex2d_rgba16f_trilinear", "tex2d_rgba32f_nearest"};
    counting_frame(list);
    for (int k = 0; k < 3; k++)
        r[k] = tpw_fetches(H.m, H.self, "gi.vc_composite", kinds[k]);
    printf("# glass-fog %s: composite %.0f depth, %.0f airlight, %.0f caustic texels\n", list, r[0], r[1], r[2]);
}

/* The composite's reads against a hand count on glass-fog as shipped (its spot lights the glass:
   lines and surface caustics to show). With every term shown, per pixel: the depth for the
   attenuated surfaces and again for the surface caustics, the airlight image and the lines' image
   once, and the surface caustics' irradiance at each pixel that holds a surface -- here every one:
   the camera is inside the room (the G-buffer's albedo, read back, is set at every pixel). With the
   airlight term alone: its image once a pixel, nothing else. */
static void composite_reads_by_hand(void **state)
{
    (void)state;
    double r[3], pixels = (double)W * HH;
    unsigned char *albedo = malloc((size_t)W * HH * 4);
    gkt_read_rgba(&H.gbuf, 0, GL_UNSIGNED_BYTE, albedo);
    long surfaces = 0;
    for (int i = 0; i < W * HH; i++)
        surfaces += albedo[4 * i] || albedo[4 * i + 1] || albedo[4 * i + 2];
    free(albedo);
    composite_reads("vc_output=all,vc_surface=splat", r);
    const gk_volcaustics_stats *st = gk_volcaustics_get_stats(H.self);
    assert_true(st->light_ok);
    assert_true(surfaces == W * HH);
    assert_true(r[0] == 2 * pixels && r[1] == pixels && r[2] == pixels + (double)surfaces);
    composite_reads("vc_output=airlight", r);
    assert_true(r[0] == -1.0 && r[1] == pixels && r[2] == -1.0);
}

/* The light views' scene: a floor wider than any light view of it, a spot 3 m over it looking down
   and a glass rectangle at 1 m under the spot, off-centre (its edges fall between pixel centres),
   in a fog (volcaustics runs only where a medium is). */
static gkt_scene V;
static const float GLASS[4] = {-0.3f, 0.25f, -0.2f, 0.35f}; /* x0, x1, z0, z1 at y = 1 */

static int setup_views(void **state)
{
    (void)state;
    gkt_scene_init(&V, "vc-work-views");
    int grey = gkt_material_lambert(&V, v3(0.5f, 0.5f, 0.5f)), glass = gkt_material(&V, v3(1, 1, 1), 0.0f, 0.0f);
    V.mats[glass].transmission = 1.0f;
    gkt_quad(&V, v3(-10, 0, -10), v3(10, 0, -10), v3(10, 0, 10), v3(-10, 0, 10), v3(0, 1, 0), grey);
    gkt_quad(&V, v3(GLASS[0], 1, GLASS[2]), v3(GLASS[1], 1, GLASS[2]), v3(GLASS[1], 1, GLASS[3]),
             v3(GLASS[0], 1, GLASS[3]), v3(0, 1, 0), glass);
    gkt_light(&V, GK_LIGHT_SPOT, GK_SHAPE_POINT, 50.0f, v3(0, 3, 0), v3(0, -1, 0));
    gkt_camera(&V, v3(0, 2, 2), v3(0, 0, 0), 1.0f);
    gkt_scene_bounds(&V);
    V.s.medium = (gk_medium){.present = true, .sigma_s = {0.05f, 0.05f, 0.05f}, .g = 0.0f}; /* fog filling space */
    gk_scene_evaluate(&V.s, 0.0f); /* the light node's world matrix (the harness reads the light from it) */
    return open_on(&V.s);
}

static int teardown_views(void **state)
{
    (void)state;
    h_free(&H);
    gkt_scene_free(&V);
    return 0;
}

/* The light views' fragments against a hand count: the view is framed on the glass's bounding
   sphere, so the floor covers every texel of each of the three views (front, without the specular
   objects, their back faces: each draws the whole scene and discards after counting) and the glass
   the texels whose centres its rectangle covers, counted here from its corners projected by the
   light's view (vc_state's, as lightview.vert projects them): 3 x (R² + glass texels). */
static void light_view_fragments_by_hand(void **state)
{
    (void)state;
    counting_frame("vc_buffer=128");
    const vc_state *s = H.self;
    assert_true(s->st.caustic_lights == 1 && s->light[0].ok);
    int r = s->lv.width;
    double px[4][2];
    const float corner[4][2] = {{GLASS[0], GLASS[2]}, {GLASS[1], GLASS[2]}, {GLASS[1], GLASS[3]}, {GLASS[0], GLASS[3]}};
    for (int k = 0; k < 4; k++) {
        const float *m = s->light[0].vp.m;
        float x = corner[k][0], y = 1.0f, z = corner[k][1];
        float cx = m[0] * x + m[4] * y + m[8] * z + m[12], cy = m[1] * x + m[5] * y + m[9] * z + m[13];
        float cw = m[3] * x + m[7] * y + m[11] * z + m[15];
        px[k][0] = ((double)cx / cw * 0.5 + 0.5) * r;
        px[k][1] = ((double)cy / cw * 0.5 + 0.5) * r;
    }
    long glass = 0;
    for (int j = 0; j < r; j++)
        for (int i = 0; i < r; i++) {
            int pos = 0, neg = 0;
            for (int k = 0; k < 4; k++) {
                const double *a = px[k], *b = px[(k + 1) % 4];
                double e = (b[0] - a[0]) * (j + 0.5 - a[1]) - (b[1] - a[1]) * (i + 0.5 - a[0]);
                pos += e > 0, neg += e < 0;
            }
            glass += pos == 4 || neg == 4;
        }
    double counted = tpw_fetches(H.m, H.self, "gi.vc_light", "raster_r16f_depth_fill");
    printf("# light views of %d^2: %.0f fragments counted, 3 x (%d + %ld glass texels) = %.0f by hand\n", r, counted,
           r * r, glass, 3.0 * ((double)r * r + glass));
    assert_true(glass > 0 && glass < r * r);
    assert_true(counted == 3.0 * ((double)r * r + glass));
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(composite_reads_by_hand), cmocka_unit_test(airlight_reads_by_hand)};
    const struct CMUnitTest views[] = {cmocka_unit_test(light_view_fragments_by_hand)};
    int failed = cmocka_run_group_tests(tests, setup, teardown);
    return failed + cmocka_run_group_tests_name("light views", views, setup_views, teardown_views);
}
