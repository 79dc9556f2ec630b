/* The `vpl` method behind gi.h: knobs, per-frame orchestration, statistics. The passes live in
 * vpl_rsm.c, vpl_valmap.c and vpl_gather.c, the clustering in vpl_cluster.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vpl_internal.h"

/* Cost priors (relative frame cost of the method, cheapest = 1), from the thesis's Table 6.2
 * shares (gather 69%, blur 21%, CSSM 8% at M = 30, the rest 2%; dong-001.md §8.2):
 *  vpl_n: gather ∝ VPLs/pixel: 0.31 + 0.69·(N/256)            -> 1, 1.69, 3.07
 *  vpl_m: CSSM share ∝ M: 0.92 + 0.08·M/30, normalised at M=2 -> 1 ... 1.09; adaptive ~ M=16
 *  vpl_val_map: the CSSM share ∝ texels (64² -> 256² is 16×)  -> 1, 1.02, 1.11 (at M = 8)
 *  vpl_block: VPLs/pixel = N/B²: 0.31 + 0.69·(4/B)²           -> 1, 3.07, 11.35
 *  vpl_res: gather + blur ∝ pixels (90%): 0.1 + 0.9·(s/0.25)² -> 1, 3.7, 14.5
 *  vpl_blur: blur share 21% ∝ (2r+1): 0.79 + 0.21·(2r+1)/5    -> 1, 1.17, 1.50
 *  vpl_vis: VSM 2 fetches, CSSM 6 (+ basis), exact N hard maps -> 1, 1.3, 20
 *  vpl_clamp: one max() per VPL                               -> 1, 1
 *  vpl_gather: multires shades every valid region with all N VPLs instead of N/B² per pixel;
 *              T5 at 64² measured ~1/16 as many regions as pixels, i.e. par with block 4     -> 1, 1.4
 * Each prior is the method's whole cost with the other knobs held, so every trade knob scales the
 * `gi` pass (scales_pass): the scheduler predicts a step from that pass's measured time. */
enum { K_N, K_M, K_VAL_MAP, K_BLOCK, K_RES, K_BLUR, K_VIS, K_CLAMP, K_GATHER, K_UMBRA, K_COUNT };
/* Levels of the variant knobs, in the order of their values below. */
_Static_assert(K_COUNT == VPL_KNOBS, "vpl_internal.h's VPL_KNOBS counts the knobs");
enum { VIS_VSM, VIS_CSSM, VIS_EXACT };
enum { GATHER_INTERLEAVED, GATHER_MULTIRES };
static const gk_knob_def knobs[K_COUNT] = {
    {"vpl_n", "vpl", 3, {"256", "512", "1024"}, {1.0f, 1.69f, 3.07f}, 0, 0, false, .scales_pass = "gi"},
    {"vpl_m", "vpl", 6, {"2", "4", "8", "16", "32", "adaptive"}, {1.0f, 1.006f, 1.018f, 1.041f, 1.086f, 1.05f}, 2, 0, false, .scales_pass = "gi"},
    {"vpl_val_map", "vpl", 3, {"64", "128", "256"}, {1.0f, 1.02f, 1.11f}, 0, 0, false, .scales_pass = "gi"},
    {"vpl_block", "vpl", 3, {"4", "2", "1"}, {1.0f, 3.07f, 11.35f}, 0, 0, false, .scales_pass = "gi"},
    {"vpl_res", "vpl", 3, {"0.25", "0.5", "1"}, {1.0f, 3.7f, 14.5f}, 1, 0, false, .scales_pass = "gi"},
    {"vpl_blur", "vpl", 3, {"2", "4", "8"}, {1.0f, 1.17f, 1.5f}, 1, 0, false, .scales_pass = "gi"},
    /* exact (one hard map per VPL) is the reference for clustering error, never a scheduler pick. */
    {"vpl_vis", "vpl", 3, {"vsm", "cssm", "exact"}, {1.0f, 1.3f, 20.0f}, 1, .auto_max_level = 1, .scales_pass = "gi"},
    {"vpl_clamp", "vpl", 2, {"off", "on"}, {1.0f, 1.0f}, 1, 0, .fixed = true},
    {"vpl_gather", "vpl", 2, {"interleaved", "multires"}, {1.0f, 1.4f}, 0, 0, false, .scales_pass = "gi"},
    /* The deep-umbra test (gather.frag; not in the thesis): exact depths decide where the whole VAL
       is hidden, which the filtered visibility cannot near a thin wall (tests/e2e/vpl_leak.sh);
       `on` tells the receiver's own surface from a blocker by a depth margin scaled by its slope,
       `plane` by the plane of the surface the map holds; `horizon` (the default) is `plane` where
       the paraboloid's rim texels are no way around a blocker and receivers in the band between
       the VAL's surface and its map's lifted plane are looked up at the map's horizon instead of
       taken as lit (gather.frag). */
    {"vpl_umbra", "vpl", 4, {"off", "on", "plane", "horizon"}, {1.0f, 1.0f, 1.0f, 1.0f}, 3, 0, .fixed = true},
};

