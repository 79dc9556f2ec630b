/* vct light leaking (summary A.6.1 #1 and #2b), measured as numbers on llvmpipe:
 *  - thin-wall rays: 0-degree rays through the real cone loop across one plane, conservative vs
 *    thin voxelization (P.3);
 *  - partition: a zero-thickness wall splits a box, only one side is lit; dark-side / lit-side
 *    indirect luminance through the whole method (P.4). */
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

/* ---- thin-wall rays ------------------------------------------------------------------------- */
typedef struct leak_result {
    double half, full;   /* fraction of rays with accumulated alpha < 0.5 / < 0.05 */
    long occupied;       /* voxels the plane occupies */
} leak_result;

static leak_result thin_wall(vec3 normal, bool conservative, float offset)
{
    leak_result r = {-1, -1, 0};
    vt_scene sc;
    vt_scene_init(&sc);
    vec3 n = v3_norm(normal);
    vec3 t = v3_norm(v3_cross(fabsf(n.y) < 0.9f ? v3(0, 1, 0) : v3(1, 0, 0), n));
    vec3 b = v3_cross(n, t);
    vec3 c = v3(0.5f, 0.5f, 0.5f);
    vt_add_quad(&sc, v3_sub(c, v3_scale(v3_add(t, b), 0.5f)), t, b, v3(0.5f, 0.5f, 0.5f));
    vt_scene_finish(&sc);
    void *vct = vt_create(&g);
    gk_vct_options o;
    gk_vct_default_options(&o);
    o.conservative = conservative;
    o.grid_offset[0] = offset, o.grid_offset[1] = 0.7f * offset, o.grid_offset[2] = 0.3f * offset;
    gk_vct_set_options(vct, &o);
    gk_budget bud;
    vt_budget(&bud, "vct_res=64,vct_trace_scale=1");
    vt_frame f;
    vt_frame_create(&f, 8, 8, v3(0.5f, 0.5f, 3), c, v3(0, 1, 0), 0.5f);
    vt_gbuffer(&g, &f, &sc);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, v3(2, 2, 2), v3(0, -1, 0), v3(1, 1, 1), 1.0f);
    if (vt_render(vct, &f, &sc, &bud, &L, 1, NULL, NULL) != 0)
        goto out;
    gk_vct_stats st;
    gk_vct_get_stats(vct, &st);
    /* occupied voxels: count channel (channel 0) of the scratch buffer */
    long r3 = (long)st.res * st.res * st.res;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, gk_vct_scratch_buffer(vct));
    const GLuint *cnt = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(r3 * 4), GL_MAP_READ_BIT);
    for (long i = 0; cnt && i < r3; i++)
        r.occupied += cnt[i] != 0;
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);

    gk_err e = {0};
    GLuint p = gk_program_get_compute(g.programs, "vct/test/ray_leak.comp",
                                      "#define ISO_MIPS 1\n#define AXIS_WEIGHT_SQ 0\n#define OPACITY_CORRECTION 0\n", &e);
    if (!p) {
        fprintf(stderr, "# %s\n", e.msg);
        goto out;
    }
    const int rays = 16384;
    GLuint res_buf, zero[2] = {0, 0};
    glGenBuffers(1, &res_buf);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, res_buf);
    glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof zero, zero, GL_DYNAMIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, res_buf);
    glUseProgram(p);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_3D, gk_vct_radiance_texture(vct));
    glUniform1i(glGetUniformLocation(p, "u_vox0"), 0);
    glUniform1i(glGetUniformLocation(p, "u_res"), st.res);
    glUniform1f(glGetUniformLocation(p, "u_res_f"), (float)st.res);
    glUniform1f(glGetUniformLocation(p, "u_step_mul"), 1.0f);
    glUniform1f(glGetUniformLocation(p, "u_ao_lambda"), 0.0f);
    vec3 cu = v3_scale(v3_sub(c, v3(st.grid_origin[0], st.grid_origin[1], st.grid_origin[2])), 1.0f / st.grid_size);
    glUniform3f(glGetUniformLocation(p, "u_center"), cu.x, cu.y, cu.z);
    glUniform3f(glGetUniformLocation(p, "u_normal"), n.x, n.y, n.z);
    glUniform1i(glGetUniformLocation(p, "u_rays"), rays);
    glUniform1f(glGetUniformLocation(p, "u_march"), 12.0f);
    glDispatchCompute((GLuint)(rays / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const GLuint *res = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, GL_MAP_READ_BIT);
    if (res) {
        r.half = (double)res[0] / rays;
        r.full = (double)res[1] / rays;
    }
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    glDeleteBuffers(1, &res_buf);
    glBindTexture(GL_TEXTURE_3D, 0);
out:
    vt_frame_destroy(&f);
    gk_gi_vct.destroy(vct);
    vt_scene_free(&sc);
    return r;
}

