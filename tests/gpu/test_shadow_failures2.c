/* Failure tests of dong-001.md §10 not in test_shadow_failures.c, and the shadow_subdiv knob:
 *   F2 CSSM ringing: V sampled along the normal of a straight shadow edge (T1, S = 1) must be
 *      monotone with ringing suppression (cssm_sat: alpha = 1.12 + sharpening) and shows extrema
 *      without it (cssm_raw: alpha = 1, A = 0; both SAT-prefiltered, so only the suppression differs).
 *   F3 contact leak: a unit cube on the receiver (T3), light off to the side so that a band along
 *      the cube's shadowed base is umbra; mean V there for vssm, vssm_nocontact, pcss, cssm_sat,
 *      cssm_raw.
 *   F7 SAT exactness read-back: the r32ui (z, z^2) SATs of a real T3 light-view depth map are read
 *      back; their modular box sums must equal a double-precision CPU SAT of the same quantised
 *      depths bit for bit, while a float32 SAT of the same data must not.
 *   shadow_subdiv: the VSSM subdivision knob (renderer_knobs.c): level 3 = no pin (the thesis's
 *      m = 5, H = 3), level 0 changes the non-planar kernels and costs no accuracy on T3's floor
 *      beyond a measured bound.
 * 128x128 pixels, shadow map 512. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gpu/test_shadow_util.h"
#include "render/shadow/shadow_prefilter.h"

SX_SESSION_GROUP(128)
#define MAP 512



/* Renders V = L / L_unblocked of `method` (extra pins appended) for a set-up; truth into t. */
static void render_v(const sx_setup *st, const char *pins_extra, const char *method, float *v, sx_truth *t)
{
    fx_scene with, without;
    sx_build(&with, st, true);
    sx_build(&without, st, false);
    sx_truth_build(t, &with, st, W, H);
    static float a[W * H], b[W * H];
    char pins[160];
    gk_err e = {0};
    snprintf(pins, sizeof pins, "shadow=%s,shadow_map=%d%s", method, MAP, pins_extra ? pins_extra : "");
    if (gk_renderer_set_scene(ses.r, &without.s, &e) != 0 || sx_draw(&ses, "shadow=hard,shadow_map=512", b) != 0 ||
        gk_renderer_set_scene(ses.r, &with.s, &e) != 0 || sx_draw(&ses, pins, a) != 0)
        fail_msg("render %s: %s", method, e.msg);
    gk_renderer_set_scene(ses.r, NULL, &e);
    sx_ratio(a, b, t, v);
    gkt_scene_free(&with);
    gkt_scene_free(&without);
}

/* --- F2 ---------------------------------------------------------------------------------------- */
/* T1 seen from a camera under the blocker looking straight down at the edge z = +1's penumbra
   (exact: z in [1.167, 1.5] for S = 1): image rows run along world z, the edge normal, at 8 mm
   per pixel, so the penumbra spans ~40 rows. */
static sx_setup f2_setup(void)
{
    sx_setup st = {.S = 1, .light = v3(0, SX_LIGHT_Y, 0), .n_rects = 1, .eye = v3(0, 0.9f, 1.33f),
                   .target = v3(0, 0, 1.33f), .yfov = 1.0471976f};
    st.rect[0] = (sx_rect){-1, 1, -1, 1, 1};
    return st;
}

/* Direction reversals of a profile that swing by more than tol (hysteresis): the local extrema. */
static int count_extrema(const double *p, int n, double tol)
{
    int count = 0, dir = 0;
    double anchor = p[0];
    for (int i = 1; i < n; i++) {
        if (dir >= 0 && p[i] < anchor - tol) {
            count += dir > 0;
            dir = -1;
            anchor = p[i];
        } else if (dir <= 0 && p[i] > anchor + tol) {
            count += dir < 0;
            dir = 1;
            anchor = p[i];
        } else if ((dir > 0 && p[i] > anchor) || (dir < 0 && p[i] < anchor)) {
            anchor = p[i];
        }
    }
    return count;
}

/* Profile along the edge normal: the mean of the 16 centre columns per row (the line x ~ 0),
   rows ordered by world z; returns the extrema count with tolerance tol. */
