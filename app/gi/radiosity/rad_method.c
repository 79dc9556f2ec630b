/* The `radiosity` method behind gi.h: knobs, the scene's worker, per-frame orchestration (submit,
 * take the newest publication, bounce, display), statistics. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "rad_internal.h"

/* Knobs (research dong-001.md §2.4). Cost priors: relative frame cost on the render thread. Link
 * creation runs on the worker; the frame pays the bounces (a gather over every leaf link, then the
 * pull-up) and the display.
 *   radiosity_bins:    6 x N² bins per node, N = 8, 12 (the seed's default, "a good compromise"),
 *                      16; priors from Table 4.1's totals 112 / 148 / 218 ms
 *   radiosity_bounces: gather + pull-up iterations (the seed shows direct, 1 and 2; "one bounce is
 *                      sufficient for a pleasing result"); the bounce pass grows linearly, priors
 *                      assume it is half the frame
 *   radiosity_tess:    the target edge length of the load-time refinement, as a fraction of the
 *                      scene's bounding diagonal (edge = diagonal / value): cornell gets 1,502, 2,983,
 *                      5,135 vertices, furnace 1,734, 2,646, 5,046 (the seed: 792 leak, ~2.5k-5k are fine); the gather grows with
 *                      the links, about linearly in the vertices
 *   radiosity_weight:  the gathering weight (rad_links.h): spill (ours, default), or the seed's two
 *                      readings, element (eq. 4.5) and bin (assumption 4); a variant switch
 *   radiosity_sync:    async (the seed: the frame uses the last complete link set) or lockstep (the
 *                      frame waits for its request: deterministic captures for tests)
 *   radiosity_link_every: the link update rate where meshes move: links rebuilt on every 4th, 2nd or
 *                      every (the seed: every frame) worker tick that moved a mesh; the hierarchy is
 *                      refit every tick. Its cost is the worker's, which the frame does not wait for
 *                      (async): on the render thread only the link upload follows it, and on a
 *                      scene without moving meshes it changes nothing. Flat priors: the scheduler
 *                      expects no saving from it, so it is the last knob it steps down (it still
 *                      can: a knob believed free is dropped once every other is at its floor)
 *   radiosity_env:     where a scene has an environment, how its light reaches the surfels (rad_env.h):
 *                      bins (the seed: the leaves' empty bins gather the bin's mean radiance), rest
 *                      (ours: the same, scaled to what the links leave of the hemisphere) or rays
 *                      (ours: shadow rays towards the map like every other light); a variant switch
 *   radiosity_vis:     bins (the seed: implicit visibility only, the shortest link per bin) or rays
 *                      (ours, the default: walls split the surfaces they cross and every leaf link is
 *                      tested by a shadow ray, rad_vis.h; light-leak's RMSE 0.562 -> 0, cornell
 *                      0.0403 -> 0.0396, caustic-ring 0.319 -> 0.339). Its cost is the worker's (the
 *                      rays take about twice the link build), not the frame's: flat priors, and a
 *                      variant switch the scheduler does not move */
enum { K_BINS, K_BOUNCES, K_TESS, K_WEIGHT, K_SYNC, K_LINK_EVERY, K_ENV, K_VIS, K_COUNT };
_Static_assert(K_COUNT == RAD_KNOBS, "rad_internal.h's RAD_KNOBS counts the knobs");
static const gk_knob_def knobs[K_COUNT] = {
    {.name = "radiosity_bins", .owner = "radiosity", .n_values = 3, .values = {"8", "12", "16"},
     .cost = {1.0f, 1.32f, 1.95f}, .default_level = 1},
    {.name = "radiosity_bounces", .owner = "radiosity", .n_values = 4, .values = {"1", "2", "4", "8"},
     .cost = {1.0f, 1.5f, 2.5f, 4.5f}, .default_level = 2},
    {.name = "radiosity_tess", .owner = "radiosity", .n_values = 3, .values = {"16", "24", "32"},
     .cost = {1.0f, 2.0f, 3.5f}, .default_level = 1},
    {.name = "radiosity_weight", .owner = "radiosity", .n_values = 3, .values = {"spill", "element", "bin"},
     .cost = {1.0f, 1.0f, 1.0f}, .default_level = 0, .fixed = true},
    {.name = "radiosity_sync", .owner = "radiosity", .n_values = 2, .values = {"async", "lockstep"},
     .cost = {1.0f, 1.0f}, .default_level = 0, .fixed = true},
    {.name = "radiosity_link_every", .owner = "radiosity", .n_values = 3, .values = {"4", "2", "1"},
     .cost = {1.0f, 1.0f, 1.0f}, .default_level = 2},
    {.name = "radiosity_env", .owner = "radiosity", .n_values = 3, .values = {"bins", "rest", "rays"},
     .cost = {1.0f, 1.0f, 1.0f}, .default_level = 0, .fixed = true},
    {.name = "radiosity_vis", .owner = "radiosity", .n_values = 2, .values = {"bins", "rays"},
     .cost = {1.0f, 1.0f}, .default_level = 1, .fixed = true},
};


