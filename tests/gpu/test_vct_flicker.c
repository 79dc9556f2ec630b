/* vct temporal stability (summary A.6.1 #5) on llvmpipe: the grid-offset sweep (the scene shifted
 * against the grid by sub-voxel offsets, P.5) and a moving object (0.1 voxel per frame), with the
 * dirty-region re-voxelization checked against a full one. */
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

#define W 64
#define H 64

/* Bounds from the measurements on llvmpipe (printed by the tests), ~1.5x headroom:
   offset sweep 32^3: median 8.7%, p95 48.9%; 64^3: median 4.2%, p95 27.7%; 64^3 at trace scale
   0.5: median 3.1%, p95 10.6% (P.5 had median 4.4-5.7%, p95 21-36% in its Cornell box);
   moving block at 0.1 voxel/frame: worst frame 0.040% on static receivers (0.027% with the
   thesis's cone sampling and renormalised voxel normals). */
#define FLICKER_MED32 0.13
#define FLICKER_P95_32 0.66
#define FLICKER_MED64 0.06
#define FLICKER_P95_64 0.40
#define MOVE_WORST 0.0006
/* The default, vct_axis_clamp=thin: the block's bottom face lies on the floor, back to back with it,
   so the voxels they share are a thin wall's to the flag pass (vct/thin_flag.comp), and the clamp's
   limits (up to 16 voxels behind them) move with the block: worst frame 0.099% (measured; bound
   1.5x). */
#define MOVE_WORST_THIN 0.0015

/* Cornell-like box open towards +z: white floor, ceiling and back, red left, green right wall, a
   white block; point light under the ceiling. Returns the block's node. */
static int build_box(vt_scene *sc, bool block_animated)
{
    vt_scene_init(sc);
    vec3 white = v3(0.75f, 0.75f, 0.75f);
    vt_add_quad(sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), white);
    vt_add_quad(sc, v3(0, 1, 0), v3(1, 0, 0), v3(0, 0, 1), white);
    vt_add_quad(sc, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), white);
    vt_add_quad(sc, v3(0, 0, 0), v3(0, 1, 0), v3(0, 0, 1), v3(0.63f, 0.06f, 0.05f));
    vt_add_quad(sc, v3(1, 0, 0), v3(0, 0, 1), v3(0, 1, 0), v3(0.14f, 0.45f, 0.09f));
    int block = vt_add_box(sc, v3(0.5f, 0, 0.3f), v3(0.25f, 0.35f, 0.25f), white, block_animated);
    vt_scene_finish(sc);
    return block;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static void offset_sweep(const char *budget, double *median, double *p95, double *frac10, double *mean_out)
{
    vt_scene sc;
    build_box(&sc, false);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, v3(0.5f, 0.9f, 0.5f), v3(0, -1, 0), v3(2, 2, 2), 1);
    vt_frame f;
    vt_frame_create(&f, W, H, v3(0.5f, 0.5f, 2.0f), v3(0.5f, 0.5f, 0.4f), v3(0, 1, 0), 0.8f);
    vt_gbuffer(&g, &f, &sc);
    gk_budget b;
    vt_budget(&b, budget);
    float *img[4], *lo = calloc(W * H, sizeof(float)), *hi = calloc(W * H, sizeof(float));
    double *sum = calloc(W * H, sizeof(double));
    for (int k = 0; k < 4; k++) {
        img[k] = malloc(sizeof(float) * 4 * W * H);
        void *vct = vt_create(&g);
        gk_vct_options o;
        gk_vct_default_options(&o);
        float off = 0.25f * (float)k;
        o.grid_offset[0] = off, o.grid_offset[1] = 0.7f * off, o.grid_offset[2] = 0.3f * off;
        gk_vct_set_options(vct, &o);
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, img[k], NULL), 0);
        gk_gi_vct.destroy(vct);
    }
    double gsum = 0;
    int n = 0;
    for (int i = 0; i < W * H; i++) {
        lo[i] = 1e30f, hi[i] = 0;
        for (int k = 0; k < 4; k++) {
            float l = vt_lum(img[k] + i * 4);
            lo[i] = fminf(lo[i], l), hi[i] = fmaxf(hi[i], l);
            sum[i] += l / 4;
        }
        gsum += sum[i];
    }
    gsum /= W * H;
    float *rel = malloc(sizeof(float) * W * H);
    double acc = 0;
    int over10 = 0;
    for (int i = 0; i < W * H; i++) {
        if (sum[i] <= 0.05 * gsum)   /* background and near-black pixels: relative range undefined */
            continue;
        rel[n] = (float)((hi[i] - lo[i]) / sum[i]);
        acc += rel[n];
        over10 += rel[n] > 0.1f;
        n++;
    }
    qsort(rel, (size_t)n, sizeof(float), cmp_float);
    *median = rel[n / 2];
    *p95 = rel[(n * 95) / 100];
    *frac10 = (double)over10 / n;
    *mean_out = acc / n;
    for (int k = 0; k < 4; k++)
        free(img[k]);
    free(lo), free(hi), free(sum), free(rel);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

