/* vct direct-light injection on llvmpipe: the voxels' radiance against the formula
 * L_o = rho / pi * I cos / d^2 (inject.comp), and shadowing from the light's shadow map
 * (gk_gi_light.shadow_depth_tex / shadow_view_proj) versus no shadow map; the injection's work
 * model (app/gi/vct/vct_work.c) against a hand count of the occupied voxels. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "test_vct_util.h"

static vt_gl g;

static int group_setup(void **state)
{
    (void)state;
    return vt_gl_init(&g);
}

static int group_teardown(void **state)
{
    (void)state;
    vt_gl_fini(&g);
    return 0;
}

/* Reads one z-slice of the level-0 radiance texture (RGBA16F) as floats. */
static void read_slice(void *vct, int res, int z, float *out)
{
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, gk_vct_radiance_texture(vct), 0, z);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, res, res, GL_RGBA, GL_FLOAT, out);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
}

/* Depth-only shadow map of the scene from the light (the test G-buffer program, no colour). */
static GLuint shadow_map(const vt_scene *sc, mat4 view_proj, int size)
{
    vt_frame f;
    memset(&f, 0, sizeof f);
    f.w = f.h = size;
    gkt_target(&f.gbuf, "test shadow map", size, size, 3, vt_gbuf_formats, true);
    f.view_proj = view_proj;
    f.eye = v3(0, 10, 0);
    vt_gbuffer(&g, &f, sc);
    GLuint depth = f.gbuf.depth;
    f.gbuf.depth = 0; /* kept: the caller owns the map */
    gk_target_destroy(&f.gbuf);
    return depth;
}

/* The floor's level-0 radiance (red) summed over the voxels whose centre lies in [x0, x1] x [z0, z1],
   and the largest relative error there against rho/pi I cos/d^2 from a point light at lp. */
typedef struct floor_region {
    float x0, x1, z0, z1;
    double sum, max_err;
    int n;
} floor_region;

static void floor_regions(void *vct, vec3 lp, float I, float rho, floor_region *r, int n_r)
{
    gk_vct_stats st;
    gk_vct_get_stats(vct, &st);
    int res = st.res;
    float *slice = malloc(sizeof(float) * 4 * res * res);
    int y0 = (int)floorf((0.0f - st.grid_origin[1]) / st.voxel_size);
    for (int z = 0; z < res; z++) {
        read_slice(vct, res, z, slice);
        for (int x = 0; x < res; x++) {
            const float *p = slice + ((size_t)y0 * res + x) * 4;
            vec3 c = v3(st.grid_origin[0] + (x + 0.5f) * st.voxel_size, 0, st.grid_origin[2] + (z + 0.5f) * st.voxel_size);
            for (int k = 0; k < n_r; k++) {
                if (p[3] < 0.5f || c.x < r[k].x0 || c.x > r[k].x1 || c.z < r[k].z0 || c.z > r[k].z1)
                    continue;
                vec3 d = v3_sub(lp, c);
                float d2 = v3_dot(d, d);
                float expect = rho / 3.14159265f * I * (d.y / sqrtf(d2)) / d2;
                r[k].sum += p[0];
                r[k].max_err = fmax(r[k].max_err, fabs(p[0] - expect) / expect);
                r[k].n++;
            }
        }
    }
    free(slice);
}

/* A unit floor of albedo rho, a grey occluder above it (y = 0.5), with `marker` a black speck at
   y = 1 that stretches the grid's bounds (above the light: outside its map); a point light of
   intensity I at lp = (0.5, 0.9, 0.5) with a 126-degree perspective shadow map of 256² (the floor's
   corners are 38 degrees off its axis); a 16² view from above with its G-buffer. Returns the map. */
static GLuint floor_under_light(vt_scene *sc, float rho, float I, bool marker, gk_gi_light *L, vt_frame *f)
{
    vt_scene_init(sc);
    vt_add_quad(sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), v3(rho, rho, rho));               /* floor */
    vt_add_quad(sc, v3(0.1f, 0.5f, 0.1f), v3(0, 0, 0.3f), v3(0.3f, 0, 0), v3(0.5f, 0.5f, 0.5f)); /* occluder */
    if (marker)
        vt_add_quad(sc, v3(0, 1, 0), v3(0.01f, 0, 0), v3(0, 0, 0.01f), v3(0, 0, 0));
    vt_scene_finish(sc);
    vec3 lp = v3(0.5f, 0.9f, 0.5f);
    *L = vt_light(sc, GK_LIGHT_POINT, lp, v3(0, -1, 0), v3(I, I, I), 1);
    mat4 view = m4_look_at(lp, v3(lp.x, 0, lp.z), v3(0, 0, -1));
    L->shadow_view_proj = m4_mul(m4_perspective(2.2f, 1.0f, 0.05f, 3.0f), view);
    L->shadow_is_perspective = true;
    L->shadow_near = 0.05f, L->shadow_far = 3.0f; /* the injection compares distances along the map's axis */
    GLuint depth = shadow_map(sc, L->shadow_view_proj, 256);
    vt_frame_create(f, 16, 16, v3(0.5f, 1.5f, 0.51f), v3(0.5f, 0, 0.5f), v3(0, 0, -1), 0.5f);
    vt_gbuffer(&g, f, sc);
    return depth;
}