rad_settings rad_settings_for(const gk_scene *sc, float tess, int n_face, rad_weight weight)
{
    vec3 ext = v3_sub(sc->bmax, sc->bmin);
    float diag = v3_len(ext) > 0.0f ? v3_len(ext) : 1.0f;
    return (rad_settings){.edge = diag / tess, .n_face = n_face, .weight = weight, .samples = RAD_DIRECT_SAMPLES,
                          .max_verts = RAD_MAX_VERTS, .link_every = 1};
}

float gk_radiosity_tess(int level)
{
    const gk_knob_def *k = &knobs[K_TESS];
    return (float)atof(k->values[level >= 0 && level < k->n_values ? level : k->default_level]);
}

int gk_radiosity_tess_levels(void) { return knobs[K_TESS].n_values; }

int gk_radiosity_refined_vertices(const gk_scene *s, int tess_level, gk_err *e)
{
    rad_settings set = rad_settings_for(s, gk_radiosity_tess(tess_level), 12, RAD_WEIGHT_SPILL);
    rad_mesh m;
    if (rad_mesh_build(&m, s, set.edge, set.max_verts, e))
        return -1;
    int n = m.n_verts;
    rad_mesh_free(&m);
    return n;
}

static void declare_knobs(gk_budget *b)
{
    gk_budget_add_all(b, knobs, K_COUNT);
}

/* Light bouncing between diffuse surfaces and a model of the seed's size (moving meshes are fine:
   the hierarchy is refit every frame and the links rebuilt at the link update rate, rad_worker.h;
   moving lights recompute the direct light: cornell-spot-anim): its scenes have 2.5k-5k vertices, the refinement never merges triangles, and link
   creation pairs every chart root. RAD_MAX_SOURCE_TRIS lets caustic-ring (202 triangles, 0.9 s to
   its first result on llvmpipe's machine) in and keeps atrium (79,808, past the vertex limit before
   any link) out. */
#define RAD_MAX_SOURCE_TRIS 10000

static bool applies(const gk_scene *s)
{
    return s->features.has_interreflection && s->n_triangles <= RAD_MAX_SOURCE_TRIS;
}

static void *create(const gk_gi_context *ctx, gk_err *e)
{
    rad_state *s = calloc(1, sizeof *s);
    if (!s) {
        gk_fail(e, GK_ERUNTIME, "radiosity: out of memory");
        return NULL;
    }
    s->ctx = *ctx;
    gk_knob_handles(s->knob, knobs, K_COUNT);
    s->own_cache = gk_gi_context_own_programs(&s->ctx);
    return s;
}

static void teardown_scene(rad_state *s)
{
    rad_worker_destroy(s->worker); /* joins its thread before what it reads goes */
    s->worker = NULL;
    rad_gpu_free(&s->gpu);
    gk_counters_free(&s->display_fragments);
    gk_scene_free(s->own_scene);
    s->own_scene = NULL;
    gk_wall_regions_free(&s->regions);
    s->scene = s->source = NULL;
    s->seen = 0;
    s->logged_failure = false;
    memset(&s->st, 0, sizeof s->st);
}

static int setup_scene(rad_state *s, const gk_scene *sc, gk_err *e)
{
    teardown_scene(s);
    s->source = sc;
    /* The worker reads meshes, materials and lights between frames; the renderer's scene may be
       freed before the method hears of the next one, so it reads its own copy, loaded from the same
       file (as lightmap does). */
    if (sc->path[0]) {
        gk_err le = {0};
        s->own_scene = gk_scene_load(sc->path, &le);
        if (s->own_scene && (s->own_scene->n_nodes != sc->n_nodes || s->own_scene->n_triangles != sc->n_triangles)) {
            gk_log("radiosity: %s changed on disk since it was loaded; using the loaded scene", sc->path);
            gk_scene_free(s->own_scene);
            s->own_scene = NULL;
        }
        if (s->own_scene)
            for (int i = 0; i < sc->n_nodes; i++)
                s->own_scene->nodes[i].world = sc->nodes[i].world;
    }
    s->scene = s->own_scene ? s->own_scene : sc;
    /* radiosity_vis=rays: walls split the surfaces they cross (scene/wall_split.h), in the method's
       own copy only, so that no element straddles a wall (rad_vis.h) */
    if (s->rays && s->own_scene && gk_split_walls(s->own_scene, &s->regions, e) < 0)
        return -1;
    if (!(s->worker = rad_worker_create(s->scene, s->regions.n_meshes ? &s->regions : NULL, e)))
        return -1;
    return 0;
}

