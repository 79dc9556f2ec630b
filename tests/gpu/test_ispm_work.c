/* The caustic passes' work models (app/gi/ispm/ispm_work.c, #21) against independent counts, on
 * test_ispm_mirror's scene (a square mirror over a grey floor, a camera straight down at the floor,
 * the mirror off-screen): every pixel of the lists sees the floor and nothing else, so
 *   ispm_lists: fragments = trace_res² exactly (a hand count), 5 atomics each;
 *   ispm_trace: the photons read back are marched again on the CPU (trace.comp's march, in float,
 *     against the GPU's own per-pixel lists: one node, the floor, whose depth is the pixel's zmin)
 *     and the steps and nodes visited are counted;
 *   ispm_splat: the hits read back are turned into splat.vert's quads and the splat target's pixel
 *     centres inside them are counted (edge functions in double);
 *   ispm_upsample: every pixel is lit, so each reads the taps of its 3x3 with a bilinear weight: one a
 *     side at ispm_splat=1 (the low-resolution position lands on a texel centre), two at 0.5 (it
 *     lands a quarter texel off the centres) -- except that upsample.frag clamps a tap to the target
 *     before its weight, so next to the screen's edge a tap outside reads the edge texel once more:
 *     at 1 the first and last pixel of each row and column, at 0.5 the second and second-to-last.
 *     So (W + 2) x (H + 2) and (2 W + 2) x (2 H + 2) (a hand count; 19 764 and 77 924 measured).
 * Without count_work nothing is reported. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "gi/ispm/ispm_internal.h"
#include "test_ispm_harness.h"
#include "test_pass_work.h"

#define W 160
#define HH 120
#define FOV_DEG 40.0f
#define CAM_H 2.0f

/* Measured on llvmpipe (1236 photons): the march's loads counted - replayed = +1 of 63 238 at
   ispm_trace=64 and -8 of 102 526 at 128 (float replays of a float shader: a ray's depth within
   rounding of a list's range or a hit's reach), bound 4x the larger (4e-4); the splats' fragments
   0 of 21 401 and 0 of 83 525 with the corners snapped to llvmpipe's 8 sub-pixel bits and the
   top-left rule (unsnapped and strict the replay was off by 0.15%: whole edges of pixel centres
   flip), bound 1e-4. A model off by one step per photon is off by 1.2%, one that misses a splat's
   edge row by 10%+. A rasterizer with other sub-pixel precision would need its own snapping here. */
#define TRACE_TOLERANCE 4e-4
#define SPLAT_TOLERANCE 1e-4
#define SUBPIXELS 256.0

static gkt_scene T;
static ispm_h H;

static int setup(void **state)
{
    (void)state;
    gkt_scene_init(&T, "ispm-work-mirror");
    int grey = gkt_material_lambert(&T, v3(0.75f, 0.75f, 0.75f)), mirror = gkt_material(&T, v3(1, 1, 1), 1, 0);
    gkt_quad(&T, v3(-3, 0, -3), v3(3, 0, -3), v3(3, 0, 3), v3(-3, 0, 3), v3(0, 1, 0), grey);
    gkt_quad(&T, v3(-0.2f, 1, -0.2f), v3(0.2f, 1, -0.2f), v3(0.2f, 1, 0.2f), v3(-0.2f, 1, 0.2f), v3(0, -1, 0), mirror);
    gkt_light(&T, GK_LIGHT_POINT, GK_SHAPE_POINT, 10.0f, v3(-0.6f, 0.5f, 0.0f), v3(1, 1, 0));
    gkt_camera(&T, v3(1.2f, CAM_H, 0), v3(1.2f, 0, 0), FOV_DEG * (float)M_PI / 180.0f);
    gkt_scene_bounds(&T);
    return ih_open_built(&H, &T, W, HH);
}

static int teardown(void **state)
{
    (void)state;
    ih_close_built(&H, &T);
    return 0;
}

static double work_of(const char *pass, const char *kind) { return tpw_fetches(&gk_gi_ispm, H.self, pass, kind); }