static int f2_extrema(const char *method, double tol, double *vmin, double *vmax)
{
    sx_setup st = f2_setup();
    static float v[W * H];
    sx_truth t;
    render_v(&st, NULL, method, v, &t);
    double prof[H];
    int n = 0;
    *vmin = 1e9, *vmax = -1e9;
    for (int y = 0; y < H; y++) {
        double s = 0;
        int k = 0;
        for (int x = W / 2 - 8; x < W / 2 + 8; x++)
            if (t.valid[y * W + x] && !isnan(v[y * W + x]))
                s += v[y * W + x], k++;
        if (k == 16) {
            prof[n++] = s / k;
            *vmin = fmin(*vmin, s / k);
            *vmax = fmax(*vmax, s / k);
        }
    }
    sx_truth_free(&t);
    assert_true(n > H - 4);
    int ext = count_extrema(prof, n, tol);
    printf("# F2 %-9s %d local extrema (tol %.3f) along %d samples of the edge normal, V in [%.3f, %.3f]\n", method,
           ext, tol, n, *vmin, *vmax);
    return ext;
}

/* The same edge-normal line cannot ring on T1 (measured: 0 extrema for cssm_raw too): receiver
   and blocker are parallel, so d - z is one constant and V is a monotone mix of two values of the
   series. The Fourier ringing lives in d - z (dong-001.md §3.3, Fig. 5.2), so the second profile
   sweeps it: T1 with the blocker at heights y = 0.3 .. 3.3 (d - z = y along the map axis), V at the umbra
   centre under the blocker (camera at y = 0.25 looking down, exact V = 0 for every height). */
static int f2_depth_sweep(const char *method, double tol, double *vmax)
{
    enum { NH = 13 };
    double prof[NH];
    for (int k = 0; k < NH; k++) {
        float y = 0.3f + 0.25f * (float)k;
        sx_setup st = {.S = 1, .light = v3(0, SX_LIGHT_Y, 0), .n_rects = 1, .eye = v3(0, 0.25f, 0),
                       .target = v3(0, 0, 0), .yfov = 1.0471976f};
        st.rect[0] = (sx_rect){-1, 1, -1, 1, y};
        static float v[W * H];
        sx_truth t;
        render_v(&st, NULL, method, v, &t);
        double s = 0;
        int n = 0;
        for (int i = 0; i < W * H; i++)
            if (t.valid[i] && !isnan(v[i]))
                s += v[i], n++;
        sx_truth_free(&t);
        assert_true(n > W * H / 2);
        prof[k] = s / n;
    }
    /* The plateau: d - z >= 1.3 m (k >= 4), where the suppressed test has saturated to 0. Below
       it is the contact slope (F3's leak), where both methods fall from ~0.5 towards 0. */
    *vmax = 0;
    for (int k = 4; k < NH; k++)
        *vmax = fmax(*vmax, prof[k]);
    int ext = count_extrema(prof + 4, NH - 4, tol);
    printf("# F2 %-9s umbra V vs d - z = 0.3..3.3 m:", method);
    for (int k = 0; k < NH; k++)
        printf(" %.3f", prof[k]);
    printf(" -> on the plateau (d - z >= 1.3 m) %d extrema (tol %.3f), max V %.3f\n", ext, tol, *vmax);
    return ext;
}

static void f2_cssm_ringing_suppressed(void **state)
{
    (void)state;
    double lo, hi;
    /* tol: the fp16 HDR target quantises each radiance to 2^-11 relative, i.e. the ratio V to
       ~1e-3; averaged over 16 columns the profile's noise is below that. 0.01 is 10x it. */
    int sat = f2_extrema("cssm_sat", 0.01, &lo, &hi);
    assert_true(hi - lo > 0.5); /* the line really crosses umbra -> lit */
    int raw = f2_extrema("cssm_raw", 0.01, &lo, &hi);
    int mm = f2_extrema("cssm", 0.01, &lo, &hi);
    /* Measured along the edge normal: cssm_sat 0, cssm_raw 0, cssm 0 extrema (V 0.195..1,
       0.228..0.969, 0.193..1) -- monotone for all, as T1's geometry implies (see above). Asserted
       for the suppressed paths only; raw is reported, it cannot fail here. */
    assert_int_equal(sat, 0);
    assert_int_equal(mm, 0);
    (void)raw;
    double vs, vr;
    int ds = f2_depth_sweep("cssm_sat", 0.01, &vs), dr = f2_depth_sweep("cssm_raw", 0.01, &vr);
    /* Measured on the plateau: cssm_sat 0 extrema, max V 0.000; cssm_raw 0 extrema, a ripple up to
       0.054 (exactly the K = 4 ripple that dong-001.md §3.3 sizes alpha >= 1.12 for, 0.5 (1 -
       1/1.12) = 0.054). Before #11 (depth over [near, far]) the raw ripple also had 2 local
       extrema in this sweep; with each map layer's own depth range (cssm_range.comp) the same
       0.3..3.3 m covers a longer stretch of the series, where the ripple decays monotonically
       from its peak, so the extremum count no longer shows it; the plateau leak does. Bounds:
       suppressed monotone and below 0.01 (10x the fp16 read-out noise); raw ripple > 0.03 (0.6x
       the measured one). */
    assert_int_equal(ds, 0);
    assert_true(vs < 0.01);
    assert_true(vr > 0.03);
    (void)dr;
}

