/* The VAL maps' work model (app/gi/vpl/vpl_work.c, #21) against a CPU replay of their
 * rasterization: on the harness's Cornell corner (tests/gpu/test_vpl_harness.h) one counting
 * frame draws every proxy triangle into each VAL's paraboloid map; here each triangle is projected
 * as vpl/val_depth.vert does (in float) and the pixel centres inside it are counted (edge functions
 * in double), map by map. The shader counted every fragment it shaded, so the two counts differ
 * only where a pixel centre lies within the GPU's sub-pixel snapping of an edge. The basis pass
 * adds res² fragments per map. Without count_work nothing is counted. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "gi/vpl/vpl_internal.h"
#include "test_vpl_harness.h"
#include "test_pass_work.h"

/* Measured on llvmpipe (8 sub-pixel bits): counted - replayed = -2 of 41617 (4 maps of 64²) and -8
   of 376895 (8 maps of 128²), -0.0048% and -0.0021%: the pixel centres within snapping distance
   of an edge. The bound is 4x the larger; a model off by a map or a triangle set is off by 10%+. */
#define TOLERANCE 2e-4

VPL_H_BOX_GROUP


/* vpl/val_depth.vert's window position of world point w in a res² map of the frame (c, t, b, n) */
static void project(const float c[3], const gk_val *v, vec3 w, int res, double out[2])
{
    float d[3] = {w.x - c[0], w.y - c[1], w.z - c[2]};
    float r = fmaxf(sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), 1e-6f);
    float lx = (d[0] * v->t.x + d[1] * v->t.y + d[2] * v->t.z) / r;
    float ly = (d[0] * v->b.x + d[1] * v->b.y + d[2] * v->b.z) / r;
    float lz = (d[0] * v->normal.x + d[1] * v->normal.y + d[2] * v->normal.z) / r;
    float q = fmaxf(1.0f + lz, 1e-3f);
    out[0] = ((double)(lx / q) + 1.0) * 0.5 * res;
    out[1] = ((double)(ly / q) + 1.0) * 0.5 * res;
}

static double edge(const double a[2], const double b[2], double x, double y)
{
    return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
}

/* pixel centres of the res² map inside triangle p (either winding: culling is off) */
static long covered(const double p[3][2], int res)
{
    double area = edge(p[0], p[1], p[2][0], p[2][1]);
    if (area == 0.0)
        return 0;
    int x0 = (int)fmax(floor(fmin(p[0][0], fmin(p[1][0], p[2][0]))), 0.0);
    int x1 = (int)fmin(ceil(fmax(p[0][0], fmax(p[1][0], p[2][0]))), (double)res);
    int y0 = (int)fmax(floor(fmin(p[0][1], fmin(p[1][1], p[2][1]))), 0.0);
    int y1 = (int)fmin(ceil(fmax(p[0][1], fmax(p[1][1], p[2][1]))), (double)res);
    long n = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            double px = x + 0.5, py = y + 0.5;
            double e0 = edge(p[0], p[1], px, py), e1 = edge(p[1], p[2], px, py), e2 = edge(p[2], p[0], px, py);
            if (area > 0 ? e0 > 0 && e1 > 0 && e2 > 0 : e0 < 0 && e1 < 0 && e2 < 0)
                n++;
        }
    return n;
}