static void grid_offset_flicker_is_bounded(void **state)
{
    (void)state;
    static const char *budgets[] = {"vct_res=32,vct_trace_scale=1", "vct_res=64,vct_trace_scale=1",
                                    "vct_res=64,vct_trace_scale=0.5"};
    double med[3], p95[3], f10[3], mean[3];
    for (int i = 0; i < 3; i++) {
        offset_sweep(budgets[i], &med[i], &p95[i], &f10[i], &mean[i]);
        printf("# grid-offset sweep %s: relative range mean %.1f%%, median %.1f%%, p95 %.1f%%, "
               "pixels > 10%%: %.1f%%\n", budgets[i], 100 * mean[i], 100 * med[i], 100 * p95[i], 100 * f10[i]);
    }
    /* see the bounds' definitions at the top of the file */
    assert_true(med[0] < FLICKER_MED32 && p95[0] < FLICKER_P95_32);
    assert_true(med[1] < FLICKER_MED64 && p95[1] < FLICKER_P95_64);
    assert_true(med[2] < FLICKER_MED64 * 1.2 && p95[2] < FLICKER_P95_64 * 1.2);
    assert_true(med[0] > 0.0);   /* the sweep does move the grid */
}

/* ---- moving object ---------------------------------------------------------------------------- */
static void set_translation(gk_node *n, float x)
{
    n->world = m4_identity();
    n->world.m[12] = x;
}

static void moving_object_flicker(const char *budget, double bound)
{
    vt_scene sc;
    int block = build_box(&sc, true);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, v3(0.5f, 0.9f, 0.5f), v3(0, -1, 0), v3(2, 2, 2), 1);
    vt_frame f;
    vt_frame_create(&f, W, H, v3(0.5f, 0.5f, 2.0f), v3(0.5f, 0.5f, 0.4f), v3(0, 1, 0), 0.8f);
    gk_budget b;
    vt_budget(&b, budget);
    void *vct = vt_create(&g);
    float *prev = malloc(sizeof(float) * 4 * W * H), *cur = malloc(sizeof(float) * 4 * W * H);
    float *ppos = malloc(sizeof(float) * 4 * W * H), *cpos = malloc(sizeof(float) * 4 * W * H);
    gk_vct_stats st0 = {0}, st = {0};
    double worst = 0, total = 0;
    const int frames = 8;
    float x = 0;
    for (int fr = 0; fr <= frames; fr++) {
        if (fr > 0) {
            x += 0.1f * st0.voxel_size;   /* 0.1 voxel per frame */
            set_translation(&sc.nodes[block], x);
        }
        vt_gbuffer(&g, &f, &sc);
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, cur, NULL), 0);
        vt_read_positions(&f, cpos);
        gk_vct_get_stats(vct, &st);
        if (fr == 0) {
            st0 = st;
        } else {
            /* the block moved: re-voxelized in its dirty region only */
            assert_int_equal(st.voxelize_runs, st0.voxelize_runs + fr);
            assert_true(st.last_voxelized_region < (long)st.res * st.res * st.res / 4);
            /* static receivers: pixels whose G-buffer position did not change */
            double d = 0, m = 0;
            for (int i = 0; i < W * H; i++) {
                if (cpos[i * 4 + 3] == 0 || memcmp(cpos + i * 4, ppos + i * 4, 4 * sizeof(float)) != 0)
                    continue;
                d += fabs(vt_lum(cur + i * 4) - vt_lum(prev + i * 4));
                m += vt_lum(cur + i * 4);
            }
            double rel = m > 0 ? d / m : 1;
            total += rel / frames;
            worst = fmax(worst, rel);
        }
        float *t = prev; prev = cur; cur = t;
        t = ppos; ppos = cpos; cpos = t;
    }
    printf("# moving block, 0.1 voxel/frame, %s: mean |frame difference| / mean on static receivers: "
           "average %.3f%%, worst %.3f%%; dirty region %ld of %d voxels\n",
           budget, 100 * total, 100 * worst, st.last_voxelized_region, st.res * st.res * st.res);
    /* see MOVE_WORST */
    assert_true(worst < bound);
    assert_true(total > 0.0);   /* the moving block does change the indirect light */

    /* The dirty-region update leaves exactly the voxels a full voxelization of the final state makes
       (fixed-point sums are order-independent): bit-identical scratch. */
    long n1, n2;
    unsigned *inc = vt_read_scratch(vct, &n1);
    void *fresh = vt_create(&g);
    assert_int_equal(vt_render(fresh, &f, &sc, &b, &L, 1, NULL, NULL), 0);
    unsigned *full = vt_read_scratch(fresh, &n2);
    assert_int_equal(n1, n2);
    assert_memory_equal(inc, full, (size_t)n1 * 4);
    free(inc), free(full);
    /* vct_axis_clamp=thin's flags too (made anew over the whole grid after each update) */
    unsigned tb[2] = {gk_vct_thin_buffer(vct), gk_vct_thin_buffer(fresh)};
    assert_true((tb[0] != 0) == (tb[1] != 0));
    if (tb[0]) {
        long nv = (long)st.res * st.res * st.res;
        unsigned *fl[2];
        for (int k = 0; k < 2; k++) {
            fl[k] = malloc((size_t)nv * 4);
            assert_non_null(fl[k]);
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, tb[k]);
            const void *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(nv * 4), GL_MAP_READ_BIT);
            assert_non_null(p);
            memcpy(fl[k], p, (size_t)nv * 4);
            glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
        }
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        long flagged = 0;
        for (long i = 0; i < nv; i++)
            flagged += (fl[1][i] & 0x100u) != 0;   /* THIN_BIT: the block's bottom on the floor */
        printf("# %s: %ld thin voxels after the moves, flag volume as a full voxelization's\n", budget, flagged);
        assert_true(flagged > 0);
        assert_memory_equal(fl[0], fl[1], (size_t)nv * 4);
        free(fl[0]), free(fl[1]);
    }
    gk_gi_vct.destroy(fresh);
    gk_gi_vct.destroy(vct);
    free(prev), free(cur), free(ppos), free(cpos);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

