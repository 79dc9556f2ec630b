/* The `lightmap` method behind gi.h: knobs, the scene's atlas and worker pool, per-frame
 * orchestration (submit a tick, take the newest AIM atlases, gather IIM texels, draw), statistics. */
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "lm_internal.h"

/* Cost priors (relative frame cost on the render thread, cheapest = 1). The photon tracing and the
 * AIMs run on the worker pool, not on the render thread: the frame pays the UV and compose passes
 * (independent of these knobs) and one upload of the atlas per publication. So the priors are
 * nearly flat; on a machine whose CPU also runs the GPU driver (llvmpipe) more photons still slow
 * the frame, which the scheduler measures.
 *   lightmap_groups: photons = groups x 40 (the seed's 77 groups); one retrace per group a frame
 *   lightmap_aim:    AIM texels a frame (the seed caps IIM texels at 20; AIMs "a limited amount")
 *   lightmap_iim:    IIM texels gathered a frame (the seed: at most 20); 0 shows the AIM's indirect
 *                    part instead. A gather is a render of the scene: Table 2 puts it at 0.75 ms
 *                    + 0.006 ms per 1,000 polygons of a 28 ms frame, so 20 gathers ~ +54%:
 *                    1 + 0.027 per texel
 *   lightmap_gather: gather render size (Table 2: 8², 16², 32² cost within 4% of each other)
 *   lightmap_texels: the resolution rule (the seed: 5 texels along the largest surface); a change
 *                    re-parameterises the scene and re-emits every photon, so the scheduler never
 *                    moves it
 *   lightmap_sync:   async (the seed: the frame uses the last complete result) or lockstep (the
 *                    frame waits for its tick: deterministic captures for tests and measurements)
 *   lightmap_caustics: caustic photons (the seed's 10,000), traced on the workers; the frame pays
 *                    their upload, the counting points and the filter in the tiles they cover
 *                    (the seed: 37.6 ms full screen, 0.38 ms at 1% of it, linear in area), which
 *                    grow with the caustic's area rather than with the count: a flat prior. 0: no
 *                    caustics. A switch the scheduler does not move: on caustic-ring 2,500, 10,000
 *                    and 40,000 photons measured within 0.01 of each other in the caustic mask
 *                    (tests/e2e/lightmap_caustics.sh: the 7x7 filter's blur, not the count, sets
 *                    the error), so a calibration would find nothing to buy
 *   lightmap_window: W, frames over which every caustic photon is retraced once (the seed: 8);
 *                    the workers' share shrinks as 1/W, the render thread's not at all; a steady
 *                    image does not depend on it (identical at W = 1 and 8), only a moving
 *                    generator's trail, which a static calibration cannot see: a switch too
 *   lightmap_workers: the photon pool's threads: `config` ([cpu] workers, default cores - 1) or 1;
 *                    a switch for the bench's side-by-side measurement of what the photon work
 *                    costs the render thread (`make bench`, tools/bench.sh's lightmap-workers);
 *                    a change restarts the pool and re-emits the photons
 *   lightmap_count:  the caustic count target: 8bit (the seed's, at most 255 photons a pixel: M14)
 *                    or float (R16F where it is colour-renderable, else 8bit, logged): a switch */
enum { K_GROUPS, K_AIM, K_IIM, K_GATHER, K_TEXELS, K_SYNC, K_CAUSTICS, K_WINDOW, K_WORKERS, K_CCOUNT, K_COUNT };
_Static_assert(K_COUNT == LM_KNOBS, "lm_internal.h's LM_KNOBS counts the knobs");
static const gk_knob_def knobs[K_COUNT] = {
    {"lightmap_groups", "lightmap", 4, {"77", "154", "308", "616"}, {1.0f, 1.02f, 1.05f, 1.1f}, 0, 0, false, NULL},
    {"lightmap_aim", "lightmap", 4, {"20", "80", "320", "1280"}, {1.0f, 1.01f, 1.02f, 1.04f}, 1, 0, false, NULL},
    {"lightmap_iim", "lightmap", 4, {"0", "5", "20", "80"}, {1.0f, 1.14f, 1.54f, 3.16f}, 2, 0, false, NULL},
    {"lightmap_gather", "lightmap", 3, {"8", "16", "32"}, {1.0f, 1.01f, 1.04f}, 1, 0, false, NULL},
    {"lightmap_texels", "lightmap", 3, {"5", "10", "20"}, {1.0f, 1.0f, 1.0f}, 0, 0, .fixed = true},
    {"lightmap_sync", "lightmap", 2, {"async", "lockstep"}, {1.0f, 1.0f}, 0, 0, .fixed = true},
    [K_CAUSTICS] = {.name = "lightmap_caustics", .owner = "lightmap", .n_values = 4,
                    .values = {"0", "2500", "10000", "40000"}, .cost = {1.0f, 1.01f, 1.02f, 1.04f}, .default_level = 2, .fixed = true},
    [K_WINDOW] = {.name = "lightmap_window", .owner = "lightmap", .n_values = 4, .values = {"16", "8", "4", "1"},
                  .cost = {1.0f, 1.0f, 1.01f, 1.02f}, .default_level = 1, .fixed = true},
    [K_WORKERS] = {.name = "lightmap_workers", .owner = "lightmap", .n_values = 2, .values = {"1", "config"},
                   .cost = {1.0f, 1.0f}, .default_level = 1, .fixed = true},
    [K_CCOUNT] = {.name = "lightmap_count", .owner = "lightmap", .n_values = 2, .values = {"8bit", "float"},
                  .cost = {1.0f, 1.0f}, .default_level = 0, .fixed = true},
};