static void thin_wall_rays_conservative_beats_thin(void **state)
{
    (void)state;
    const vec3 normals[3] = {v3(1, 1, 0), v3(1, 1, 1), v3(1, 0.4f, 0.2f)};
    double thin_mean[3];
    for (int i = 0; i < 3; i++) {
        /* The thin result depends on where the plane cuts the voxel centres, so it is averaged over
           four sub-voxel grid offsets (o, 0.7o, 0.3o), o = 0, 1/4, 1/2, 3/4. */
        leak_result thin_sum = {0, 0, 0}, cons_sum = {0, 0, 0};
        for (int k = 0; k < 4; k++) {
            leak_result thin = thin_wall(normals[i], false, 0.25f * (float)k);
            leak_result cons = thin_wall(normals[i], true, 0.25f * (float)k);
            assert_true(thin.half >= 0 && cons.half >= 0);
            /* A 26-separating voxelization cannot be crossed by a ray through the real loop: 0 leaked
               rays at every offset for all three normals (as in P.3); any leak is a bug. */
            assert_true(cons.half == 0.0);
            assert_true(cons.occupied >= thin.occupied);
            thin_sum.half += thin.half / 4, thin_sum.full += thin.full / 4, thin_sum.occupied += thin.occupied / 4;
            cons_sum.half += cons.half / 4, cons_sum.full += cons.full / 4, cons_sum.occupied += cons.occupied / 4;
        }
        thin_mean[i] = thin_sum.half;
        printf("# thin wall n=(%.1f,%.1f,%.1f), mean of 4 offsets: thin %ld voxels, rays alpha<0.5 %.2f%% "
               "(<0.05 %.2f%%); conservative %ld voxels, %.2f%% (%.2f%%)\n",
               normals[i].x, normals[i].y, normals[i].z, thin_sum.occupied, 100 * thin_sum.half,
               100 * thin_sum.full, cons_sum.occupied, 100 * cons_sum.half, 100 * cons_sum.full);
    }
    /* Diagonal walls leak through the thin (6-separating) voxelization (P.3: 19% for (1,1,0) and 32%
       for (1,1,1), trilinear, 1-voxel steps). Measured here (mean of 4 offsets): 12.0% and 41.6%
       (0.2% for the nearly axis-aligned (1,0.4,0.2)); the bounds (half of that) require the failure
       to be clearly there, so the test shows that the conservative mode (0%) is what removes it. */
    assert_true(thin_mean[0] > 0.06);
    assert_true(thin_mean[1] > 0.20);
}

/* ---- partition ------------------------------------------------------------------------------ */
/* Box [0,1]^3 open towards +z, a zero-thickness wall at x = 0.5; a narrow spot light lights only
   the floor of the x < 0.5 half. Returns dark-side / lit-side mean indirect luminance over visible
   pixels more than 0.08 from the wall (ground truth 0). */
/* Largest distance (m) between a G-buffer pixel's rasterized position and the one reconstructed
   from its window depth with inv_view_proj, as the method does (vct/sparse.glsl). */
static double recon_err_max;