static void counting_frame(const char *budget)
{
    assert_int_equal(ih_budget(&H, budget), 0);
    H.count_work = false;
    assert_int_equal(ih_frame(&H), 0);
    assert_true(work_of("gi.ispm_trace", "ssbo_rgba32f_load") < 0.0); /* not a counting frame */
    assert_true(work_of("gi.ispm_splat", "raster_r16f_depth_fill") < 0.0);
    assert_true(work_of("gi.ispm_upsample", "tex2d_rgba32f_nearest") < 0.0);
    assert_true(work_of("gi.ispm_photons", "raster_r16f_depth_fill") < 0.0);
    H.count_work = true;
    assert_int_equal(ih_frame(&H), 0);
    H.count_work = false;
}

/* ---- the march (trace.comp), replayed ---- */

typedef struct march_ctx {
    mat4 view, proj;
    int res;
    float near, tmax, eps_abs, eps_slope, skip_rel, hit_px, edge_on_cos, edge_reach;
    const gk_ispm_pixel *px;
} march_ctx;

static vec3 xyz(vec4 v) { return v3(v.x, v.y, v.z); }

/* trace.comp's pixel_point: the view-space point of trace pixel (x, y) at linear depth z */
static vec3 pixel_point(const march_ctx *c, int x, int y, float z)
{
    float nx = ((float)x + 0.5f) / (float)c->res * 2.0f - 1.0f, ny = ((float)y + 0.5f) / (float)c->res * 2.0f - 1.0f;
    return v3(z * (nx + c->proj.m[8]) / c->proj.m[0], z * (ny + c->proj.m[9]) / c->proj.m[5], -z);
}