static void declare_knobs(gk_budget *b)
{
    gk_budget_add_all(b, knobs, (int)(sizeof knobs / sizeof knobs[0]));
}

static bool applies(const gk_scene *s)
{
    /* One bounce between diffuse surfaces from a light: every light type has an RSM (directional
       lights an orthographic one, vpl_rsm.c). */
    bool light = s->n_lights > 0;
    bool diffuse = false;
    for (int i = 0; i < s->n_materials; i++) {
        const gk_material *m = &s->materials[i];
        diffuse |= !m->light_proxy && m->metallic < 0.99f && (m->base_color[0] + m->base_color[1] + m->base_color[2]) > 0.0f;
    }
    return light && diffuse;
}

void gk_vpl_default_debug(gk_vpl_debug *d)
{
    memset(d, 0, sizeof *d);
    d->w_pos = 0.7f, d->w_nrm = 0.3f;
    /* d_min = the mean VPL spacing (dong-001.md §4.5); F13 measured the energy it removes. */
    d->clamp_scale = 1.0f;
    d->fade_frames = 4;
    d->vis_override = -1;
    /* Doubling M must cut the mean k-means distance by ≥ 35%: splitting a plane further only gains
       1 − 1/√2 ≈ 29% (measured 29–31%), separating walls gains 66% (test_vpl_cluster: the corner
       settles at M = 4, a flat patch at M = 2). */
    d->adaptive_drop = 0.35f;
}

/* The GLES 3.1 floor has no float colour buffers; RGBA16F ones come with EXT_color_buffer_half_float
 * (or 3.2 core), RGBA32F ones with EXT_color_buffer_float. GK_VPL_TARGETS (vpl.h) forces a path. */
static int choose_targets(vpl_state *s, gk_err *e)
{
    gk_gl_caps caps;
    gk_gl_caps_query(&caps, s->ctx.gles_version ? s->ctx.gles_version : 31);
    const char *force = getenv("GK_VPL_TARGETS");
    if (force && *force && strcmp(force, "half") && strcmp(force, "float") && strcmp(force, "auto"))
        return gk_fail(e, GK_EINPUT, "vpl: GK_VPL_TARGETS='%s' is not one of half, float, auto", force);
    bool want_half = force && strcmp(force, "half") == 0, want_float = force && strcmp(force, "float") == 0;
    if (caps.color_buffer_float && !want_half) {
        s->tgt_fmt = GL_RGBA32F, s->tgt_half = false;
        return 0;
    }
    if (want_float)
        return gk_fail(e, GK_ERUNTIME, "vpl: GK_VPL_TARGETS=float but EXT_color_buffer_float is missing");
    if (caps.color_buffer_half) {
        s->tgt_fmt = GL_RGBA16F, s->tgt_half = true;
        return 0;
    }
    return gk_fail(e, GK_ERUNTIME, "vpl: needs RGBA16F or RGBA32F render targets (GLES 3.2, "
                                   "EXT_color_buffer_half_float or EXT_color_buffer_float); none is available");
}

static void *create(const gk_gi_context *ctx, gk_err *e)
{
    vpl_state *s = calloc(1, sizeof *s);
    if (!s) {
        gk_fail(e, GK_ERUNTIME, "vpl: out of memory");
        return NULL;
    }
    s->ctx = *ctx;
    gk_knob_handles(s->knob, knobs, K_COUNT);
    s->own_cache = gk_gi_context_own_programs(&s->ctx);
    if (choose_targets(s, e)) {
        if (s->own_cache)
            gk_program_cache_destroy(s->own_cache);
        free(s);
        return NULL;
    }
    gk_vpl_default_debug(&s->dbg);
    glGenVertexArrays(1, &s->empty_vao);
    return s;
}