static double partition_leak(const char *budget, const gk_vct_options *opt, double *lit_mean)
{
    vt_scene sc;
    vt_scene_init(&sc);
    vec3 white = v3(0.75f, 0.75f, 0.75f);
    vt_add_quad(&sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), white);    /* floor, +y */
    vt_add_quad(&sc, v3(0, 1, 0), v3(1, 0, 0), v3(0, 0, 1), white);    /* ceiling, -y */
    vt_add_quad(&sc, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), white);    /* back, +z */
    vt_add_quad(&sc, v3(0, 0, 0), v3(0, 1, 0), v3(0, 0, 1), white);    /* left, +x */
    vt_add_quad(&sc, v3(1, 0, 0), v3(0, 0, 1), v3(0, 1, 0), white);    /* right, -x */
    vt_add_quad(&sc, v3(0.5f, 0, 0), v3(0, 0, 1), v3(0, 1, 0), white); /* partition */
    vt_scene_finish(&sc);
    /* spot at (0.25, 0.95, 0.5) straight down, outer cone 13 deg: floor footprint radius
       0.95 tan 13 = 0.22 < 0.25, so no direct light reaches the dark half or the wall */
    gk_gi_light L = vt_light(&sc, GK_LIGHT_SPOT, v3(0.25f, 0.95f, 0.5f), v3(0, -1, 0), v3(20, 20, 20),
                             13.0f * 3.14159265f / 180.0f);
    void *vct = vt_create(&g);
    if (opt)
        gk_vct_set_options(vct, opt);
    gk_budget bud;
    vt_budget(&bud, budget);
    vt_frame f;
    const int W = 64, H = 64;
    vt_frame_create(&f, W, H, v3(0.5f, 0.5f, 2.2f), v3(0.5f, 0.45f, 0.4f), v3(0, 1, 0), 0.9f);
    vt_gbuffer(&g, &f, &sc);
    float *img = malloc(sizeof(float) * 4 * W * H), *pos = malloc(sizeof(float) * 4 * W * H);
    double ratio = -1;
    if (vt_render(vct, &f, &sc, &bud, &L, 1, img, NULL) == 0) {
        vt_read_positions(&f, pos);
        double sl = 0, sd = 0;
        int nl = 0, nd = 0;
        for (int i = 0; i < W * H; i++) {
            if (pos[i * 4 + 3] == 0)
                continue;
            vec4 ndc = {((float)(i % W) + 0.5f) / W * 2 - 1, ((float)(i / W) + 0.5f) / H * 2 - 1, pos[i * 4 + 3] * 2 - 1, 1};
            vec4 w = m4_vec4(f.inv_view_proj, ndc);
            vec3 d = v3_sub(v3(w.x / w.w, w.y / w.w, w.z / w.w), v3(pos[i * 4], pos[i * 4 + 1], pos[i * 4 + 2]));
            recon_err_max = fmax(recon_err_max, v3_len(d));
            float x = pos[i * 4];
            if (x < 0.42f)
                sl += vt_lum(img + i * 4), nl++;
            else if (x > 0.58f)
                sd += vt_lum(img + i * 4), nd++;
        }
        if (nl > 100 && nd > 100) {
            ratio = (sd / nd) / (sl / nl);
            *lit_mean = sl / nl;
        }
    }
    free(img);
    free(pos);
    vt_frame_destroy(&f);
    gk_gi_vct.destroy(vct);
    vt_scene_free(&sc);
    return ratio;
}