/* the fragments of every proxy triangle in every VAL's map, replayed */
static long replay_fragments(const vpl_state *s)
{
    long total = 0;
    for (int i = 0; i < s->proxy.n_draws; i++) {
        const vpl_proxy_draw *d = &s->proxy.draws[i];
        glBindBuffer(GL_ARRAY_BUFFER, d->vbo);
        const float *pos = glMapBufferRange(GL_ARRAY_BUFFER, 0, (GLsizeiptr)d->vertices * 3 * sizeof(float),
                                            GL_MAP_READ_BIT);
        assert_non_null(pos);
        mat4 world = H.scene.nodes[d->node].world;
        for (int k = 0; k < s->st.m; k++) {
            float c[3], rnear, far;
            vpl_emitter_params(s, &s->st.vals[k], false, c, &rnear, &far);
            for (int t = 0; t + 2 < d->vertices; t += 3) {
                double p[3][2];
                for (int j = 0; j < 3; j++) {
                    const float *a = pos + 3 * (t + j);
                    project(c, &s->st.vals[k], m4_point(world, v3(a[0], a[1], a[2])), s->val_res, p[j]);
                }
                total += covered(p, s->val_res);
            }
        }
        glUnmapBuffer(GL_ARRAY_BUFFER);
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return total;
}

static double valsm_fragments(void) { return tpw_fetches(H.m, H.self, "gi.vpl_valsm", "raster_r16f_depth_fill"); }

static void val_map_fragments_match_a_replay(void **state)
{
    (void)state;
    static const char *const budgets[] = {"vpl_n=256,vpl_m=4,vpl_val_map=64,vpl_vis=vsm",
                                          "vpl_n=256,vpl_m=8,vpl_val_map=128,vpl_vis=cssm"};
    for (int b = 0; b < 2; b++) {
        assert_int_equal(h_budget(&H, budgets[b]), 0);
        H.count_work = false;
        assert_int_equal(h_frame(&H, 0), 0);
        assert_true(valsm_fragments() < 0.0); /* not a counting frame: nothing counted */
        H.count_work = true;
        assert_int_equal(h_frame(&H, 0), 0);
        H.count_work = false;
        const vpl_state *s = H.self;
        double counted = s->map_fragments.value[0];
        long replay = replay_fragments(s), basis = (long)s->val_res * s->val_res * s->st.m;
        print_message("# %s: %d maps of %d², %ld proxy triangles: counted %.0f fragments, replayed %ld "
                      "(%+.4f%%), basis %ld\n", budgets[b], s->st.m, s->val_res, s->proxy.triangles, counted, replay,
                      100.0 * (counted - (double)replay) / (double)replay, basis);
        assert_true(s->st.m > 0 && replay > 0);
        assert_true(fabs(counted - (double)replay) <= TOLERANCE * (double)replay);
        assert_true(valsm_fragments() == counted + (double)basis);
        /* the mips, a hand count: one lookup per texel of levels 1.. of each map in use, VSM's one
           moment chain at 64² (32² + ... + 1² = 1365 a map), CSSM's 2 RGBA8 and 3 16-bit chains at
           128² (5461 a map) */
        double rgba8 = tpw_fetches(H.m, H.self, "gi.vpl_valsm", "tex2d_rgba8_trilinear");
        double f16 = tpw_fetches(H.m, H.self, "gi.vpl_valsm", "tex2d_rgba16f_trilinear");
        print_message("# mips: %.0f RGBA8 and %.0f 16-bit lookups\n", rgba8, f16);
        if (b == 0)
            assert_true(rgba8 < 0.0 && f16 == 1365.0 * s->st.m);
        else
            assert_true(rgba8 == 2 * 5461.0 * s->st.m && f16 == 3 * 5461.0 * s->st.m);
    }
}

/* The deep-umbra chain's reads (vpl_zmax_reads, from the map's size) against val_zmax.frag's
   counting variant, and its coarser levels against a hand count: 4 reads a texel of levels 2..,
   4 (16² + 8² + 4² + 2² + 1²) = 1364 a 64² map, 4 (32² + ... + 1²) = 5460 at 128². Level 1's reads
   are at most 16 a texel (32² x 16 = 16 384 at 64²) and fewer by the rim's texels. Without the
   chain (vpl_umbra=off) none. */
static void umbra_chain_reads_match_the_shaders_count(void **state)
{
    (void)state;
    static const char *const budgets[] = {"vpl_n=256,vpl_m=4,vpl_val_map=64,vpl_vis=cssm,vpl_umbra=on",
                                          "vpl_n=256,vpl_m=8,vpl_val_map=128,vpl_vis=vsm,vpl_umbra=plane",
                                          "vpl_n=256,vpl_m=4,vpl_val_map=64,vpl_vis=cssm,vpl_umbra=off"};
    static const double coarse[] = {1364.0, 5460.0, 0.0};
    for (int b = 0; b < 3; b++) {
        assert_int_equal(h_budget(&H, budgets[b]), 0);
        H.count_work = true;
        assert_int_equal(h_frame(&H, 0), 0);
        H.count_work = false;
        const vpl_state *s = H.self;
        double model = tpw_fetches(H.m, H.self, "gi.vpl_valsm", "tex2d_r16f_nearest");
        double per_map = vpl_zmax_reads(s->val_res), half = s->val_res / 2;
        print_message("# %s: %d maps of %d²: modelled %.0f chain reads (%.0f a map), counted %.0f\n", budgets[b],
                      s->st.m, s->val_res, model, per_map, s->zmax_fetches.counted ? s->zmax_fetches.value[0] : -1.0);
        assert_true(s->st.m > 0);
        if (b == 2) {
            assert_true(model < 0.0 && !s->zmax_fetches.counted);
            continue;
        }
        assert_true(s->zmax_fetches.counted);
        assert_true(model == per_map * s->st.m && s->zmax_fetches.value[0] == model);
        double level1 = per_map - coarse[b];
        assert_true(level1 > 0.5 * 16.0 * half * half && level1 < 16.0 * half * half);
    }
}

static double gather_fetches(const char *kind) { return tpw_fetches(H.m, H.self, "gi.vpl_gather", kind); }

/* The multi-resolution gather (vpl_gather=multires) runs the interleaved gather's VPL loop over all
   n VPLs once per region it shades. Without visibility (no lookups that depend on the receiver)
   that loop's table reads are the same at every receiver: the dense interleaved gather (block 1,
   every pixel all VPLs; the camera is inside the box, so every pixel gathers) counts pixels x c, and
   the multires one must count its regions (read back from its levels, debug.measure) x the same c,
   2n <= c <= 3n (2 reads a VPL, a third for one that can light anything). */
static void multires_gather_counts_regions(void **state)
{
    (void)state;
    gk_vpl_debug d;
    gk_vpl_default_debug(&d);
    d.fade_frames = 0, d.measure = true, d.vis_override = GK_VPL_VIS_NONE;
    gk_vpl_set_debug(H.self, &d);
    const char *u = "tex2d_rgba32f_nearest";
    assert_int_equal(h_budget(&H, "vpl_n=256,vpl_m=8,vpl_block=1,vpl_res=1,vpl_gather=interleaved"), 0);
    H.count_work = true;
    assert_int_equal(h_frame(&H, 0), 0);
    double dense = gather_fetches(u), c = dense / (W * HH);
    assert_int_equal(h_budget(&H, "vpl_n=256,vpl_m=8,vpl_block=1,vpl_res=1,vpl_gather=multires"), 0);
    assert_int_equal(h_frame(&H, 0), 0);
    H.count_work = false;
    double multires = gather_fetches(u);
    int regions = gk_vpl_get_stats(H.self)->mr_regions;
    print_message("# vis none, n = 256: dense gather %.0f table reads (%.1f a pixel of %d), multires %.0f for %d "
                  "regions (%.1f a region)\n", dense, c, W * HH, multires, regions, multires / regions);
    assert_true(c == floor(c) && c >= 2 * 256 && c <= 3 * 256);
    assert_true(regions > 0 && regions < W * HH && multires == c * regions);
    /* with visibility the lookups depend on the receiver: only that both gathers count some */
    d.vis_override = -1;
    gk_vpl_set_debug(H.self, &d);
    assert_int_equal(h_budget(&H, "vpl_n=256,vpl_m=8,vpl_vis=cssm,vpl_gather=multires"), 0);
    H.count_work = true;
    assert_int_equal(h_frame(&H, 0), 0);
    H.count_work = false;
    assert_true(gather_fetches(u) > 0.0 && gather_fetches("tex2d_rgba8_trilinear") > 0.0);
    gk_vpl_default_debug(&d);
    gk_vpl_set_debug(H.self, &d);
}

/* RGBA of one of the gather's targets (attachment 1: positions, 2: normals), iw x ih floats x 4 */
static float *read_ind_target(const vpl_state *s, int attachment)
{
    float *px = malloc(sizeof(float) * 4 * (size_t)s->iw * (size_t)s->ih);
    assert_non_null(px);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s->ind_fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0 + (GLenum)attachment);
    glReadPixels(0, 0, s->iw, s->ih, GL_RGBA, GL_FLOAT, px);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return px;
}