static float uint_float(unsigned u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* window position of view-space point p in the res² trace image */
static void to_screen(const march_ctx *c, vec3 p, float out[2])
{
    vec4 q = m4_vec4(c->proj, (vec4){p.x, p.y, p.z, 1.0f});
    out[0] = (q.x / q.w * 0.5f + 0.5f) * (float)c->res, out[1] = (q.y / q.w * 0.5f + 0.5f) * (float)c->res;
}

/* The loads of one photon's march o + r·t until its first hit (the floor, normal +y, its only node). */
static long march_loads(const march_ctx *c, vec3 o, vec3 r)
{
    vec3 a = xyz(m4_vec4(c->view, (vec4){o.x, o.y, o.z, 1.0f}));
    vec3 e = v3_add(o, v3_scale(r, c->tmax));
    vec3 b = xyz(m4_vec4(c->view, (vec4){e.x, e.y, e.z, 1.0f}));
    if (a.z > -c->near && b.z > -c->near)
        return 0;
    float ta = 0.0f, tb = 1.0f;
    if (a.z > -c->near)
        ta = (-c->near - a.z) / (b.z - a.z);
    if (b.z > -c->near)
        tb = (-c->near - a.z) / (b.z - a.z);
    vec3 A = v3_lerp(a, b, ta), B = v3_lerp(a, b, tb), AB = v3_sub(B, A);
    vec4 ca = m4_vec4(c->proj, (vec4){A.x, A.y, A.z, 1.0f}), cb = m4_vec4(c->proj, (vec4){B.x, B.y, B.z, 1.0f});
    float res = (float)c->res;
    float sa[2] = {(ca.x / ca.w * 0.5f + 0.5f) * res, (ca.y / ca.w * 0.5f + 0.5f) * res};
    float sb[2] = {(cb.x / cb.w * 0.5f + 0.5f) * res, (cb.y / cb.w * 0.5f + 0.5f) * res};
    float ia = 1.0f / ca.w, ib = 1.0f / cb.w, s0 = 0.0f, s1 = 1.0f, dsv[2] = {sb[0] - sa[0], sb[1] - sa[1]};
    for (int ax = 0; ax < 2; ax++) {
        float lo = -sa[ax], hi = res - sa[ax], dv = dsv[ax];
        if (fabsf(dv) < 1e-9f) {
            if (lo > 0.0f || hi < 0.0f)
                return 0;
        } else {
            float t0 = lo / dv, t1 = hi / dv;
            s0 = fmaxf(s0, fminf(t0, t1));
            s1 = fminf(s1, fmaxf(t0, t1));
        }
    }
    if (s0 > s1)
        return 0;
    float len = fmaxf(fabsf(dsv[0]), fabsf(dsv[1])) * (s1 - s0);
    int n = (int)ceilf(len) + 1;
    float ds = n > 1 ? (s1 - s0) / (float)(n - 1) : 0.0f;
    float px_angle = 2.0f * fmaxf(1.0f / c->proj.m[0], 1.0f / c->proj.m[5]) / res;
    vec3 nv = xyz(m4_vec4(c->view, (vec4){0.0f, 1.0f, 0.0f, 0.0f})); /* the floor's normal in view space */
    long loads = 0;
    for (int k = 0; k < n; ++k) {
        loads++;
        float s = s0 + (float)k * ds;
        int x = (int)floorf(sa[0] + (sb[0] - sa[0]) * s), y = (int)floorf(sa[1] + (sb[1] - sa[1]) * s);
        x = x < 0 ? 0 : x >= c->res ? c->res - 1 : x;
        y = y < 0 ? 0 : y >= c->res ? c->res - 1 : y;
        float zr = 1.0f / (ia + (ib - ia) * s);
        float zr1 = 1.0f / (ia + (ib - ia) * fminf(1.0f, s + fmaxf(ds, 1e-6f)));
        float eps = c->eps_abs + c->eps_slope * fabsf(zr1 - zr);
        const gk_ispm_pixel *q = &c->px[y * c->res + x];
        float margin = eps + c->skip_rel * zr + fabsf(zr1 - zr);
        if (q->head < 0 || zr < uint_float(q->zmin) - margin || zr > uint_float(q->zmax) + margin)
            continue;
        loads++; /* its one node: the floor (r points down: not its back) */
        float depth = uint_float(q->zmin);
        vec3 pn = pixel_point(c, x, y, depth);
        float den = v3_dot(AB, nv);
        if (fabsf(den) < 1e-12f)
            continue;
        float u = v3_dot(v3_sub(pn, A), nv) / den;
        if (u < 0.0f || u > 1.0f)
            continue;
        vec3 Q = v3_add(A, v3_scale(AB, u));
        float sq[2];
        to_screen(c, Q, sq);
        float dx = sq[0] - ((float)x + 0.5f), dy = sq[1] - ((float)y + 0.5f);
        if (fmaxf(fabsf(dx), fabsf(dy)) > c->hit_px)
            continue;
        if (fabsf(v3_dot(nv, pn)) < c->edge_on_cos * v3_len(pn) &&
            v3_len(v3_sub(Q, pn)) > c->edge_reach * depth * px_angle)
            continue;
        return loads; /* the first pixel with a hit ends the march */
    }
    return loads;
}

static long replay_trace(void)
{
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    gk_ispm_debug d;
    gk_ispm_default_debug(&d);
    march_ctx c = {.view = H.view, .proj = H.proj, .res = (int)st->trace_res};
    float diam = v3_len(v3_sub(T.s.bmax, T.s.bmin));
    /* as ispm_splat.c's ispm_trace sets them */
    c.near = H.proj.m[14] / (H.proj.m[10] - 1.0f), c.tmax = diam;
    c.eps_abs = d.eps_abs_rel * diam, c.eps_slope = d.eps_slope, c.hit_px = d.hit_px;
    c.edge_on_cos = d.edge_on_cos, c.edge_reach = d.edge_reach;
    float px_angle = 2.0f * fmaxf(1.0f / H.proj.m[5], 1.0f / H.proj.m[0]) / (float)c.res;
    float slope = sqrtf(1.0f - d.edge_on_cos * d.edge_on_cos) / fmaxf(d.edge_on_cos, 1e-3f);
    c.skip_rel = slope * px_angle * (d.hit_px + 0.5f) * 1.4143f;
    gk_ispm_pixel *px = malloc(sizeof *px * (size_t)(c.res * c.res));
    assert_int_equal(gk_ispm_read_pixels(H.self, px, c.res * c.res), c.res * c.res);
    for (int i = 0; i < c.res * c.res; i++)
        assert_int_equal(px[i].count, 1); /* the floor and nothing else */
    c.px = px;
    gk_ispm_photon *p = malloc(sizeof *p * (size_t)st->capacity);
    int n = gk_ispm_read_photons(H.self, p, st->capacity);
    long loads = 0;
    for (int i = 0; i < n; i++)
        if (p[i].org[3] != 0.0f)
            loads += march_loads(&c, v3(p[i].org[0], p[i].org[1], p[i].org[2]),
                                 v3_norm(v3(p[i].dir[0], p[i].dir[1], p[i].dir[2])));
    free(p);
    free(px);
    return loads;
}

/* ---- the splats (splat.vert's quads), replayed ---- */

static double edge(const double a[2], const double b[2], double x, double y)
{
    return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
}

/* pixel centres of the w×h target inside the convex quadrilateral q (in order round it) */
static long quad_covered(const double q[4][2], int w, int h)
{
    double x0 = q[0][0], x1 = q[0][0], y0 = q[0][1], y1 = q[0][1], area = 0.0;
    for (int i = 0; i < 4; i++) {
        x0 = fmin(x0, q[i][0]), x1 = fmax(x1, q[i][0]), y0 = fmin(y0, q[i][1]), y1 = fmax(y1, q[i][1]);
        area += q[i][0] * q[(i + 1) % 4][1] - q[(i + 1) % 4][0] * q[i][1];
    }
    long n = 0;
    for (int y = (int)fmax(floor(y0), 0.0); y < (int)fmin(ceil(y1), (double)h); y++)
        for (int x = (int)fmax(floor(x0), 0.0); x < (int)fmin(ceil(x1), (double)w); x++) {
            bool in = area != 0.0;
            for (int i = 0; i < 4 && in; i++) {
                /* the edges counter-clockwise, a -> b; a centre on an edge is the polygon's when the
                   edge is a top or left one (window y up: it runs leftwards, or downwards) */
                const double *a = area > 0.0 ? q[i] : q[(i + 1) % 4], *b = area > 0.0 ? q[(i + 1) % 4] : q[i];
                double e = edge(a, b, x + 0.5, y + 0.5), dx = b[0] - a[0], dy = b[1] - a[1];
                in = e > 0.0 || (e == 0.0 && (dy < 0.0 || (dy == 0.0 && dx > 0.0)));
            }
            n += in;
        }
    return n;
}

static long replay_splats(void)
{
    const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
    gk_ispm_debug d;
    gk_ispm_default_debug(&d);
    int sw = st->splat_w, sh = st->splat_h;
    float pixel_angle = 2.0f / H.proj.m[5] / (float)sh; /* as ispm_splat sets u_pixel_angle */
    gk_ispm_hit *hit = malloc(sizeof *hit * (size_t)st->capacity);
    int n = gk_ispm_read_hits(H.self, hit, st->capacity);
    long total = 0;
    for (int i = 0; i < n; i++) {
        if (hit[i].pos_valid[3] == 0.0f)
            continue;
        vec3 c = v3(hit[i].pos_valid[0], hit[i].pos_valid[1], hit[i].pos_valid[2]);
        vec3 nrm = v3(hit[i].nrm_h[0], hit[i].nrm_h[1], hit[i].nrm_h[2]);
        float least = d.h_pixels * pixel_angle * v3_len(v3_sub(c, H.eye));
        vec3 t = v3_norm(fabsf(nrm.y) < 0.999f ? v3_cross(v3(0, 1, 0), nrm) : v3_cross(v3(1, 0, 0), nrm));
        vec3 bt = v3_cross(nrm, t);
        float a = fmaxf(hit[i].nrm_h[3], least);
        static const float corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}; /* round the quad */
        double q[4][2];
        for (int k = 0; k < 4; k++) {
            vec3 w = v3_add(c, v3_add(v3_scale(t, corner[k][0] * a), v3_scale(bt, corner[k][1] * a)));
            vec4 p = m4_vec4(H.vp, (vec4){w.x, w.y, w.z, 1.0f});
            q[k][0] = ((double)(p.x / p.w) + 1.0) * 0.5 * sw, q[k][1] = ((double)(p.y / p.w) + 1.0) * 0.5 * sh;
            /* the rasterizer's 8 sub-pixel bits: the splats' edges are axis-aligned on this view, so
               a whole edge's pixel centres move in or out with its snapping */
            q[k][0] = round(q[k][0] * SUBPIXELS) / SUBPIXELS, q[k][1] = round(q[k][1] * SUBPIXELS) / SUBPIXELS;
        }
        total += quad_covered(q, sw, sh);
    }
    free(hit);
    return total;
}

