/* The `ispm` method behind gi.h: knobs, the tier probe, per-frame orchestration, statistics.
 * ispm = direct (the renderer's) + vpl's diffuse indirect (the vpl method run through its gi.h
 * interface, so the seed's multi-resolution splatting is not copied) + caustics (the passes of
 * ispm_photons.c, ispm_lists.c and ispm_splat.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "ispm_internal.h"

/* Cost priors (relative cost of the caustic part, cheapest = 1), from the seed's Table 4.1 (simple
 * ring, GTX 460): trace 7 ms of an 11 ms frame at 17,021 photons and 128², ×2 at 256² (14 ms), the
 * rest (RSM, lists, splat, upsample) ≈ 4 ms; research L19: trace time ∝ photons × trace resolution.
 *   ispm_photons: 4 + 7·N/17021 ms, normalised at N = 1024          -> 1, 1.29, 2.42, 6.99
 *   ispm_trace:   7·R/128 + 4 (the lists' share is in the 4)        -> 7.5, 11, 18 ms -> 1, 1.47, 2.4
 *   ispm_splat:   splat 0.3–1 ms of 11 ∝ pixels (scale²)            -> 1, 1.05, 1.2
 *   ispm_pool:    memory only (clearing is per pixel, not per node) -> 1, 1, 1
 *   ispm_tier:    a switch, never moved by the scheduler            -> 1, 1
 *   ispm_bounces: a switch (1 = the seed's single specular bounce; 2, 3 = specular chains, research
 *                 L7), never moved by the scheduler; a further bounce marches again the photons that
 *                 met a mirror (on caustic-ring about a quarter of them)   -> 1, 1.25, 1.3
 *   ispm_radius:  a switch (seed = the seed's splat radius, density = from the hits' density,
 *                 ispm_density.c, footprint = ellipses from the photons' neighbours after the
 *                 density's passes, ispm_footprint.c), never moved by the scheduler; two passes
 *                 over the hits, three more and 16 kernel samples per splat fragment
 *                 (llvmpipe, 160x120: gi 1.3x the density's)        -> 1, 1.05, 1.1 */
enum { K_PHOTONS, K_TRACE, K_SPLAT, K_POOL, K_TIER, K_BOUNCES, K_RADIUS, K_COUNT };
_Static_assert(K_COUNT == ISPM_KNOBS, "ispm_internal.h's ISPM_KNOBS counts the knobs");
static const gk_knob_def knobs[K_COUNT] = {
    {"ispm_photons", "ispm", 4, {"1024", "4096", "16384", "65536"}, {1.0f, 1.29f, 2.42f, 6.99f}, 1, 0, false, NULL},
    {"ispm_trace", "ispm", 3, {"64", "128", "256"}, {1.0f, 1.47f, 2.4f}, 1, 0, false, NULL},
    {"ispm_splat", "ispm", 3, {"0.25", "0.5", "1"}, {1.0f, 1.05f, 1.2f}, 1, 0, false, NULL},
    /* list-pool megabytes; 20 is the seed's */
    {"ispm_pool", "ispm", 3, {"2", "8", "20"}, {1.0f, 1.0f, 1.0f}, 2, 0, false, NULL},
    {"ispm_tier", "ispm", 2, {"peel", "lists"}, {1.0f, 1.0f}, 1, 0, .fixed = true},
    {"ispm_bounces", "ispm", 3, {"1", "2", "3"}, {1.0f, 1.25f, 1.3f}, 0, 0, .fixed = true},
    {"ispm_radius", "ispm", 3, {"seed", "density", "footprint"}, {1.0f, 1.05f, 1.1f}, 0, 0, .fixed = true},
};

static void declare_knobs(gk_budget *b)
{
    gk_budget_add_all(b, knobs, K_COUNT);
}

/* Caustics need a specular surface lit by a point or spot light (gi_catalogue.c's
 * GK_GI_NEEDS_CAUSTICS; glass is not a reflector of the seed's). */
static bool applies(const gk_scene *s)
{
    /* as the scene derived it at load (features.c): a drawn mirror, and caustics lit by a lamp */
    return s->features.has_specular && s->features.has_caustics;
}