static void declare_knobs(gk_budget *b)
{
    gk_budget_add_all(b, knobs, K_COUNT);
}

/* Light bouncing between diffuse surfaces (gi_catalogue.c's GK_GI_NEEDS_INTERREFLECTION): photons
   come from every light type and from emissive surfaces. */
static bool applies(const gk_scene *s) { return s->features.has_interreflection; }

static void *create(const gk_gi_context *ctx, gk_err *e)
{
    lm_state *s = calloc(1, sizeof *s);
    if (!s) {
        gk_fail(e, GK_ERUNTIME, "lightmap: out of memory");
        return NULL;
    }
    s->ctx = *ctx;
    s->caustic_cull = true;
    gk_gl_caps_query(&s->caps, ctx->gles_version ? ctx->gles_version : 31);
    gk_knob_handles(s->knob, knobs, K_COUNT);
    s->own_cache = gk_gi_context_own_programs(&s->ctx);
    return s;
}

static int lm_threads_wanted(const lm_state *s);

static void teardown_scene(lm_state *s)
{
    lm_worker_destroy(s->worker); /* joins its threads before what they read goes */
    s->worker = NULL;
    lm_display_free(s);
    lm_work_free(s);
    if (s->have_atlas)
        lm_atlas_free(&s->atlas);
    s->have_atlas = false;
    gk_scene_free(s->own_scene);
    s->own_scene = NULL;
    s->scene = s->source = NULL;
    s->seen = 0;
    s->caustic_seen = 0;
}

static int setup_scene(lm_state *s, const gk_scene *sc, int texels_across, gk_err *e)
{
    teardown_scene(s);
    s->source = sc;
    /* The worker threads read meshes, materials and lights between frames; the renderer's scene may
       be freed before the method hears of the next one (the bench frees a scene, then sets the
       next), so the method traces its own copy, loaded from the same file. */
    if (sc->path[0]) {
        gk_err le = {0};
        s->own_scene = gk_scene_load(sc->path, &le);
        if (s->own_scene && (s->own_scene->n_nodes != sc->n_nodes || s->own_scene->n_triangles != sc->n_triangles)) {
            gk_log("lightmap: %s changed on disk since it was loaded; tracing the loaded scene", sc->path);
            gk_scene_free(s->own_scene);
            s->own_scene = NULL;
        }
        if (s->own_scene)
            for (int i = 0; i < sc->n_nodes; i++)
                s->own_scene->nodes[i].world = sc->nodes[i].world;
    }
    s->scene = s->own_scene ? s->own_scene : sc;
    /* walls split the surfaces they cross (scene/wall_split.h): only in the method's own copy, which the
       tracer and the atlas both read */
    gk_wall_regions regions = {0};
    s->st.wall_cuts = 0;
    if (s->own_scene) {
        int cuts = gk_split_walls(s->own_scene, &regions, e);
        if (cuts < 0)
            return -1;
        s->st.wall_cuts = cuts;
    }
    int rc = lm_atlas_build_regions(&s->atlas, s->scene, texels_across, s->own_scene ? &regions : NULL, e);
    gk_wall_regions_free(&regions);
    if (rc)
        return -1;
    s->have_atlas = true;
    int threads = lm_threads_wanted(s);
    if (!(s->worker = lm_worker_create(s->scene, &s->atlas, threads, e)))
        return -1;
    if (lm_display_setup(s, e))
        return -1;
    s->st.atlas_w = s->atlas.width, s->st.atlas_h = s->atlas.height, s->st.charts = s->atlas.n_charts;
    s->st.texel_size = s->atlas.texel_size;
    s->st.threads = threads;
    return 0;
}

/* The pool's size: a test's override, else 1 when lightmap_workers=1, else [cpu] workers, else
   cores - 1. */
static int lm_threads_wanted(const lm_state *s)
{
    if (s->threads_override > 0)
        return s->threads_override;
    if (s->one_worker)
        return 1;
    return s->ctx.cpu_workers > 0 ? s->ctx.cpu_workers : lm_default_threads();
}