static void lists_trace_and_splat_match_replays(void **state)
{
    (void)state;
    static const char *const budgets[] = {"ispm_photons=4096,ispm_trace=64,ispm_splat=0.5",
                                          "ispm_photons=4096,ispm_trace=128,ispm_splat=1"};
    for (int b = 0; b < 2; b++) {
        counting_frame(budgets[b]);
        const gk_ispm_stats *st = gk_ispm_get_stats(H.self);
        const ispm_state *s = H.self;
        long res2 = (long)st->trace_res * st->trace_res;
        double lists = work_of("gi.ispm_lists", "ssbo_r32ui_atomic");
        double trace = work_of("gi.ispm_trace", "ssbo_rgba32f_load");
        double splat = work_of("gi.ispm_splat", "raster_r16f_depth_fill");
        double upsample = work_of("gi.ispm_upsample", "tex2d_rgba32f_nearest");
        long trace_replay = replay_trace(), splat_replay = replay_splats();
        double trace_off = (trace - (double)trace_replay) / (double)trace_replay;
        double splat_off = (splat - (double)splat_replay) / (double)splat_replay;
        print_message("# %s: %u photons, %u hits; lists %.0f atomics (%ld pixels); trace counted %.0f loads, replayed "
                      "%ld (%+.4f%%); splat counted %.0f fragments, replayed %ld (%+.4f%%)\n", budgets[b], st->photons,
                      st->hits, lists, res2, trace, trace_replay, 100.0 * trace_off, splat, splat_replay, 100.0 * splat_off);
        assert_true(st->hits > 1000 && st->hits == st->photons); /* every photon lands on the floor */
        /* the lists: one fragment per pixel (the floor), 5 atomics each, none dropped */
        assert_int_equal(st->fragments, res2);
        assert_true(lists == 5.0 * (double)res2);
        assert_true(trace_replay > 0 && fabs(trace_off) <= TRACE_TOLERANCE);
        assert_true(splat_replay > 0 && fabs(splat_off) <= SPLAT_TOLERANCE);
        assert_true(splat == s->splat_fragments.value[0]);
        print_message("# upsample: %.0f splat texels for %d pixels at splat %dx%d\n", upsample, W * HH, st->splat_w,
                      st->splat_h);
        int side = st->splat_w == W ? 1 : 2; /* taps a side away from the edge */
        assert_true(upsample == (side * W + 2.0) * (side * HH + 2.0));
    }
}