void gk_ispm_default_debug(gk_ispm_debug *d)
{
    memset(d, 0, sizeof *d);
    d->delta = 0.25f;        /* research Appendix E's middle value: the Gaussian keeps 43% unnormalised */
    d->c0 = 1.5f;            /* see trace.comp: disks 1.5× a photon's plane-mirror footprint overlap
                                their neighbours (C0 is not given in the seed) */
    d->cos_min = 0.2f;       /* L14: radius grows at most √5× at grazing incidence */
    d->h_min_rel = 0.002f;   /* L14: 1.5 cm on caustic-ring's 7.5 m diameter */
    d->h_max_rel = 0.03f;    /* L14: 22 cm */
    d->h_pixels = 1.5f;      /* L15: a disk of 1.5 splat pixels deposits Φ within 2% (measured) */
    d->pixel_samples = 4;    /* caustic-ring, ispm_bounces=3, richest budget: 1/2/3/4/6/8 gave mask IoU
                                0.518/0.672/0.696/0.709/0.715/0.719, rel. RMSE inside 0.195/0.165/0.160/
                                0.158/0.157/0.156: 16 kernel samples per splat pixel */
    d->eps_abs_rel = 0.0005f;
    d->eps_slope = 1.0f;     /* research A.1.11: k = 1 found all 400 hits on the right surface */
    d->hit_px = 1.0f;        /* the pixel and half a pixel round it: a ray stepped one pixel along its
                                major axis passes diagonal neighbours it does not sample */
    d->edge_on_cos = 0.1f;   /* within 5.7° of edge-on (caustic-ring: the ring facet that took
                                photons 16 cm from it is seen at cos 0.01) */
    d->edge_reach = 3.0f;
    d->upsample_k = 16.0f;
    d->density_k = 32.0f;     /* caustic-ring, ispm_bounces=3, richest budget: k = 16/32/64 gave whole-image
                                rel. RMSE 0.454/0.436/0.443, mask IoU 0.605/0.586/0.450 (seed radius:
                                0.459, 0.517) */
    d->density_cell = 2.0f;  /* 2 and 4 pixels: the same within 0.003 */   /* research A.2: k = 8–32 */
}

static int knob_int(ispm_state *s, const gk_budget *b, int k, int fallback)
{
    return (int)gk_knob_number(b, &s->knob[k], (float)fallback);
}

static void *create(const gk_gi_context *ctx, gk_err *e)
{
    ispm_state *s = calloc(1, sizeof *s);
    if (!s) {
        gk_fail(e, GK_ERUNTIME, "ispm: out of memory");
        return NULL;
    }
    s->ctx = *ctx;
    gk_knob_handles(s->knob, knobs, K_COUNT);
    s->own_cache = gk_gi_context_own_programs(&s->ctx);
    gk_ispm_default_debug(&s->dbg);
    gk_gl_caps caps;
    gk_gl_caps_query(&caps, s->ctx.gles_version ? s->ctx.gles_version : 31);
    s->lists_ok = ispm_probe_lists(s->ctx.gles_version);
    s->st.lists_available = s->lists_ok;
    s->st.rsm_res = ISPM_RSM_RES;
    s->vpl = gk_gi_find("vpl");
    /* Splats add thousands of small irradiances per pixel: in RGBA16F the increments below half an
       ulp of the running sum vanish (test_ispm_mirror, L12 row: energy/Φ 0.9902 in RGBA16F against
       1.0011 in RGBA32F at 18,902 photons; GK_ISPM_SPLAT_HALF=1 forces RGBA16F), so RGBA32F where
       it can be blended. */
    s->splat_fmt = caps.color_buffer_float && gk_gl_has_extension("GL_EXT_float_blend") ? GL_RGBA32F : GL_RGBA16F;
    if (getenv("GK_ISPM_SPLAT_HALF"))
        s->splat_fmt = GL_RGBA16F;
    if (!caps.color_buffer_half) {
        gk_fail(e, GK_ERUNTIME, "ispm: needs RGBA16F render targets for the splats (GLES 3.2 or "
                                "EXT_color_buffer_half_float); none is available");
    } else if (!s->vpl) {
        gk_fail(e, GK_ERUNTIME, "ispm: the vpl method (its diffuse indirect light) is not registered");
    } else {
        s->vpl_self = s->vpl->create(ctx, e);
        if (s->vpl_self)
            return s;
    }
    if (s->own_cache)
        gk_program_cache_destroy(s->own_cache);
    free(s);
    return NULL;
}