static void partition_leak_is_small(void **state)
{
    (void)state;
    static const char *budgets[] = {
        "vct_res=32,vct_trace_scale=1,vct_mips=aniso", "vct_res=64,vct_trace_scale=1,vct_mips=aniso",
        "vct_res=64,vct_trace_scale=1,vct_mips=iso", "vct_res=64,vct_trace_scale=0.5,vct_mips=aniso",
        "vct_res=64,vct_trace_scale=1,vct_cones=4", "vct_res=64,vct_trace_scale=1,vct_cones=9",
        "vct_res=64,vct_trace_scale=1,vct_mips=aniso,vct_level0=aniso",
        "vct_res=64,vct_trace_scale=1,vct_thick=1.5", "vct_res=64,vct_trace_scale=1,vct_thick=3",
    };
    double r[9], lit;
    for (int i = 0; i < 9; i++) {
        r[i] = partition_leak(budgets[i], NULL, &lit);
        printf("# partition leak %s: dark/lit = %.3f%% (lit-side mean indirect %.4f nits)\n", budgets[i],
               100 * r[i], lit);
        assert_true(r[i] >= 0);
        assert_true(lit > 0);
    }
    /* The thesis's cone sampling (no footprint clamp, wide cones not clipped at the border) */
    gk_vct_options thesis;
    gk_vct_default_options(&thesis);
    thesis.footprint_clamp = 0, thesis.clip_cones = false, thesis.directional_injection = false;
    double t[3];
    static const char *res_budgets[3] = {"vct_res=32,vct_trace_scale=1", "vct_res=64,vct_trace_scale=1",
                                         "vct_res=128,vct_trace_scale=1"};
    for (int i = 0; i < 3; i++) {
        t[i] = partition_leak(res_budgets[i], &thesis, &lit);
        printf("# partition leak %s, thesis cone sampling: dark/lit = %.3f%%\n", res_budgets[i], 100 * t[i]);
        assert_true(t[i] >= 0);
    }
    /* Measured (llvmpipe, this scene), default: 32^3 2.8%, 64^3 4.1%, 64^3 iso 19.5%, 64^3 at trace
       scale 0.5 4.0%, 4 cones 7.5%, 9 cones 2.8% (directional level-1 views, the default since
       issue 11; with isotropic ones 3.9%, 4.6%, 19.5%, 4.3%, 6.1%, 3.5%); thesis cone sampling 6.0% / 2.9% / 1.3% at
       32^3 / 64^3 / 128^3; vct_level0=aniso 4.2% at 64^3 (the partition is unlit, its light comes
       from the coarse levels, which an anisotropic level 0 leaves as they were), and for the same
       reason vct_thick=1.5 / 3 4.3% / 4.2% (its solid voxels are left out of the coarse levels,
       mip_aniso.comp: they change level 0 only, where this partition is one opaque voxel). P.4 measured 0.3-0.6% in a box whose lit side is lit all over; here only
       a small spot of floor is lit, 2 voxels (64^3) from the wall, so the lit side's indirect light
       (the denominator) is weaker. The footprint clamp trades here: its narrow near-field samples
       cross the one-voxel wall at level 0, where trilinear samples with 1-voxel steps see it only
       partly opaque (the thin-wall test above), so the default leaks more than the thesis's cones
       at 64^3 and does not fall with resolution, while it removes self-illumination (test_vct.c)
       and halves the Cornell box's error (tests/e2e/gi_bounce.sh).
       Bounds: ~1.5x the measurements; isotropic mips must leak clearly more than anisotropic
       ones (the red-green wall problem, Fig. 11b); with the thesis's sampling a finer grid leaks
       less (P.4). */
    assert_true(r[0] < 0.06);
    assert_true(r[1] < 0.07);
    assert_true(r[2] > 3 * r[1]);
    assert_true(r[3] < 0.07);
    assert_true(r[6] < 0.07);
    assert_true(r[7] < 0.07 && r[8] < 0.07);
    assert_true(r[4] < 0.09 && r[5] < 0.055);
    assert_true(t[0] < 0.09 && t[1] < 0.045 && t[2] < 0.02);
    assert_true(t[2] < t[1] && t[1] < t[0]);
    /* The method reads the renderer's layout (positions reconstructed from depth): the
       reconstruction must not change the result, so it must land on the rasterized positions to a
       small fraction of a voxel (1/64 m at 64^3) in every frame above. */
    printf("# position reconstructed from depth: max error %.2e m\n", recon_err_max);
    assert_true(recon_err_max < 0.1 / 64);
}

/* ---- vct_thick: solid voxels behind surfaces -------------------------------------------------- */
/* A lit floor (+y) and a single-sided wall on it facing -x at x = 0.5, a point light on the wall's
   back side (no shadow map: every fragment's voxel is lit), voxelized without and with vct_thick at
   32^3. The marks must (1) leave every voxel that holds fragments as it was, its scratch channels
   and its injected radiance bit for bit (a mark is not a fragment: the lit floor behind the wall
   keeps its radiance), (2) turn voxels that were empty into opaque black ones, (3) only behind a
   surface: behind the wall (x > 0.5), under the floor (y < 0) or above the bounds marker (y > 1,
   facing down), within the thickness plus the
   voxel a fragment's point lies in. */