/* A full pool: a dropped fragment costs ll_build.frag two atomics (the counter and the overflow's),
   a kept one five. */
static void list_atomics_by_hand(void **state)
{
    (void)state;
    assert_true(ispm_list_atomics(10, 0) == 50.0);
    assert_true(ispm_list_atomics(10, 3) == 5.0 * 7 + 2.0 * 3);
    assert_true(ispm_list_atomics(0, 0) == 0.0);
}

/* The RSM's fragments (gi.ispm_photons) against a replay of its rasterization: the light sits below
   the mirror's level and the RSM is framed on the mirror's bounding sphere, so its frustum holds the
   mirror and nothing else (the floor lies below its lower edge); the mirror's corners projected by
   the RSM's view (ispm_state's, as rsm.vert projects them) and snapped to the rasterizer's sub-pixel
   bits, their quad's texel centres counted. */
static void rsm_fragments_match_a_replay(void **state)
{
    (void)state;
    counting_frame("ispm_trace=64");
    const ispm_state *s = H.self;
    static const float corner[4][2] = {{-0.2f, -0.2f}, {0.2f, -0.2f}, {0.2f, 0.2f}, {-0.2f, 0.2f}};
    double q[4][2];
    for (int k = 0; k < 4; k++) {
        vec4 p = m4_vec4(s->light.vp, (vec4){corner[k][0], 1.0f, corner[k][1], 1.0f});
        for (int a = 0; a < 2; a++) {
            q[k][a] = ((double)((a ? p.y : p.x) / p.w) + 1.0) * 0.5 * ISPM_RSM_RES;
            q[k][a] = round(q[k][a] * SUBPIXELS) / SUBPIXELS;
        }
    }
    long replay = quad_covered(q, ISPM_RSM_RES, ISPM_RSM_RES);
    double counted = work_of("gi.ispm_photons", "raster_r16f_depth_fill");
    printf("# RSM %d^2: %.0f fragments counted, %ld replayed (the mirror)\n", ISPM_RSM_RES, counted, replay);
    assert_true(replay > 0 && replay < ISPM_RSM_RES * ISPM_RSM_RES);
    assert_true(counted == (double)replay);
}