static void injection_matches_formula_and_uses_the_shadow_map(void **state)
{
    (void)state;
    vt_scene sc;
    const float rho = 0.6f, I = 3.0f;
    gk_gi_light L;
    vt_frame f;
    GLuint depth = floor_under_light(&sc, rho, I, true, &L, &f);
    vec3 lp = L.position;
    gk_budget b;
    vt_budget(&b, "vct_res=32,vct_trace_scale=1");
    /* under the occluder (umbra: x, z < 0.275), and the open floor: x or z > 0.6, within [0.05, 0.95] */
    floor_region under[2] = {{0.05f, 0.22f, 0.05f, 0.22f, 0, 0, 0}, {0.05f, 0.22f, 0.05f, 0.22f, 0, 0, 0}};
    floor_region open[2] = {{0.6f, 0.95f, 0.05f, 0.95f, 0, 0, 0}, {0.05f, 0.6f, 0.6f, 0.95f, 0, 0, 0}};
    for (int with_map = 0; with_map < 2; with_map++) {
        L.shadow_depth_tex = with_map ? depth : 0;
        void *vct = vt_create(&g);
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        floor_regions(vct, lp, I, rho, &under[with_map], 1);
        if (with_map)
            floor_regions(vct, lp, I, rho, open, 2);
        gk_gi_vct.destroy(vct);
    }
    double shadowed[2] = {under[0].sum, under[1].sum}, lit_err = fmax(open[0].max_err, open[1].max_err);
    int n_sh[2] = {under[0].n, under[1].n}, n_lit = open[0].n + open[1].n;
    printf("# injection: floor under the occluder %.4f nits without shadow map, %.4f with; "
           "largest relative error against rho/pi I cos/d^2 in the open: %.2f%% (%d voxels)\n",
           shadowed[0] / n_sh[0], shadowed[1] / n_sh[1], 100 * lit_err, n_lit);
    assert_true(n_sh[0] > 10 && n_sh[1] > 10 && n_lit > 50);
    assert_true(shadowed[0] / n_sh[0] > 0.1);           /* lit when no shadow map is given */
    assert_true(shadowed[1] / n_sh[1] < 1e-3);          /* dark with it */
    /* The floor voxels' mean position is the voxel centre projected on the floor (conservative
       voxelizer), where the formula is evaluated here, so only RGBA16F rounding (2^-11 = 0.05%
       relative) and the 8-bit position quantisation remain: measured 0.11%; bound 0.5%. */
    assert_true(lit_err < 0.005);
    glDeleteTextures(1, &depth);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

/* the `pass` entry of the last frame's work (of kind `kind`), or -1 */
static double work_of(void *vct, const char *pass, const char *kind)
{
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_gi_vct.pass_work(vct, w, GK_MAX_PASS_WORK);
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].pass, pass)) {
            assert_string_equal(w[i].kind, kind);
            return w[i].fetches;
        }
    return -1.0;
}

static double inject_fetches(void *vct) { return work_of(vct, "gi.vct_inject", "tex2d_depth32f_nearest"); }
static double voxelize_atomics(void *vct) { return work_of(vct, "gi.vct_voxelize", "ssbo_r32ui_atomic"); }

/* A floor and an occluder under a point light whose shadow map sees all of both: every occupied
   voxel's lookup lands in the map, so the injection fetches 9 depth texels (3x3 PCF) per occupied
   voxel, counted here from the injected level 0 (alpha 1 where occupied). Without a shadow map it
   fetches none; outside a counting frame nothing is counted; a frame that does not re-inject
   reports no injection. The voxelizer's atomics (vct_work.c): 10 per voxel a triangle wrote (the
   count and 3 x albedo, normal, position), so 10 x the sum of the scratch's count channel. */