static int set_scene(void *self, const gk_scene *sc, gk_err *e)
{
    ispm_state *s = self;
    vec3 ext = v3_sub(sc->bmax, sc->bmin);
    s->diam = v3_len(ext) > 0.0f ? v3_len(ext) : 1.0f;
    return s->vpl->set_scene(s->vpl_self, sc, e);
}

static void read_budget(ispm_state *s, const gk_budget *b)
{
    s->photons = knob_int(s, b, K_PHOTONS, 4096);
    s->photons = s->photons < 1 ? 1 : s->photons;
    s->trace_res = knob_int(s, b, K_TRACE, 128);
    s->splat_scale = gk_knob_number(b, &s->knob[K_SPLAT], 0.5f);
    s->pool_bytes = (long)(gk_knob_number(b, &s->knob[K_POOL], 20.0f) * 1048576.0f);
    s->bounces = knob_int(s, b, K_BOUNCES, 1);
    s->bounces = s->bounces < 1 ? 1 : s->bounces;
    s->radius = gk_knob_level(b, &s->knob[K_RADIUS], ISPM_RADIUS_SEED);
    int tier = gk_knob_level(b, &s->knob[K_TIER], GK_ISPM_TIER_LISTS);
    if (tier == GK_ISPM_TIER_LISTS && !s->lists_ok) {
        if (!s->logged_tier)
            gk_log("ispm: fewer than 4 fragment storage blocks: per-pixel lists unavailable, depth peeling (%d layers)",
                   ISPM_PEEL_LAYERS);
        s->logged_tier = true;
        tier = GK_ISPM_TIER_PEEL;
    }
    s->tier = tier;
    s->st.tier = tier, s->st.trace_res = s->trace_res, s->st.budget = s->photons;
}

/* The counters: every frame synchronously with debug.measure, else a copy made this frame is read
 * next frame (one frame late, so reading does not wait for the GPU). */
static void read_counters(ispm_state *s)
{
    const int ph_bytes = ISPM_PH_HEADER_BYTES, ll_bytes = 16;
    if (!s->readback[0]) {
        glGenBuffers(2, s->readback);
        for (int i = 0; i < 2; i++) {
            glBindBuffer(GL_COPY_WRITE_BUFFER, s->readback[i]);
            glBufferData(GL_COPY_WRITE_BUFFER, ph_bytes + ll_bytes, NULL, GL_STREAM_READ);
        }
    }
    int cur = (int)(s->frame_index & 1u);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_WRITE_BUFFER, s->readback[cur]);
    glBindBuffer(GL_COPY_READ_BUFFER, s->photon_ssbo);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, ph_bytes);
    glBindBuffer(GL_COPY_READ_BUFFER, s->ctr_ssbo);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, ph_bytes, ll_bytes);
    /* the bench's counting frame reads its own counts (ispm_work.c) */
    bool now = s->dbg.measure || s->counting;
    int rd = now ? cur : 1 - cur;
    if (!now && s->readback_frame == 0) {
        s->readback_frame = 1;
        return;   /* nothing copied a frame ago yet */
    }
    glBindBuffer(GL_COPY_READ_BUFFER, s->readback[rd]);
    const unsigned *p = glMapBufferRange(GL_COPY_READ_BUFFER, 0, ph_bytes + ll_bytes, GL_MAP_READ_BIT);
    if (p) {
        gk_ispm_stats *st = &s->st;
        st->photons = p[ISPM_PH_COUNT], st->level = p[ISPM_PH_LEVEL], st->photon_overflow = p[ISPM_PH_OVERFLOW];
        st->specular_texels = p[ISPM_PH_TOP], st->hits = p[ISPM_PH_HITS], st->reflected = p[ISPM_PH_REFLECTED];
        st->trace_work = p[ISPM_PH_STEPS];
        const unsigned *ll = p + ISPM_PH_HEADER_UINTS;
        st->fragments = s->tier == GK_ISPM_TIER_LISTS ? ll[ISPM_LL_COUNT] : 0;
        st->list_overflow = s->tier == GK_ISPM_TIER_LISTS ? ll[ISPM_LL_OVERFLOW] : 0;
        ispm_work_counters(s, st->trace_work, st->fragments, st->list_overflow);
        ispm_work_photons(s, p);
        glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    if ((s->st.list_overflow || s->st.photon_overflow) && !s->logged_overflow) {
        gk_log("ispm: overflow: %u list fragments dropped (pool %ld MB at ispm_trace=%d), %u photons dropped",
               s->st.list_overflow, s->pool_bytes >> 20, s->trace_res, s->st.photon_overflow);
        s->logged_overflow = true;
    }
}