/* The mask pyramid's and the emission's work (gi.ispm_photons beside the RSM's fragments, modelled
   from the photon header: ispm_photons_model) against mask.comp's and emit.comp's counting variant,
   kind by kind, exact; and its parts by hand on the mirror: the mirror is the only surface in the
   RSM, all specular, so the mask's level-0 count M (ph_top) is the RSM's fragments, level 0's
   the pyramid's loads 4 (128² + ... + 1²) = 87 380; and each photon's emission reads 4^l mask
   texels. With a budget above M (65 536) every specular texel is a photon at level 0; below it
   (1024) the level rises. */
static void photon_emission_matches_the_shaders_count(void **state)
{
    (void)state;
    static const char *const budgets[2] = {"ispm_trace=64,ispm_photons=65536", "ispm_trace=64,ispm_photons=1024"};
    for (int b = 0; b < 2; b++) {
        counting_frame(budgets[b]);
        const ispm_state *s = H.self;
        static const char *const kinds[4] = {"tex2d_r32f_nearest", "tex2d_depth32f_nearest", "ssbo_rgba32f_load",
                                             "ssbo_r32ui_atomic"};
        double model[4];
        for (int k = 0; k < 4; k++)
            model[k] = work_of("gi.ispm_photons", kinds[k]);
        const gk_counters *c = &s->photons_fetches;
        assert_true(c->counted);
        double rsm = work_of("gi.ispm_photons", "raster_r16f_depth_fill");
        print_message("# %s: level %u, %u photons (capacity %d), %u reflected, M %u, RSM fragments %.0f: modelled %.0f "
                      "texels, %.0f depths, %.0f loads, %.0f atomics; counted %.0f, %.0f, %.0f, %.0f\n", budgets[b],
                      s->st.level, s->st.photons, s->capacity, s->st.reflected, s->st.specular_texels, rsm, model[0],
                      model[1], model[2], model[3], c->value[0], c->value[1], c->value[2], c->value[3]);
        for (int k = 0; k < 4; k++)
            assert_true(model[k] > 0.0 && model[k] == c->value[k]);
        /* by hand: the mirror's texels are the mask's, and each block read 4^l of them */
        double m = s->st.specular_texels, side = ISPM_RSM_RES >> s->st.level;
        assert_true(m > 0.0 && m == rsm);
        double kept = s->st.photons < (unsigned)s->capacity ? s->st.photons : (double)s->capacity;
        assert_true(model[0] == (double)ISPM_RSM_RES * ISPM_RSM_RES + s->st.photons * (double)(1u << (2 * s->st.level)) + 3.0 * kept);
        assert_true(model[1] == kept && model[2] == 87380.0 + side * side);
        if (b == 0)
            assert_true(s->st.level == 0 && s->st.photons == m); /* every specular texel a photon */
        else
            assert_true(s->st.level > 0 && s->st.photons < m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(list_atomics_by_hand),
        cmocka_unit_test(rsm_fragments_match_a_replay),
        cmocka_unit_test(photon_emission_matches_the_shaders_count),
        cmocka_unit_test(lists_trace_and_splat_match_replays),
    };
    return cmocka_run_group_tests_name("ispm_work", tests, setup, teardown);
}