static int set_scene(void *self, const gk_scene *sc, gk_err *e)
{
    vpl_state *s = self;
    vec3 ext = v3_sub(sc->bmax, sc->bmin);
    s->diam = v3_len(ext) > 0.0f ? v3_len(ext) : 1.0f;
    vec3 c = v3_scale(v3_add(sc->bmin, sc->bmax), 0.5f);
    s->origin[0] = c.x, s->origin[1] = c.y, s->origin[2] = c.z;
    if (s->have_proxy)
        vpl_proxy_free(&s->proxy);
    s->have_proxy = false;
    /* Edges ≤ 1/24 of the diameter: an edge of length L seen at distance r ≥ diam/10 spans
       θ ≤ 0.42 rad, and a straight chord instead of the paraboloid's curve is off by ~θ²/16 ≈ 0.011
       in uv, under one texel at 64² (estimate, not measured). 300k triangles cap it at ~10 MB. */
    if (vpl_proxy_build(&s->proxy, sc, s->diam / 24.0f, 300000, e))
        return -1;
    s->have_proxy = true;
    s->prev_m = 0;
    s->have_hist = false;
    return 0;
}

static int knob_int(vpl_state *s, const gk_budget *b, int k, int fallback)
{
    return (int)gk_knob_number(b, &s->knob[k], (float)fallback);
}

static void read_budget(vpl_state *s, const gk_budget *b)
{
    s->n = knob_int(s, b, K_N, 256);
    s->n = s->n < 16 ? 16 : (s->n > GK_VPL_MAX_N ? GK_VPL_MAX_N : s->n);
    s->m_knob = gk_knob_level(b, &s->knob[K_M], -1) == knobs[K_M].n_values - 1 ? 0 /* adaptive */
                                                                                : knob_int(s, b, K_M, 8);
    s->val_res = knob_int(s, b, K_VAL_MAP, 64);
    s->block = knob_int(s, b, K_BLOCK, 4);
    s->block = s->block < 1 ? 1 : s->block;
    s->blur_radius = knob_int(s, b, K_BLUR, 4);
    s->res_scale = gk_knob_number(b, &s->knob[K_RES], 0.5f);
    int vis = gk_knob_level(b, &s->knob[K_VIS], VIS_CSSM);
    s->vis = vis == VIS_VSM ? GK_VPL_VIS_VSM : vis == VIS_EXACT ? GK_VPL_VIS_EXACT : GK_VPL_VIS_CSSM;
    if (s->dbg.vis_override >= 0)
        s->vis = s->dbg.vis_override;
    s->clamp = gk_knob_level(b, &s->knob[K_CLAMP], 1) == 1;
    s->umbra = gk_knob_level(b, &s->knob[K_UMBRA], VPL_UMBRA_HORIZON);
    s->multires = gk_knob_level(b, &s->knob[K_GATHER], GATHER_INTERLEAVED) == GATHER_MULTIRES;
}

static void cluster(vpl_state *s)
{
    gk_kmeans_opts o = {s->dbg.w_pos, s->dbg.w_nrm, s->diam, 16, s->dbg.warm_start && s->prev_m > 0};
    gk_vpl_stats *st = &s->st;
    gk_kmeans_result r;
    if (o.warm_start) {
        memcpy(st->vals, s->prev_vals, sizeof st->vals);
        r = gk_vpl_kmeans(st->vpl, s->n, s->prev_m, &o, st->labels, st->vals);
    } else if (s->m_knob <= 0) {
        r = gk_vpl_kmeans_adaptive(st->vpl, s->n, 2, GK_VPL_MAX_M, s->dbg.adaptive_drop, s->prev_m, &o, st->labels,
                                   st->vals);
    } else {
        r = gk_vpl_kmeans(st->vpl, s->n, s->m_knob, &o, st->labels, st->vals);
    }
    if (s->prev_m > 0 && r.m != s->prev_m && !o.warm_start)
        st->fade_left = s->dbg.fade_frames;
    st->m = r.m, st->empty = r.empty, st->iters = r.iters, st->cluster_error = r.error;
    memcpy(s->prev_vals, st->vals, sizeof s->prev_vals);
    if (!o.warm_start || s->prev_m == 0)
        s->prev_m = r.m;
}