static void injection_fetches_nine_per_occupied_voxel(void **state)
{
    (void)state;
    vt_scene sc;
    gk_gi_light L;
    vt_frame f;
    GLuint depth = floor_under_light(&sc, 0.6f, 3.0f, false, &L, &f); /* no marker: all inside the map */
    gk_budget b;
    vt_budget(&b, "vct_res=32,vct_trace_scale=1");
    for (int with_map = 0; with_map < 2; with_map++) {
        L.shadow_depth_tex = with_map ? depth : 0;
        void *vct = vt_create(&g);
        f.count_work = false;
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        assert_true(inject_fetches(vct) < 0.0 && voxelize_atomics(vct) < 0.0); /* ran, not counted */
        gk_gi_vct.invalidate(vct);               /* re-voxelize and re-inject, counting */
        f.count_work = true;
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        double counted = inject_fetches(vct), atomics = voxelize_atomics(vct);
        gk_vct_stats st;
        gk_vct_get_stats(vct, &st);
        long n_scratch = 0;
        unsigned *scratch = vt_read_scratch(vct, &n_scratch);
        assert_non_null(scratch);
        double written = 0.0; /* channel 0 (CH_COUNT, vct/common.glsl): a voxel's writes */
        for (long i = 0; i < (long)st.res * st.res * st.res; i++)
            written += scratch[i];
        free(scratch);
        printf("# voxelize: %.0f voxel writes, %.0f atomics counted\n", written, atomics);
        assert_true(written > 0.0 && atomics == 10.0 * written);
        float *slice = malloc(sizeof(float) * 4 * st.res * st.res);
        long occupied = 0;
        for (int z = 0; z < st.res; z++) {
            read_slice(vct, st.res, z, slice);
            for (long i = 0; i < (long)st.res * st.res; i++)
                occupied += slice[i * 4 + 3] > 0.5f;
        }
        free(slice);
        printf("# injection %s shadow map: %ld occupied voxels of %d^3, %.0f shadow fetches counted\n",
               with_map ? "with" : "without", occupied, st.res, counted);
        assert_true(occupied > st.res * st.res / 2); /* the floor's layer at least */
        if (with_map)
            assert_true(counted == 9.0 * (double)occupied);
        else
            assert_true(counted < 0.0); /* no map, no fetches: no entry */
        f.count_work = true;            /* a counting frame that does not re-inject: no entry */
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        assert_true(inject_fetches(vct) < 0.0 && voxelize_atomics(vct) < 0.0);
        gk_gi_vct.destroy(vct);
    }
    glDeleteTextures(1, &depth);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

/* A thin wall (two faces 2 cm apart, 0.6 high) splits the floor; a point light 0.7 above the floor on
   one side. Light-leak's two faults of injection, each in a light map the renderer makes
   (render_gi.c: perspective, near plane 1 mm .. 1 cm): (a) the shadow bias, once 0.0015 of window
   depth, which with a near plane at 1 mm is 0.7 m of depth at the floor 0.7 m below the light (depth
   changes by near / z^2 a metre), so the dark floor behind the wall was lit; (b) a map narrower than the light's reach (a point light's 160-degree face):
   voxels outside it were lit through the wall, now a voxel ray decides. */
static void injection_shadows_behind_a_thin_wall_inside_and_outside_the_map(void **state)
{
    (void)state;
    vt_scene sc;
    vt_scene_init(&sc);
    const float rho = 0.6f, I = 3.0f;
    vt_add_quad(&sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), v3(rho, rho, rho));             /* floor, +y */
    vt_add_quad(&sc, v3(0.49f, 0, 0), v3(0, 0, 1), v3(0, 0.6f, 0), v3(0.5f, 0.5f, 0.5f));   /* lit face, -x */
    vt_add_quad(&sc, v3(0.51f, 0, 0), v3(0, 0.6f, 0), v3(0, 0, 1), v3(0.5f, 0.5f, 0.5f));   /* dark face, +x */
    vt_add_quad(&sc, v3(0, 1, 0), v3(0.01f, 0, 0), v3(0, 0, 0.01f), v3(0, 0, 0));             /* bounds marker */
    vt_scene_finish(&sc);
    vec3 lp = v3(0.2f, 0.7f, 0.5f);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, lp, v3(0, -1, 0), v3(I, I, I), 1);
    mat4 view = m4_look_at(lp, v3(lp.x, 0, lp.z), v3(0, 0, -1));
    L.shadow_is_perspective = true;
    L.shadow_near = 0.001f, L.shadow_far = 2.0f;
    vt_frame f;
    vt_frame_create(&f, 16, 16, v3(0.5f, 1.5f, 0.51f), v3(0.5f, 0, 0.5f), v3(0, 0, -1), 0.5f);
    vt_gbuffer(&g, &f, &sc);
    gk_budget b;
    vt_budget(&b, "vct_res=32,vct_trace_scale=1");
    /* (a) fov 1.2 rad: the map reaches x <= 0.68 at the floor; (b) fov 0.6 rad: x in [-0.02, 0.42],
       z in [0.28, 0.72]. The dark floor's regions start 2 voxels (7 cm) from the wall, past the
       voxels that hold both faces. */
    static const float fovs[2] = {1.2f, 0.6f};
    floor_region dark[2] = {{0.58f, 0.66f, 0.3f, 0.7f, 0, 0, 0}, {0.58f, 0.95f, 0.05f, 0.95f, 0, 0, 0}};
    floor_region lit_outside[2] = {{0}, {0.05f, 0.4f, 0.05f, 0.22f, 0, 0, 0}};
    for (int i = 0; i < 2; i++) {
        L.shadow_view_proj = m4_mul(m4_perspective(fovs[i], 1.0f, L.shadow_near, L.shadow_far), view);
        GLuint depth = shadow_map(&sc, L.shadow_view_proj, 256);
        L.shadow_depth_tex = depth;
        void *vct = vt_create(&g);
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        floor_region r[2] = {dark[i], lit_outside[i]};
        floor_regions(vct, lp, I, rho, r, i == 1 ? 2 : 1);
        printf("# thin wall, map fov %.1f: dark floor %d voxels, mean %.5f nits%s", fovs[i], r[0].n, r[0].sum / r[0].n,
               i == 1 ? "" : "\n");
        if (i == 1)
            printf("; lit floor outside the map %d voxels, largest error %.2f%%\n", r[1].n, 100 * r[1].max_err);
        assert_true(r[0].n > 10);
        /* the lit floor there is ~0.6 nits: dark is 0 up to RGBA16F's zero */
        assert_true(r[0].sum / r[0].n < 1e-4);
        if (i == 1) {
            /* lit outside the map: the voxel ray finds nothing in its way; the formula's bound as above */
            assert_true(r[1].n > 10);
            assert_true(r[1].max_err < 0.005);
        }
        gk_gi_vct.destroy(vct);
        glDeleteTextures(1, &depth);
    }
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