static void thick_marks_solid_voxels_behind_without_diluting(void **state)
{
    (void)state;
    vt_scene sc;
    vt_scene_init(&sc);
    const float rho = 0.7f;
    vt_add_quad(&sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), v3(rho, rho, rho));        /* floor, +y */
    vt_add_quad(&sc, v3(0.5f, 0, 0), v3(0, 0, 1), v3(0, 0.6f, 0), v3(0.5f, 0.5f, 0.5f)); /* wall, -x */
    vt_add_quad(&sc, v3(0, 1, 0), v3(0.01f, 0, 0), v3(0, 0, 0.01f), v3(0, 0, 0));       /* bounds marker */
    vt_scene_finish(&sc);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, v3(0.8f, 0.7f, 0.5f), v3(0, -1, 0), v3(3, 3, 3), 1);
    vt_frame f;
    vt_frame_create(&f, 16, 16, v3(0.5f, 1.5f, 0.51f), v3(0.5f, 0, 0.5f), v3(0, 0, -1), 0.5f);
    vt_gbuffer(&g, &f, &sc);
    static const char *budgets[3] = {"vct_res=32,vct_thick=0", "vct_res=32,vct_thick=1.5", "vct_res=32,vct_thick=3"};
    static const float thick[3] = {0, 1.5f, 3};
    unsigned *scratch[3];
    float *rad[3];
    gk_vct_stats st;
    for (int k = 0; k < 3; k++) {
        gk_budget b;
        vt_budget(&b, budgets[k]);
        void *vct = vt_create(&g);
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        gk_vct_get_stats(vct, &st);
        long n;
        scratch[k] = vt_read_scratch(vct, &n);
        rad[k] = vt_read_radiance(vct, st.res);
        assert_non_null(scratch[k]);
        assert_non_null(rad[k]);
        gk_gi_vct.destroy(vct);
    }
    const int res = st.res;
    const long N = (long)res * res * res;
    const unsigned solid_bit = 0x80000000u; /* SOLID_BIT, vct/common.glsl */
    const int channels = gk_vct_channels(false);
    for (int k = 1; k < 3; k++) {
        long with_fragments = 0, solid = 0, misplaced = 0, changed = 0;
        for (long i = 0; i < N; i++) {
            unsigned c0 = scratch[0][i], ck = scratch[k][i];
            assert_true((c0 & solid_bit) == 0); /* no marks without vct_thick */
            if (c0 != 0) {
                with_fragments++;
                /* (1) the fragments' sums and count, and the radiance, as without marks */
                bool same = (ck & ~solid_bit) == c0 && memcmp(rad[0] + i * 4, rad[k] + i * 4, 4 * sizeof(float)) == 0;
                for (int ch = 1; ch < channels; ch++)
                    same = same && scratch[0][ch * N + i] == scratch[k][ch * N + i];
                changed += !same;
                continue;
            }
            if (ck == 0) {
                assert_true(rad[k][i * 4 + 3] == 0.0f);
                continue;
            }
            /* (2) a mark alone: opaque, black */
            assert_int_equal(ck, solid_bit);
            assert_true(rad[k][i * 4 + 0] == 0.0f && rad[k][i * 4 + 1] == 0.0f && rad[k][i * 4 + 2] == 0.0f);
            assert_true(rad[k][i * 4 + 3] == 1.0f);
            solid++;
            /* (3) behind the wall or under the floor, within thickness + 1 voxel */
            int x = (int)(i % res), y = (int)(i / res % res);
            float cx = st.grid_origin[0] + (x + 0.5f) * st.voxel_size, cy = st.grid_origin[1] + (y + 0.5f) * st.voxel_size;
            float reach = (thick[k] + 1.0f) * st.voxel_size;
            bool behind_wall = cx > 0.5f && cx < 0.5f + reach && cy > -reach && cy < 0.6f + reach;
            bool under_floor = cy < 0.0f && cy > -reach;
            bool above_marker = cy > 1.0f && cy < 1.0f + reach; /* the marker faces -y */
            misplaced += !(behind_wall || under_floor || above_marker);
        }
        printf("# vct_thick=%.1f at %d^3: %ld voxels with fragments, %ld changed; %ld solid voxels, %ld not behind "
               "a surface\n", thick[k], res, with_fragments, changed, solid, misplaced);
        assert_true(with_fragments > 100);
        assert_int_equal(changed, 0);
        assert_int_equal(misplaced, 0);
        /* the floor (1 m x 1 m) alone has some 28^2 voxels' columns under it (voxel ~3.6 cm): at
           least one solid layer under each */
        assert_true(solid > 28 * 28);
    }
    /* thicker marks more */
    long solid_count[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++)
        for (long i = 0; i < N; i++)
            solid_count[k] += scratch[k][i] == solid_bit;
    assert_true(solid_count[2] > solid_count[1]);
    for (int k = 0; k < 3; k++) {
        free(scratch[k]);
        free(rad[k]);
    }
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

/* ---- vct_axis_clamp: the distances to the first occupied voxel along each axis ------------------ */
/* One frame of a test scene at BUDGET: the method (the caller destroys it), its stats, and the voxel
   scratch buffer read back (the caller frees it). */