static int set_scene(void *self, const gk_scene *sc, gk_err *e) { return setup_scene(self, sc, e); }

static int render(void *self, const gk_gi_frame *f, gk_err *e)
{
    rad_state *s = self;
    const gk_budget *b = f->budget;
    bool rays = gk_knob_level(b, &s->knob[K_VIS], 0) == 1;
    if (!s->worker || f->scene != s->source || rays != s->rays) {
        s->rays = rays; /* the walls' cuts are made in the scene copy the worker reads: a new one */
        if (setup_scene(s, f->scene, e))
            return -1;
    }
    rad_settings set = rad_settings_for(f->scene, gk_knob_number(b, &s->knob[K_TESS], 24.0f),
                                        (int)gk_knob_number(b, &s->knob[K_BINS], 12.0f),
                                        (rad_weight)gk_knob_level(b, &s->knob[K_WEIGHT], 0));
    set.link_every = (int)gk_knob_number(b, &s->knob[K_LINK_EVERY], 1.0f);
    static const rad_env_mode env_modes[] = {RAD_ENV_BINS, RAD_ENV_REST, RAD_ENV_RAYS}; /* the knob's levels */
    int env_level = gk_knob_level(b, &s->knob[K_ENV], 0);
    set.env = env_modes[env_level >= 0 && env_level < 3 ? env_level : 0];
    set.vis_rays = s->rays;
    bool lockstep = gk_knob_level(b, &s->knob[K_SYNC], 0) == 1;
    /* the render thread's share of the CPU work: hand over the frame's node matrices, (lockstep:
       wait), upload the newest publication if there is one */
    gk_pass_begin(f->pass, "radiosity_upload");
    rad_worker_submit(s->worker, f->scene, &set);
    if (lockstep)
        rad_worker_wait(s->worker);
    rad_worker_take(s->worker, &s->seen, rad_gpu_take, s);
    gk_pass_end(f->pass);
    rad_worker_get_stats(s->worker, &s->st.worker);
    if (s->st.worker.failed && !s->logged_failure) {
        /* the kiosk keeps showing direct light (and the last result, if one was uploaded) */
        gk_log("%s", s->st.worker.error); /* the message names the method */
        s->logged_failure = true;
    }
    s->st.shown = s->gpu.geometry_id != 0 && s->gpu.have_b0;
    s->st.bounces = 0;
    s->display_fragments.counted = false; /* a frame without the display reports none */
    if (!s->st.shown)
        return 0; /* no complete result yet: direct light only */
    if (rad_gpu_bounce(s, f, (int)gk_knob_number(b, &s->knob[K_BOUNCES], 4.0f), e) || rad_gpu_display(s, f, e))
        return -1;
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "radiosity: GL error 0x%04x during the frame", err);
    return 0;
}

/* gi.h's invalidate (the bench's --rebuild-gi): the worker redoes the seed's per-frame pipeline on
   its next request (rad_worker_redo). */
static void invalidate(void *self)
{
    rad_state *s = self;
    if (s->worker)
        rad_worker_redo(s->worker);
}

static long memory_bytes(const void *self) { return rad_gpu_memory(&((const rad_state *)self)->gpu); }

static void destroy(void *self)
{
    rad_state *s = self;
    if (!s)
        return;
    teardown_scene(s);
    if (s->own_cache)
        gk_program_cache_destroy(s->own_cache);
    free(s);
}

const gk_radiosity_stats *gk_radiosity_get_stats(const void *self) { return &((const rad_state *)self)->st; }

int gk_radiosity_read_irradiance(void *self, float *out, int cap)
{
    rad_state *s = self;
    rad_gpu *g = &s->gpu;
    if (!g->geometry_id || !g->have_b0)
        return -1;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, g->leaves);
    const float *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(48 * (size_t)g->n_leaves), GL_MAP_READ_BIT);
    if (!p) {
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        return -1;
    }
    for (int i = 0; i < g->n_leaves && i < cap; i++)
        for (int c = 0; c < 3; c++)
            out[3 * i + c] = p[12 * i + 8 + c];
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    return g->n_leaves;
}

const gk_gi_method gk_gi_radiosity = {
    .name = "radiosity",
    .applies = applies,
    .declare_knobs = declare_knobs,
    .create = create,
    .set_scene = set_scene,
    .render = render,
    .memory_bytes = memory_bytes,
    .invalidate = invalidate,
    .pass_work = rad_pass_work,
    .destroy = destroy,
};