/* --- F3 ---------------------------------------------------------------------------------------- */
/* T3: the unit cube (45 degree yaw) on the receiver; the light (S = 1, y = 4) off to +x so the
   band along the cube's -x base is umbra; camera on the -x side looking at that band. */
static sx_setup f3_setup(void)
{
    sx_setup st = {.S = 1, .light = v3(2, SX_LIGHT_Y, 0), .box = true, .box_yaw = 0.7853982f,
                   .eye = v3(-3.0f, 2.4f, 0.7f), .target = v3(-0.9f, 0, 0), .yfov = 1.0471976f};
    return st;
}

/* Distance on the receiver from p to the cube's footprint. */
static double footprint_dist(const sx_setup *st, vec3 p)
{
    float c = cosf(st->box_yaw), s = sinf(st->box_yaw);
    double u = fabs(c * p.x - s * p.z) - 0.5, w = fabs(s * p.x + c * p.z) - 0.5;
    return hypot(fmax(u, 0), fmax(w, 0));
}

typedef struct f3_result {
    double mean_v, mean_pos_err;
    int n;
} f3_result;

/* Mean V over the contact band: receiver pixels within `band` m of the footprint whose exact V is
   0 (umbra), and the mean positive error max(V - V_exact, 0) over all band pixels. */
static f3_result f3_measure(const char *method, const char *pins, double band)
{
    sx_setup st = f3_setup();
    static float v[W * H];
    sx_truth t;
    render_v(&st, pins, method, v, &t);
    f3_result r = {0};
    int n_all = 0;
    for (int i = 0; i < W * H; i++) {
        if (!t.valid[i] || isnan(v[i]) || footprint_dist(&st, t.p[i]) > band)
            continue;
        r.mean_pos_err += fmax(v[i] - t.v[i], 0.0);
        n_all++;
        if (t.v[i] <= 1e-6f) {
            r.mean_v += v[i];
            r.n++;
        }
    }
    sx_truth_free(&t);
    r.mean_v /= r.n ? r.n : 1;
    r.mean_pos_err /= n_all ? n_all : 1;
    printf("# F3 %-15s%s contact band %.2f m: mean V %.4f over %d umbra pixels, mean max(V - V_exact, 0) %.4f over %d\n",
           method, pins ? pins : "", band, r.mean_v, r.n, r.mean_pos_err, n_all);
    return r;
}