/* vpl/blur.frag's texel reads, replayed over the targets the gather wrote (read back): per pixel and
   pass its position, its normal where it is a surface, and per tap of the row or column inside the
   image the tap's position, its normal where it is a surface, its irradiance where the normals
   agree (dot > 0.8; no cross-fade here, so no history read). */
static long replay_blur(const vpl_state *s, const float *pos, const float *nrm)
{
    long texels = 0;
    int w = s->iw, h = s->ih, r = s->blur_radius;
    for (int pass = 0; pass < 2; pass++)
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                const float *pc = pos + 4 * ((size_t)y * w + x), *nc = nrm + 4 * ((size_t)y * w + x);
                texels += pc[3] <= 0.0f ? 1 : 2;
                if (pc[3] <= 0.0f)
                    continue;
                for (int k = -r; k <= r; k++) {
                    int ox = x + (pass == 0) * k, oy = y + (pass == 1) * k;
                    if (ox < 0 || oy < 0 || ox >= w || oy >= h)
                        continue;
                    size_t o = 4 * ((size_t)oy * w + ox);
                    texels += pos[o + 3] <= 0.0f ? 1 : 2;
                    if (pos[o + 3] > 0.0f && nrm[o] * nc[0] + nrm[o + 1] * nc[1] + nrm[o + 2] * nc[2] > 0.8f)
                        texels++;
                }
            }
    return texels;
}