static unsigned *render_and_read_scratch(void **vct_out, gk_vct_stats *st, vt_frame *f, const vt_scene *sc,
                                         const char *budget, const gk_gi_light *L)
{
    gk_budget b;
    vt_budget(&b, budget);
    void *vct = vt_create(&g);
    assert_int_equal(vt_render(vct, f, sc, &b, L, 1, NULL, NULL), 0);
    gk_vct_get_stats(vct, st);
    long n;
    unsigned *scratch = vt_read_scratch(vct, &n);
    assert_non_null(scratch);
    *vct_out = vct;
    return scratch;
}

/* The scene of the test above with vct_thick=1.5 (fragments and solid marks: both count as occupied)
   and vct_axis_clamp=first / second at 32^3: axis_dist.comp's words must equal the distances to the
   first / second occupied voxel (the voxel itself counted) found on the CPU from the scratch buffer's
   count channel, for every voxel and all six directions (0xFFFF where the row holds fewer that way).
   The march then reads them (cone_lib.glsl). */
static void axis_clamp_distances(int nth)
{
    vt_scene sc;
    vt_scene_init(&sc);
    vt_add_quad(&sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), v3(0.7f, 0.7f, 0.7f));
    vt_add_quad(&sc, v3(0.5f, 0, 0), v3(0, 0, 1), v3(0, 0.6f, 0), v3(0.5f, 0.5f, 0.5f));
    vt_scene_finish(&sc);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, v3(0.8f, 0.7f, 0.5f), v3(0, -1, 0), v3(3, 3, 3), 1);
    vt_frame f;
    vt_frame_create(&f, 16, 16, v3(0.5f, 1.5f, 0.51f), v3(0.5f, 0, 0.5f), v3(0, 0, -1), 0.5f);
    vt_gbuffer(&g, &f, &sc);
    gk_vct_stats st;
    void *vct;
    unsigned *scratch = render_and_read_scratch(&vct, &st, &f, &sc, nth == 1 ? "vct_res=32,vct_thick=1.5,vct_axis_clamp=first" : "vct_res=32,vct_thick=1.5,vct_axis_clamp=second", &L);
    const int res = st.res;
    const long N = (long)res * res * res;
    unsigned axis_buf = gk_vct_axis_buffer(vct);
    assert_true(axis_buf != 0);
    unsigned *dist = malloc((size_t)(3 * N) * sizeof *dist);
    assert_non_null(dist);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, axis_buf);
    /* the memory the method reports: the formula's, plus three words per voxel, as allocated */
    GLint64 size = 0;
    glGetBufferParameteri64v(GL_SHADER_STORAGE_BUFFER, GL_BUFFER_SIZE, &size);
    assert_int_equal(size, gk_vct_axis_clamp_memory(res));
    assert_int_equal(size, 3 * 4 * N);
    assert_int_equal(gk_gi_vct.memory_bytes(vct),
                     gk_vct_memory_formula(res, st.aniso, st.aniso_level0, gk_vct_channels(false), st.trace_w, st.trace_h, 4) +
                         gk_vct_axis_clamp_memory(res));
    const void *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(3 * N * 4), GL_MAP_READ_BIT);
    assert_non_null(p);
    memcpy(dist, p, (size_t)(3 * N * 4));
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    long wrong = 0, occupied = 0, finite = 0;
    for (long i = 0; i < N; i++) {
        int c[3] = {(int)(i % res), (int)(i / res % res), (int)(i / res / res)};
        occupied += scratch[i] != 0;
        for (int a = 0; a < 3; a++) {
            unsigned want[2] = {0xFFFFu, 0xFFFFu};   /* along -a, +a */
            for (int s = 0; s < 2; s++)
                for (int d = 0, seen = 0; d < res; d++) {
                    int q[3] = {c[0], c[1], c[2]};
                    q[a] += s ? d : -d;
                    if (q[a] < 0 || q[a] >= res)
                        break;
                    if (scratch[((long)q[2] * res + q[1]) * res + q[0]] != 0 && ++seen == nth) {
                        want[s] = (unsigned)d;
                        break;
                    }
                }
            finite += want[0] != 0xFFFFu;
            wrong += dist[a * N + i] != (want[0] | want[1] << 16);
        }
    }
    printf("# vct_axis_clamp=%s at %d^3: %ld occupied voxels, %ld of %ld distances along -x, -y, -z finite, %ld "
           "wrong\n", nth == 1 ? "first" : "second", res, occupied, finite, 3 * N, wrong);
    assert_true(occupied > 28 * 28);
    /* the floor's voxels and the solid ones under it lie in the -y rows of most voxels above it */
    assert_true(finite > N / 4);
    assert_int_equal(wrong, 0);
    free(dist);
    free(scratch);
    gk_gi_vct.destroy(vct);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