/* The compose's (gi.vct_compose) count of `kind`, or -1 */
static double compose_work(void *vct, const char *kind)
{
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_gi_vct.pass_work(vct, w, GK_MAX_PASS_WORK);
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].pass, "gi.vct_compose") && !strcmp(w[i].kind, kind))
            return w[i].fetches;
    return -1.0;
}

/* The compose's reads (vct_work.c) against a hand count: the 16x16 view looks straight down at the
   floor, which fills it (checked on the G-buffer's positions), so every pixel and every tap is a
   surface. At trace_scale 1 a pixel reads its depth and its 2 traced texels: 2 W H texels, W H depth
   reads; at 0.5 (2x2 blocks) its depth, then for each of its 3x3 taps the tap's depth and 2 texels:
   18 W H texels, 10 W H depth reads. Nothing is reported outside a counting frame. */
static void compose_reads_by_hand(void **state)
{
    (void)state;
    vt_scene sc;
    gk_gi_light L;
    vt_frame f;
    GLuint depth = floor_under_light(&sc, 0.6f, 3.0f, false, &L, &f);
    L.shadow_depth_tex = depth;
    float pos[16 * 16 * 4];
    vt_read_positions(&f, pos);
    for (int i = 0; i < 16 * 16; i++)
        assert_true(pos[4 * i + 3] != 0.0f); /* a surface */
    static const char *const pins[] = {"vct_res=32,vct_trace_scale=1", "vct_res=32,vct_trace_scale=0.5"};
    static const double texels[] = {2.0 * 256, 18.0 * 256}, depths[] = {256.0, 10.0 * 256};
    for (int k = 0; k < 2; k++) {
        gk_budget b;
        vt_budget(&b, pins[k]);
        void *vct = vt_create(&g);
        f.count_work = false;
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        assert_true(compose_work(vct, "tex2d_rgba32f_nearest") < 0.0 && compose_work(vct, "tex2d_depth32f_nearest") < 0.0);
        f.count_work = true;
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        double t = compose_work(vct, "tex2d_rgba32f_nearest"), d = compose_work(vct, "tex2d_depth32f_nearest");
        printf("# compose at %s: %.0f low-resolution texels, %.0f depth reads\n", pins[k], t, d);
        assert_true(t == texels[k] && d == depths[k]);
        gk_gi_vct.destroy(vct);
    }
    glDeleteTextures(1, &depth);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(injection_matches_formula_and_uses_the_shadow_map),
        cmocka_unit_test(injection_fetches_nine_per_occupied_voxel),
        cmocka_unit_test(injection_shadows_behind_a_thin_wall_inside_and_outside_the_map),
        cmocka_unit_test(compose_reads_by_hand),
    };
    return cmocka_run_group_tests_name("vct_inject", tests, group_setup, group_teardown);
}