static void moving_object_flicker_and_dirty_update(void **state)
{
    (void)state;
    moving_object_flicker("vct_res=32,vct_trace_scale=1,vct_axis_clamp=off", MOVE_WORST);
    moving_object_flicker("vct_res=32,vct_trace_scale=1", MOVE_WORST_THIN);
}

/* vct_thick's solid marks in the dirty-region update: the region grows by the marks' reach (vct.c), so
   after a single-sided panel moved, the scratch is bit for bit what a full voxelization of the final
   state makes, marks included (without the growth, marks up to 3 voxels behind the panel's old
   place stayed; a closed block's marks stay inside it, within its region). */
static void dirty_update_moves_the_solid_marks(void **state)
{
    (void)state;
    vt_scene sc;
    vt_scene_init(&sc);
    vec3 white = v3(0.75f, 0.75f, 0.75f);
    vt_add_quad(&sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), white); /* floor */
    vt_add_quad(&sc, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), white); /* back */
    const float panel[1][9] = {{0.4f, 0.1f, 0.2f, 0, 0, 0.5f, 0, 0.5f, 0}}; /* facing -x, marks towards +x */
    int block = vt_add_quads(&sc, 1, panel, white, v3(0, 0, 0), true);
    vt_scene_finish(&sc);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, v3(0.5f, 0.9f, 0.5f), v3(0, -1, 0), v3(2, 2, 2), 1);
    vt_frame f;
    vt_frame_create(&f, W, H, v3(0.5f, 0.5f, 2.0f), v3(0.5f, 0.5f, 0.4f), v3(0, 1, 0), 0.8f);
    gk_budget b;
    vt_budget(&b, "vct_res=32,vct_trace_scale=1,vct_thick=3");
    void *vct = vt_create(&g);
    gk_vct_stats st = {0};
    for (int fr = 0; fr <= 4; fr++) {
        if (fr > 0)
            set_translation(&sc.nodes[block], 0.7f * (float)fr * st.voxel_size); /* 0.7 voxel per frame */
        vt_gbuffer(&g, &f, &sc);
        assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
        if (fr == 0)
            gk_vct_get_stats(vct, &st);
    }
    gk_vct_get_stats(vct, &st);
    assert_true(st.last_voxelized_region < (long)st.res * st.res * st.res / 2); /* still a region */
    long n1, n2, solid = 0;
    unsigned *inc = vt_read_scratch(vct, &n1);
    void *fresh = vt_create(&g);
    assert_int_equal(vt_render(fresh, &f, &sc, &b, &L, 1, NULL, NULL), 0);
    unsigned *full = vt_read_scratch(fresh, &n2);
    assert_int_equal(n1, n2);
    for (long i = 0; i < (long)st.res * st.res * st.res; i++)
        solid += (full[i] & 0x80000000u) != 0; /* SOLID_BIT, vct/common.glsl */
    printf("# vct_thick=3, panel moved 4 x 0.7 voxel at 32^3: %ld solid voxels, dirty region %ld voxels\n", solid,
           st.last_voxelized_region);
    assert_true(solid > 0);
    assert_memory_equal(inc, full, (size_t)n1 * 4);
    free(inc), free(full);
    gk_gi_vct.destroy(fresh);
    gk_gi_vct.destroy(vct);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(grid_offset_flicker_is_bounded),
        cmocka_unit_test(moving_object_flicker_and_dirty_update),
        cmocka_unit_test(dirty_update_moves_the_solid_marks),
    };
    return cmocka_run_group_tests_name("vct_flicker", tests, group_setup, group_teardown);
}