static void axis_clamp_distances_match_the_voxels(void **state)
{
    (void)state;
    axis_clamp_distances(1);
    axis_clamp_distances(2);
}

/* ---- vct_axis_clamp=thin: the thin-wall flags ------------------------------------------------ */
/* A floor (+y), a thin wall (two quads 6 mm apart, facing -x and +x, at x = 0.5: both faces in one
   voxel or two adjacent ones at 32^3, voxel ~3.6 cm) and a single-sided wall (facing -x, x = 0.8),
   vct_axis_clamp=thin at 32^3. The flag volume must hold (1) face bits exactly in the voxels that
   hold fragments (the scratch buffer's count, the solid mark aside), (2) THIN_BIT exactly where the
   rule says, recomputed here from the face bits read back (a fragment facing +a with one facing -a in
   its voxel or the next two behind it along -a, and the other way round), (3) on the thin wall: every
   voxel column of its face flagged, none farther than 1.5 voxels from x = 0.5, so neither the
   single-sided wall nor the floor away from the thin wall; (4) THIN_MARK (where the clamp stops too,
   VCT_THIN_DEPTH = 16 voxels behind a flagged voxel's fragments) only on voxels with a flagged voxel
   within 16 along an axis, and no solid mark in the scratch buffer (thin's marks are not opaque);
   and the memory the method reports includes the volume. */