/* The blur (gi.vpl_blur) against the replay of its taps, at two indirect resolutions and radii; the
   compose (gi.vpl_compose) against a hand count: the camera is inside the box, so every pixel is
   shaded and every texel of the indirect targets is a surface (checked on the read-back positions),
   so each pixel reads its 2x2 taps' position, normal and irradiance: 12 x W x H. Neither depends on
   the gather (interleaved or multires) that filled the targets. Exact: the same reads, counted. */
static void blur_and_compose_reads_match_a_replay(void **state)
{
    (void)state;
    gk_vpl_debug d;
    gk_vpl_default_debug(&d);
    d.fade_frames = 0; /* no cross-fade: the blur reads no history */
    gk_vpl_set_debug(H.self, &d);
    static const char *const budgets[] = {"vpl_n=256,vpl_m=4,vpl_res=0.5,vpl_blur=2",
                                          "vpl_n=256,vpl_m=8,vpl_res=1,vpl_blur=8",
                                          "vpl_n=256,vpl_m=8,vpl_res=0.5,vpl_blur=4,vpl_gather=multires"};
    for (int b = 0; b < 3; b++) {
        assert_int_equal(h_budget(&H, budgets[b]), 0);
        assert_int_equal(h_frame(&H, 0), 0);
        assert_true(tpw_fetches(H.m, H.self, "gi.vpl_blur", "tex2d_rgba32f_nearest") < 0.0); /* not counting */
        H.count_work = true;
        assert_int_equal(h_frame(&H, 0), 0);
        H.count_work = false;
        const vpl_state *s = H.self;
        float *pos = read_ind_target(s, 1), *nrm = read_ind_target(s, 2);
        long surfaces = 0, replay = replay_blur(s, pos, nrm);
        for (int i = 0; i < s->iw * s->ih; i++)
            surfaces += pos[4 * i + 3] > 0.0f;
        free(pos);
        free(nrm);
        double blur = tpw_fetches(H.m, H.self, "gi.vpl_blur", "tex2d_rgba32f_nearest");
        double compose = tpw_fetches(H.m, H.self, "gi.vpl_compose", "tex2d_rgba32f_nearest");
        print_message("# %s: indirect %dx%d, radius %d: blur %.0f texels counted, %ld replayed; compose %.0f\n",
                      budgets[b], s->iw, s->ih, s->blur_radius, blur, replay, compose);
        assert_true(surfaces == (long)s->iw * s->ih);
        assert_true(replay > 2L * 2 * s->iw * s->ih && blur == (double)replay);
        assert_true(compose == 12.0 * W * HH);
    }
    gk_vpl_default_debug(&d);
    gk_vpl_set_debug(H.self, &d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(val_map_fragments_match_a_replay),
        cmocka_unit_test(umbra_chain_reads_match_the_shaders_count),
        cmocka_unit_test(multires_gather_counts_regions),
        cmocka_unit_test(blur_and_compose_reads_match_a_replay),
    };
    return cmocka_run_group_tests_name("vpl_work", tests, setup, teardown);
}