static int render(void *self, const gk_gi_frame *f, gk_err *e)
{
    vpl_state *s = self;
    if (!s->have_proxy && set_scene(s, f->scene, e))
        return -1;
    read_budget(s, f->budget);
    /* The document's passes, each a pass of the renderer's clock (nested under `gi`). */
    gk_pass_begin(f->pass, "vpl_rsm");
    int rc = vpl_generate(s, f, e) < 0 ? -1 : 0;
    gk_pass_end(f->pass);
    if (rc)
        return -1;

    gk_vpl_stats *st = &s->st;
    const gk_val *emitters = st->vals;
    int n_emitters = st->m;
    gk_val *ev = NULL;
    gk_pass_begin(f->pass, "vpl_cluster");
    if (s->vis == GK_VPL_VIS_EXACT) {
        /* Instant radiosity reference: every VPL is its own emitter with a hard map. */
        ev = calloc((size_t)s->n, sizeof *ev);
        if (!ev) {
            gk_pass_end(f->pass);
            return gk_fail(e, GK_ERUNTIME, "vpl: out of memory");
        }
        for (int i = 0; i < s->n; i++) {
            bool ok = st->vpl[i].flux.x + st->vpl[i].flux.y + st->vpl[i].flux.z > 0.0f;
            st->labels[i] = ok ? i : -1;
            ev[i].centre = st->vpl[i].pos, ev[i].normal = st->vpl[i].nrm;
            gk_val_frame_area(st->vpl, s->n, st->labels, i, &ev[i]);
        }
        st->m = s->n, st->empty = 0, st->iters = 0, st->cluster_error = 0.0;
        emitters = ev;
    } else {
        cluster(s);
    }
    n_emitters = st->m;
    st->spacing = gk_vpl_mean_spacing(st->vpl, s->n);
    st->dmin = s->dbg.clamp_scale * st->spacing;
    gk_pass_end(f->pass);

    gk_pass_begin(f->pass, "vpl_valsm");
    rc = vpl_build_maps(s, f, emitters, n_emitters, e);
    if (!rc)
        vpl_upload(s, emitters, n_emitters);
    gk_pass_end(f->pass);
    free(ev);
    if (rc)
        return -1;
    float fade = 1.0f;
    if (st->fade_left > 0 && s->dbg.fade_frames > 0) {
        fade = (float)(s->dbg.fade_frames - st->fade_left + 1) / (float)(s->dbg.fade_frames + 1);
        st->fade_left--;
    }
    if (vpl_gather(s, f, fade, e)) /* its passes vpl_gather, vpl_blur, vpl_compose */
        return -1;
    s->frame_index++;
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "vpl: GL error 0x%04x during the frame", err);
    return 0;
}

static long memory_bytes(const void *self)
{
    const vpl_state *s = self;
    long b = 0;
    long px = s->tgt_half ? 8 : 16; /* bytes per RGBA target texel */
    b += (long)s->rsm_w * s->rsm_h * (px * 3 + 4);
    b += (long)s->gen_n * px * 3 + (long)s->n * 16 * 3 + (long)s->val_tex_w * 64;
    long texels = (long)s->map_res * s->map_res * s->map_layers;
    long per = s->map_vis == GK_VPL_VIS_CSSM ? 2 + 4 + 4 + 8 + 8 : (s->map_vis == GK_VPL_VIS_VSM ? 2 + 8 : 2);
    b += texels * per * (s->map_vis == GK_VPL_VIS_EXACT ? 3 : 4) / 3; /* mips add ⅓ */
    if (s->map_umbra)
        b += texels * 4 * 4 / 3; /* the chain of maxima, RG16F with mips */
    if (s->map_umbra >= VPL_UMBRA_PLANE)
        b += texels * px; /* the planes, one level in the target format */
    b += (long)s->map_res * s->map_res * 4;
    b += (long)s->iw * s->ih * (px * 6);
    b += s->proxy.bytes;
    return b;
}

static void destroy(void *self)
{
    vpl_state *s = self;
    if (!s)
        return;
    vpl_free_gpu(s);
    vpl_work_free(s);
    if (s->own_cache)
        gk_program_cache_destroy(s->own_cache);
    free(s);
}

bool gk_vpl_half_targets(const void *self) { return ((const vpl_state *)self)->tgt_half; }
float vpl_target_max(const vpl_state *s) { return s->tgt_half ? 65000.0f : 3.0e38f; }
void gk_vpl_set_debug(void *self, const gk_vpl_debug *d) { ((vpl_state *)self)->dbg = *d; }
const gk_vpl_stats *gk_vpl_get_stats(const void *self) { return &((const vpl_state *)self)->st; }

const gk_gi_method gk_gi_vpl = {
    .name = "vpl",
    .applies = applies,
    .declare_knobs = declare_knobs,
    .create = create,
    .set_scene = set_scene,
    .render = render,
    .memory_bytes = memory_bytes,
    .pass_work = vpl_pass_work,
    .destroy = destroy,
};