static void f3_contact_leak(void **state)
{
    (void)state;
    const double band = 0.1; /* 4 map texels (a texel is 2.4 cm at the receiver) */
    f3_result vssm = f3_measure("vssm", NULL, band), noc = f3_measure("vssm_nocontact", NULL, band),
              pcss = f3_measure("pcss", NULL, band), csat = f3_measure("cssm_sat", NULL, band),
              craw = f3_measure("cssm_raw", NULL, band);
    assert_true(vssm.n > 30);
    /* Measured (103 umbra pixels within 0.1 m of the base): mean V vssm 0.0413, vssm_nocontact
       0.0413 (0.0636 before #21's search bound), pcss 0.0250, cssm_sat 0.031, cssm_raw 0.077 (before #11, with the depth over
       [near, far]: cssm_sat 0.383, cssm_raw 0.399).
       - The contact fallback (|z_occ - d| < 0.01 r_sc = 7 cm) does not fire here: the blocker the
         map sees over this band is the cube's top, 1 m above the receiver, so vssm and
         vssm_nocontact are identical; the residual 0.041 is Chebyshev's bound over kernels that
         straddle the cube's silhouette. Asserted: the fallback never makes it worse.
       - CSSM K = 4's contact leak came from the transition width: 0.064 of the normalised depth
         past the shifted receiver was 0.7 m over [near, far]; over the layer's own depth range
         it is a few centimetres, so the leak drops to 0.03 with the thesis's alpha = 1.12 and
         sharpening (the sharpening itself barely acts: d - z_avg ~ 1 m, exp(-10) ~ 0).
       Bounds ~1.5x the measurements so regressions show. */
    assert_true(vssm.mean_v <= noc.mean_v + 0.005);
    assert_true(vssm.mean_v < 0.1);
    assert_true(pcss.mean_v < 0.04 && pcss.mean_v < vssm.mean_v);
    assert_true(craw.mean_v < 0.12 && csat.mean_v < 0.05);
    assert_true(csat.mean_v <= craw.mean_v + 0.005);
}