static int caustics(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    bool any = false;
    gk_pass_begin(f->pass, "ispm_photons");
    int rc = ispm_emit_photons(s, f, &any, e);
    gk_pass_end(f->pass);
    if (rc || !any)
        return rc;
    gk_pass_begin(f->pass, "ispm_lists");
    rc = ispm_build_lists(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    gk_pass_begin(f->pass, "ispm_trace");
    rc = ispm_trace(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    s->st.capacity = s->capacity;
    gk_pass_begin(f->pass, "ispm_splat");
    rc = s->radius >= ISPM_RADIUS_DENSITY ? ispm_density_radius(s, f, e) : 0;
    rc = rc ? rc : s->radius == ISPM_RADIUS_FOOTPRINT ? ispm_footprint(s, f, e) : 0;
    rc = rc ? rc : ispm_splat(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    gk_pass_begin(f->pass, "ispm_upsample");
    rc = ispm_upsample(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    read_counters(s);
    return 0;
}

static int render(void *self, const gk_gi_frame *f, gk_err *e)
{
    ispm_state *s = self;
    if (s->diam <= 0.0f && set_scene(s, f->scene, e))
        return -1;
    read_budget(s, f->budget);
    ispm_work_frame(s, f);
    /* vpl's passes nest under `gi` next to ours, with their own names */
    if (!s->dbg.caustics_only && s->vpl->render(s->vpl_self, f, e))
        return -1;
    if (caustics(s, f, e))
        return -1;
    s->frame_index++;
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "ispm: GL error 0x%04x during the frame", err);
    return 0;
}

static long memory_bytes(const void *self)
{
    const ispm_state *s = self;
    long b = s->vpl->memory_bytes ? s->vpl->memory_bytes(s->vpl_self) : 0;
    b += (long)ISPM_RSM_RES * ISPM_RSM_RES * (4 + 4 + 4 + 4); /* three colour targets + depth */
    b += (long)ISPM_RSM_RES * ISPM_RSM_RES * 4 * 4 / 3;      /* count pyramid */
    b += ISPM_PH_HEADER_BYTES + (long)s->capacity * (ISPM_PHOTON_BYTES + ISPM_HIT_BYTES);
    b += s->nodes_cap * ISPM_NODE_BYTES + (long)s->ll_res * s->ll_res * 16;
    if (s->peel_fbo)   /* RGBA32UI layers (depth, normal, Node.spec) + a 32-bit depth buffer */
        b += (long)s->peel_res * s->peel_res * (16 * ISPM_PEEL_LAYERS + 4);
    b += s->grid_cap * 4;   /* ispm_radius=density's counts */
    if (s->block_ssbo)      /* ispm_radius=footprint's block map and ellipses */
        b += (long)ISPM_RSM_RES * ISPM_RSM_RES * 4 + (long)s->foot_cap * ISPM_FOOT_BYTES;
    b += (long)s->splat_w * s->splat_h * 8;
    return b;
}

/* gk_gi_method.pass_work (#21): the diffuse indirect part's passes, vpl's gather and VAL maps (their
   names are vpl's under `gi`), by vpl's own models (app/gi/vpl/vpl_work.c), then the caustic
   passes' (ispm_work.c). */
static int pass_work(void *self, gk_pass_work *out, int max)
{
    const ispm_state *s = self;
    int n = 0;
    if (!s->dbg.caustics_only && s->vpl_self && s->vpl->pass_work)
        n = s->vpl->pass_work(s->vpl_self, out, max);
    return n + ispm_caustic_work(s, out + n, max - n);
}

void ispm_free_gpu(ispm_state *s)
{
    GLuint fbos[4] = {s->rsm_fbo, s->ll_fbo, s->peel_fbo, s->splat_fbo};
    glDeleteFramebuffers(4, fbos);
    glDeleteTextures(3, s->rsm_tex);
    glDeleteTextures(1, &s->rsm_depth);
    glDeleteTextures(ISPM_PEEL_LAYERS, s->peel_tex);
    glDeleteTextures(1, &s->splat_tex);
    glDeleteRenderbuffers(1, &s->peel_depth);
    GLuint bufs[11] = {s->counts_ssbo, s->photon_ssbo, s->hit_buf, s->nodes_ssbo, s->pixels_ssbo, s->ctr_ssbo,
                       s->readback[0], s->readback[1], s->grid_ssbo, s->block_ssbo, s->foot_buf};
    glDeleteBuffers(11, bufs);
    GLuint vaos[2] = {s->splat_vao, s->empty_vao};
    glDeleteVertexArrays(2, vaos);
}

static void destroy(void *self)
{
    ispm_state *s = self;
    if (!s)
        return;
    ispm_free_gpu(s);
    ispm_work_free(s);
    if (s->vpl_self)
        s->vpl->destroy(s->vpl_self);
    if (s->own_cache)
        gk_program_cache_destroy(s->own_cache);
    free(s);
}

void gk_ispm_set_debug(void *self, const gk_ispm_debug *d) { ((ispm_state *)self)->dbg = *d; }
const gk_ispm_stats *gk_ispm_get_stats(const void *self) { return &((const ispm_state *)self)->st; }

static int read_buffer(GLuint buf, long offset, long elem, int count, void *out)
{
    if (!buf || count <= 0)
        return 0;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, buf);
    const void *p = glMapBufferRange(GL_COPY_READ_BUFFER, offset, elem * count, GL_MAP_READ_BIT);
    if (!p)
        return -1;
    memcpy(out, p, (size_t)(elem * count));
    glUnmapBuffer(GL_COPY_READ_BUFFER);
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    return count;
}

int gk_ispm_read_photons(void *self, gk_ispm_photon *out, int cap)
{
    ispm_state *s = self;
    unsigned n = 0;
    if (read_buffer(s->photon_ssbo, 0, 4, 1, &n) < 0)
        return -1;
    int count = (int)(n < (unsigned)s->capacity ? n : (unsigned)s->capacity);
    return read_buffer(s->photon_ssbo, ISPM_PH_HEADER_BYTES, ISPM_PHOTON_BYTES, count < cap ? count : cap, out);
}

int gk_ispm_read_hits(void *self, gk_ispm_hit *out, int cap)
{
    ispm_state *s = self;
    return read_buffer(s->hit_buf, 0, ISPM_HIT_BYTES, s->capacity < cap ? s->capacity : cap, out);
}

int gk_ispm_read_pixels(void *self, gk_ispm_pixel *out, int cap)
{
    ispm_state *s = self;
    int n = s->ll_res * s->ll_res;
    return read_buffer(s->pixels_ssbo, 0, 16, n < cap ? n : cap, out);
}

int gk_ispm_read_splat(void *self, float *out, int cap_floats)
{
    ispm_state *s = self;
    if (!s->splat_fbo || cap_floats < s->splat_w * s->splat_h * 4)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->splat_fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, s->splat_w, s->splat_h, GL_RGBA, GL_FLOAT, out);
    return s->splat_w * s->splat_h * 4;
}

bool gk_ispm_trace_pixel(const void *self, vec3 world, float out_px[2])
{
    const ispm_state *s = self;
    vec4 c = m4_vec4(m4_mul(s->proj, s->view), (vec4){world.x, world.y, world.z, 1.0f});
    if (c.w <= 0.0f)
        return false;
    out_px[0] = (c.x / c.w * 0.5f + 0.5f) * (float)s->trace_res;
    out_px[1] = (c.y / c.w * 0.5f + 0.5f) * (float)s->trace_res;
    return true;
}

const gk_gi_method gk_gi_ispm = {
    .name = "ispm",
    .applies = applies,
    .declare_knobs = declare_knobs,
    .create = create,
    .set_scene = set_scene,
    .render = render,
    .memory_bytes = memory_bytes,
    .pass_work = pass_work,
    .destroy = destroy,
};