static int set_scene(void *self, const gk_scene *sc, gk_err *e)
{
    lm_state *s = self;
    return setup_scene(s, sc, s->have_atlas ? s->atlas.texels_across : 5, e);
}

static int render(void *self, const gk_gi_frame *f, gk_err *e)
{
    lm_state *s = self;
    const gk_budget *b = f->budget;
    int across = (int)gk_knob_number(b, &s->knob[K_TEXELS], 5.0f);
    s->one_worker = gk_knob_level(b, &s->knob[K_WORKERS], 1) == 0;
    if (!s->have_atlas || f->scene != s->source || across != s->atlas.texels_across ||
        lm_threads_wanted(s) != s->st.threads)
        if (setup_scene(s, f->scene, across, e))
            return -1;
    lm_tick_settings set = {.groups = (int)gk_knob_number(b, &s->knob[K_GROUPS], 77.0f),
                            .aim_texels = (int)gk_knob_number(b, &s->knob[K_AIM], 80.0f),
                            .caustic_photons = (int)gk_knob_number(b, &s->knob[K_CAUSTICS], 10000.0f),
                            .caustic_window = (int)gk_knob_number(b, &s->knob[K_WINDOW], 8.0f)};
    bool lockstep = gk_knob_level(b, &s->knob[K_SYNC], 0) == 1;
    lm_work_frame(s, f);
    /* the render thread's whole share of the CPU work: hand over the frame's node matrices,
       (lockstep: wait), upload the newest atlas if there is one */
    gk_pass_begin(f->pass, "lightmap_upload");
    lm_worker_submit(s->worker, f->scene, &set);
    if (lockstep)
        lm_worker_wait(s->worker);
    lm_worker_take(s->worker, &s->seen, lm_display_upload, s);
    gk_pass_end(f->pass);
    lm_worker_get_stats(s->worker, &s->st.worker);
    if (s->st.worker.failed)
        return gk_fail(e, GK_ERUNTIME, "%s", s->st.worker.error);
    s->st.shown = s->seen > 0;
    s->st.gathered = 0;
    /* no complete result yet: no indirect light (the caustics do not wait for it) */
    if (s->st.shown) {
        int iim = (int)gk_knob_number(b, &s->knob[K_IIM], 20.0f);
        s->iim_on = iim > 0;
        if (s->iim_on && lm_display_gather(s, f, iim, (int)gk_knob_number(b, &s->knob[K_GATHER], 16.0f), e))
            return -1;
        if (lm_display_draw(s, f, e))
            return -1;
    }
    bool float_count = gk_knob_level(b, &s->knob[K_CCOUNT], 0) == 1;
    if (float_count && !s->caps.color_buffer_half && !s->warned_count) {
        gk_log("lightmap: lightmap_count=float needs R16F render targets (GLES 3.2 or "
               "EXT_color_buffer_half_float); counting in 8 bits");
        s->warned_count = true;
    }
    s->caustic.count_format = float_count && s->caps.color_buffer_half ? GL_R16F : GL_R8;
    if (lm_display_caustics(s, f, e))
        return -1;
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "lightmap: GL error 0x%04x during the frame", err);
    return 0;
}

static long memory_bytes(const void *self)
{
    const lm_state *s = self;
    long b = (long)s->atlas.width * s->atlas.height * 8 * 5;     /* RGBA16F: 2 AIMs, 3 IIMs */
    b += (long)s->gather.res * s->gather.res * s->gather.max_tiles * (16 + 4); /* gather tiles */
    b += (long)s->uv_w * s->uv_h * (8 + 4);                      /* RG32UI + depth 32F */
    b += (long)s->atlas.n_verts * LM_VERT_FLOATS * 4;            /* vertices */
    b += (long)s->caustic.w * s->caustic.h * 2;                   /* R8 counts + stencil */
    b += (long)s->caustic.cap_points * 12;                        /* caustic points */
    return b;
}

static void destroy(void *self)
{
    lm_state *s = self;
    if (!s)
        return;
    teardown_scene(s);
    if (s->own_cache)
        gk_program_cache_destroy(s->own_cache);
    free(s);
}

const gk_lightmap_stats *gk_lightmap_get_stats(const void *self) { return &((const lm_state *)self)->st; }
void gk_lightmap_set_threads(void *self, int threads) { ((lm_state *)self)->threads_override = threads; }
void gk_lightmap_set_caustic_cull(void *self, bool cull) { ((lm_state *)self)->caustic_cull = cull; }

const gk_gi_method gk_gi_lightmap = {
    .name = "lightmap",
    .applies = applies,
    .declare_knobs = declare_knobs,
    .create = create,
    .set_scene = set_scene,
    .render = render,
    .memory_bytes = memory_bytes,
    .pass_work = lm_pass_work,
    .destroy = destroy,
};