/* --- F7 ---------------------------------------------------------------------------------------- */
static void read_layer(GLuint tex, bool integer, void *out)
{
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, tex, 0, 0);
    assert_int_equal(glCheckFramebufferStatus(GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    glReadPixels(0, 0, MAP, MAP, integer ? GL_RGBA_INTEGER : GL_RGBA, integer ? GL_UNSIGNED_INT : GL_FLOAT, out);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    assert_int_equal(glGetError(), GL_NO_ERROR);
}

static void f7_sat_exact_readback(void **state)
{
    (void)state;
    /* The T3 depth map from the light, through the same code the VSSM method runs. */
    sx_setup st = f3_setup();
    fx_scene f;
    sx_build(&f, &st, true);
    gk_scene_evaluate(&f.s, 0);
    int node = -1;
    for (int i = 0; i < f.s.n_nodes; i++)
        if (f.s.nodes[i].light >= 0)
            node = i;
    gk_err e = {0};
    gk_program_cache *progs = gk_program_cache_create(getenv("GK_SHADER_DIR"), 32);
    gk_scene_gpu gpu = {0};
    gk_shadow_view v;
    gk_shadow_maps maps = {0};
    assert_non_null(progs);
    assert_int_equal(gk_scene_gpu_upload(&gpu, &f.s, &e), 0);
    assert_true(gk_shadow_view_for_light(&f.s, node, MAP, &v));
    gk_shadow_ctx ctx = {.progs = progs, .scene = &f.s, .gpu = &gpu};
    GLuint z = gk_pf_array_create(GL_R32F, MAP, 1, 1, false, &e), sz = gk_pf_array_create(GL_R32UI, MAP, 1, 1, false, &e),
           sz2 = gk_pf_array_create(GL_R32UI, MAP, 1, 1, false, &e), rz = gk_pf_array_create(GL_R32UI, MAP, 1, 1, false, &e),
           rz2 = gk_pf_array_create(GL_R32UI, MAP, 1, 1, false, &e);
    float q = (float)((1u << gk_sat_bits(MAP)) - 1u);
    assert_int_equal(gk_shadow_maps_render(&maps, &ctx, 0, &v, &e), 0);
    assert_int_equal(gk_pf_linearize(progs, maps.tex[0], &v, z, 0, &e), 0);
    assert_int_equal(gk_pf_sat(progs, 0, z, MAP, 1, q, 1.0f, sz, sz2, 0, 0, &e), 0);
    /* The row pass alone (the same program gk_pf_sat ran first): differences along a row are the
       exact per-texel fixed-point values the shader quantised, z * q and z^2 * q rounded. */
    GLuint rows = gk_program_get_compute(progs, "shadow/vssm_sat.comp", "#define SAT_ROWS 1\n#define SAT_BASIS 0\n", &e);
    assert_true(rows != 0);
    glUseProgram(rows);
    gk_pf_bind(glGetUniformLocation(rows, "u_z"), z, 0);
    gk_uniform_1i(rows, "u_size", MAP);
    gk_uniform_1f(rows, "u_q", q);
    gk_uniform_1f(rows, "u_range", 1.0f);
    glBindImageTexture(0, rz, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
    glBindImageTexture(1, rz2, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
    glDispatchCompute((MAP + 63) / 64, 1, 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    glUseProgram(0);

    size_t n = (size_t)MAP * MAP;
    uint32_t *rgba = malloc(n * 4 * sizeof(uint32_t));
    float *zf = malloc(n * 4 * sizeof(float));
    uint32_t *S[2] = {malloc(n * 4), malloc(n * 4)}, *val[2] = {malloc(n * 4), malloc(n * 4)};
    GLuint sat_tex[2] = {sz, sz2}, row_tex[2] = {rz, rz2};
    for (int c = 0; c < 2; c++) {
        read_layer(sat_tex[c], true, rgba);
        for (size_t i = 0; i < n; i++)
            S[c][i] = rgba[4 * i];
        read_layer(row_tex[c], true, rgba);
        for (size_t i = 0; i < n; i++)
            val[c][i] = rgba[4 * i] - (i % MAP ? rgba[4 * (i - 1)] : 0u);
    }
    read_layer(z, false, zf);
    /* The values are the depths: |val / q - z| <= 0.5 / q (+ fp32 rounding of z * q). */
    double qerr = 0, zmin = 1, zmax = 0;
    for (size_t i = 0; i < n; i++) {
        qerr = fmax(qerr, fabs(val[0][i] / (double)q - zf[4 * i]));
        zmin = fmin(zmin, zf[4 * i]), zmax = fmax(zmax, zf[4 * i]);
    }
    printf("# F7 map %d, %d fixed-point bits, z in [%.4f, %.4f], max |val/q - z| %.2e (half quantum %.2e)\n", MAP,
           gk_sat_bits(MAP), zmin, zmax, qerr, 0.5 / q);
    assert_true(qerr <= 0.51 / q);
    assert_true(zmax - zmin > 0.05); /* the cube is in the map */

    /* CPU SATs of the same values: exact in double (sums < 2^53), and in float32 as a GPU float
       SAT would hold them (row then column prefix of val / q). */
    double *D[2] = {malloc(n * 8), malloc(n * 8)};
    float *F[2] = {malloc(n * 4), malloc(n * 4)};
    for (int c = 0; c < 2; c++) {
        for (int y = 0; y < MAP; y++)
            for (int x = 0; x < MAP; x++) {
                size_t i = (size_t)y * MAP + x;
                D[c][i] = val[c][i] + (x ? D[c][i - 1] : 0);
                F[c][i] = (float)(val[c][i] / (double)q) + (x ? F[c][i - 1] : 0.0f);
            }
        for (int y = 1; y < MAP; y++)
            for (int x = 0; x < MAP; x++) {
                size_t i = (size_t)y * MAP + x;
                D[c][i] += D[c][i - MAP];
                F[c][i] += F[c][i - MAP];
            }
    }
    /* Boxes: every 3x3 box along the cube's base in the map (the contact) plus random boxes up to
       the widest kernel (a quarter map), all corners anywhere in the map. */
    unsigned rng = 12345u;
    int boxes = 0, int_bad = 0, float_bad = 0;
    double float_mean_err = 0, float_var_err = 0;
    int wmax = (int)(GK_SOFT_MAX_KERNEL * MAP) + 2;
    for (int k = 0; k < 40000; k++) {
        int bw, bh, x0, y0;
        if (k < 20000) { /* 3x3 boxes where the depth changes (cube silhouette and base) */
            bw = bh = 3;
            x0 = (int)((rng = rng * 1664525u + 1013904223u) >> 8) % (MAP - 4);
            y0 = (int)((rng = rng * 1664525u + 1013904223u) >> 8) % (MAP - 4);
        } else {
            bw = 1 + (int)((rng = rng * 1664525u + 1013904223u) >> 8) % wmax;
            bh = 1 + (int)((rng = rng * 1664525u + 1013904223u) >> 8) % wmax;
            x0 = (int)((rng = rng * 1664525u + 1013904223u) >> 8) % (MAP - bw);
            y0 = (int)((rng = rng * 1664525u + 1013904223u) >> 8) % (MAP - bh);
        }
        size_t a = (size_t)y0 * MAP + x0, b = a + bw, c2 = a + (size_t)bh * MAP, d = c2 + bw; /* corners (x0,y0) exclusive */
        double fm[2], em[2];
        for (int c = 0; c < 2; c++) {
            uint32_t gi = S[c][d] - S[c][b] - S[c][c2] + S[c][a];
            double exact = D[c][d] - D[c][b] - D[c][c2] + D[c][a];
            int_bad += (double)gi != exact;
            float fs = F[c][d] - F[c][b] - F[c][c2] + F[c][a];
            fm[c] = fs / (bw * bh);
            em[c] = exact / q / (bw * bh);
            float_bad += fabs(fs - exact / q) > 0.5 / q; /* off by more than rounding to the nearest quantum */
        }
        float_mean_err = fmax(float_mean_err, fabs(fm[0] - em[0]));
        float_var_err = fmax(float_var_err, fabs((fm[1] - fm[0] * fm[0]) - (em[1] - em[0] * em[0])));
        boxes++;
    }
    printf("# F7 %d boxes x 2 moments: integer SAT %d mismatches (bit-exact required); float32 SAT %d off by more than "
           "half a quantum, max |mean error| %.2e, max |variance error| %.2e (quantum %.2e)\n",
           boxes, int_bad, float_bad, float_mean_err, float_var_err, 1.0 / q);
    /* Measured: 0 integer mismatches; float32: 59995 of 80000 box sums off by more than half a
       quantum, box means off by up to 2.8e-3 and variances by 2.8e-3 (~360 quanta; the VSSM
       planar-lit threshold eps^2 is ~5e-5, so a float SAT would misclassify flat kernels at the
       far corner of the map). Asserted: bit-exact integers; float32 wrong on > 10% of the boxes
       and by > 10 quanta in the mean somewhere. */
    assert_int_equal(int_bad, 0);
    assert_true(float_bad > boxes / 5);
    assert_true(float_mean_err > 10.0 / q);

    for (int c = 0; c < 2; c++)
        free(S[c]), free(val[c]), free(D[c]), free(F[c]);
    free(rgba);
    free(zf);
    GLuint texs[5] = {z, sz, sz2, rz, rz2};
    glDeleteTextures(5, texs);
    gk_shadow_maps_free(&maps);
    gk_scene_gpu_free(&gpu);
    gk_program_cache_destroy(progs);
    gkt_scene_free(&f);
}

/* --- shadow_subdiv ------------------------------------------------------------------------------ */
static void subdiv_knob_levels(void **state)
{
    (void)state;
    sx_setup st = f3_setup();
    static float v[5][W * H], vdef[W * H];
    double pen[5];
    int diff[5];
    sx_truth t;
    render_v(&st, NULL, "vssm", vdef, &t);
    sx_truth_free(&t);
    for (int l = 0; l < 5; l++) {
        char pins[32];
        snprintf(pins, sizeof pins, ",shadow_subdiv=%d", l);
        render_v(&st, pins, "vssm", v[l], &t);
        sx_stats s = sx_compare(v[l], &t);
        int differ = 0;
        for (int i = 0; i < W * H; i++)
            differ += !isnan(v[l][i]) && !isnan(vdef[i]) && fabsf(v[l][i] - vdef[i]) > 1e-3f;
        char what[24];
        snprintf(what, sizeof what, "subdiv=%d", l);
        sx_print(what, "vssm", &s);
        printf("#   %d pixels differ from the unpinned default by > 1e-3\n", differ);
        sx_truth_free(&t);
        pen[l] = s.mean[SX_PENUMBRA];
        diff[l] = differ;
    }
    /* Measured: pixels differing from the default 102 / 36 / 2 / 0 / 4 for levels 0..4 (before
       #21's search bound 118 / 11 / 1 / 0 / 0), floor errors within 0.001 of each other (the
       non-planar kernels are on the cube's top edges, whose exact V the floor-only truth does not
       score). Asserted: the default is level 3 exactly, level 0
       really changes the image (> 30 pixels), and no level costs more than 0.005 penumbra error. */
    assert_int_equal(diff[3], 0);
    assert_true(diff[0] > 30 && diff[0] > diff[2]);
    for (int l = 0; l < 5; l++)
        assert_true(pen[l] < pen[3] + 0.005);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(f2_cssm_ringing_suppressed),
        cmocka_unit_test(f3_contact_leak),
        cmocka_unit_test(f7_sat_exact_readback),
        cmocka_unit_test(subdiv_knob_levels),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