static void thin_flags_mark_thin_walls_only(void **state)
{
    (void)state;
    vt_scene sc;
    vt_scene_init(&sc);
    vt_add_quad(&sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), v3(0.7f, 0.7f, 0.7f));          /* floor, +y */
    vt_add_quad(&sc, v3(0.497f, 0, 0), v3(0, 0, 1), v3(0, 0.6f, 0), v3(0.5f, 0.5f, 0.5f)); /* -x face */
    vt_add_quad(&sc, v3(0.503f, 0, 0), v3(0, 0.6f, 0), v3(0, 0, 1), v3(0.5f, 0.5f, 0.5f)); /* +x face */
    vt_add_quad(&sc, v3(0.8f, 0, 0), v3(0, 0, 1), v3(0, 0.6f, 0), v3(0.5f, 0.5f, 0.5f));   /* single, -x */
    vt_scene_finish(&sc);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, v3(0.3f, 0.7f, 0.5f), v3(0, -1, 0), v3(3, 3, 3), 1);
    vt_frame f;
    vt_frame_create(&f, 16, 16, v3(0.5f, 1.5f, 0.51f), v3(0.5f, 0, 0.5f), v3(0, 0, -1), 0.5f);
    vt_gbuffer(&g, &f, &sc);
    gk_vct_stats st;
    void *vct;
    unsigned *scratch = render_and_read_scratch(&vct, &st, &f, &sc, "vct_res=32,vct_axis_clamp=thin", &L);
    const int res = st.res;
    const long N = (long)res * res * res;
    unsigned buf = gk_vct_thin_buffer(vct);
    assert_true(buf != 0);
    unsigned *fl = malloc((size_t)N * sizeof *fl);
    assert_non_null(fl);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
    GLint64 size = 0;
    glGetBufferParameteri64v(GL_SHADER_STORAGE_BUFFER, GL_BUFFER_SIZE, &size);
    assert_int_equal(size, gk_vct_thin_flag_memory(res));
    assert_int_equal(size, 4 * N);
    assert_int_equal(gk_gi_vct.memory_bytes(vct),
                     gk_vct_memory_formula(res, st.aniso, st.aniso_level0, gk_vct_channels(false), st.trace_w, st.trace_h, 8) +
                         gk_vct_axis_clamp_memory(res) + gk_vct_thin_flag_memory(res));
    const void *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(N * 4), GL_MAP_READ_BIT);
    assert_non_null(p);
    memcpy(fl, p, (size_t)(N * 4));
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    const unsigned solid_bit = 0x80000000u, thin_bit = 0x100u, thin_mark = 0x200u, face_mask = 0x3Fu; /* vct/common.glsl */
    const int depth = 16;   /* VCT_THIN_DEPTH */
    long faces_wrong = 0, thin_wrong = 0, thin = 0, thin_far = 0, marks = 0, marks_misplaced = 0;
    bool column[64][64] = {{false}};   /* (y, z) columns of the thin wall with a flagged voxel */
    float wall_x = (0.5f - st.grid_origin[0]) / st.voxel_size;   /* in voxels */
    for (long i = 0; i < N; i++) {
        int c[3] = {(int)(i % res), (int)(i / res % res), (int)(i / res / res)};
        unsigned f0 = fl[i] & face_mask;
        faces_wrong += (f0 != 0) != ((scratch[i] & ~solid_bit) != 0);
        bool want = false;
        for (int a = 0; a < 3; a++)
            for (int d = 0; d <= 2; d++)
                for (int s = 0; s < 2; s++) {   /* s = 1: facing +a, the other face along -a */
                    if (!(f0 & (1u << (2 * a + s))))
                        continue;
                    int q[3] = {c[0], c[1], c[2]};
                    q[a] += s ? -d : d;
                    if (q[a] < 0 || q[a] >= res)
                        continue;
                    unsigned fq = fl[((long)q[2] * res + q[1]) * res + q[0]];
                    want = want || (fq & (1u << (2 * a + (1 - s))));
                }
        bool got = (fl[i] & thin_bit) != 0;
        thin_wrong += want != got;
        if (got) {
            thin++;
            thin_far += fabsf(c[0] + 0.5f - wall_x) > 1.5f;
            if (c[1] < 64 && c[2] < 64)
                column[c[1]][c[2]] = true;
        }
        assert_true((scratch[i] & solid_bit) == 0);
        if (fl[i] & thin_mark) {   /* behind a flagged voxel's fragment: one within `depth` along an axis */
            marks++;
            bool near = false;
            for (int a = 0; a < 3 && !near; a++)
                for (int d = -depth - 1; d <= depth + 1 && !near; d++) {
                    int q[3] = {c[0], c[1], c[2]};
                    q[a] += d;
                    near = q[a] >= 0 && q[a] < res && (fl[((long)q[2] * res + q[1]) * res + q[0]] & thin_bit);
                }
            marks_misplaced += !near;
        }
    }
    /* the wall's face, 0.6 m x 1 m, in voxel columns (y, z) its voxels span */
    int y1 = (int)floorf((0.6f - st.grid_origin[1]) / st.voxel_size), z0 = (int)ceilf((0.0f - st.grid_origin[2]) / st.voxel_size),
        z1 = (int)floorf((1.0f - st.grid_origin[2]) / st.voxel_size), y0 = (int)ceilf((0.0f - st.grid_origin[1]) / st.voxel_size);
    long columns = 0, covered = 0;
    for (int y = y0; y < y1 && y < 64; y++)
        for (int z = z0; z < z1 && z < 64; z++)
            columns++, covered += column[y][z];
    printf("# vct_axis_clamp=thin at %d^3: %ld thin voxels (%ld farther than 1.5 voxels from the thin wall), %ld of %ld "
           "columns of the wall covered; %ld wrong face words, %ld wrong flags; %ld marks (%ld misplaced)\n",
           res, thin, thin_far, covered, columns, faces_wrong, thin_wrong, marks, marks_misplaced);
    assert_int_equal(faces_wrong, 0);
    assert_int_equal(thin_wrong, 0);
    assert_true(columns > 200);
    assert_int_equal(covered, columns);
    assert_int_equal(thin_far, 0);
    assert_true(marks > 0);
    assert_int_equal(marks_misplaced, 0);
    free(fl);
    free(scratch);
    gk_gi_vct.destroy(vct);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(thin_wall_rays_conservative_beats_thin),
        cmocka_unit_test(partition_leak_is_small),
        cmocka_unit_test(thick_marks_solid_voxels_behind_without_diluting),
        cmocka_unit_test(axis_clamp_distances_match_the_voxels),
        cmocka_unit_test(thin_flags_mark_thin_walls_only),
    };
    return cmocka_run_group_tests_name("vct_leak", tests, group_setup, group_teardown);
}
