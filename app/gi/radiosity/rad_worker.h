/* The radiosity method's CPU side on a worker thread (seed 001 ch. 4 builds links on the CPU;
 * research dong-001.md §2.3 steps 0-4): the render thread submits each frame's node matrices and
 * settings and never waits; the worker runs the newest request -- (re)builds the geometry (mesh,
 * hierarchy, links: rad_solve.h) when a setting that shapes it changed; when a mesh moved, refits a
 * copy of it to the new pose and, at the link update rate, rebuilds its links incrementally (the
 * pairs of static charts come from a cache: rad_links_update); recomputes the direct light at the
 * surfels when anything moved (rad_direct.h) -- and publishes the initial radiance B0 of every
 * node with the geometry it belongs to. The frame uses the last complete publication. */
#ifndef GK_RAD_WORKER_H
#define GK_RAD_WORKER_H

#include <stdbool.h>
#include <stdint.h>

#include "rad_solve.h"

/* Where the environment's light at the surfels comes from (rad_env.h). */
typedef enum rad_env_mode {
    RAD_ENV_BINS,          /* the seed: the leaves' empty bins gather the bin's mean radiance */
    RAD_ENV_RAYS,          /* ours: shadow rays towards the map, as for every other light (rad_direct.h) */
    RAD_ENV_REST           /* ours: the empty bins scaled to what the links leave of the hemisphere */
} rad_env_mode;

typedef struct rad_settings {
    float edge;            /* target edge length (world units) */
    int n_face;            /* bins: 6 x n_face² */
    rad_weight weight;
    int samples;           /* direct-light samples per area light and surfel */
    int max_verts;
    rad_env_mode env;      /* the environment's light at the surfels (no effect without one) */
    int link_every;        /* while meshes move: links rebuilt every link_every-th tick that moved
                              them (the link update rate); the other ticks refit the hierarchy and
                              keep the last links (their targets and weights) */
    bool vis_rays;         /* links tested by shadow rays (rad_vis.h) on top of the bins' implicit
                              visibility */
} rad_settings;

typedef struct rad_worker_stats {
    uint64_t ticks, submitted, publications;
    bool busy;                 /* a tick is running */
    uint64_t geometry_builds, direct_updates;
    uint64_t refits;           /* ticks that refit the hierarchy (UpdateElements): a mesh moved, or a redo */
    uint64_t link_updates;     /* link rebuilds after the geometry's first (moving meshes) */
    int moving_charts;         /* charts of animated nodes */
    long pairs_linked, pairs_cached; /* of the last link build: root pairs linked, taken from the cache */
    int vertices, nodes, charts;
    long leaf_links, links_created, bin_bytes;
    bool failed;
    char error[1024];
} rad_worker_stats;

typedef struct rad_worker rad_worker;

/* scene: as loaded; read by the worker for its life (meshes, materials, lights); node matrices come
 * with each submit. regions: where walls cut scene's surfaces (scene/wall_split.h; NULL: no cuts),
 * read likewise: the mesh keeps the pieces in separate charts. */
rad_worker *rad_worker_create(const gk_scene *scene, const gk_wall_regions *regions, gk_err *e);
void rad_worker_destroy(rad_worker *w);
/* Non-blocking: the frame's evaluated scene (its node matrices are copied) and settings. */
void rad_worker_submit(rad_worker *w, const gk_scene *evaluated, const rad_settings *set);
/* The next tick redoes what the seed does every frame whether or not anything moved (UpdateElements
 * over every node, link creation over every pair, refinement, push-down, direct light), and
 * publishes it: the bench's --rebuild-gi times the seed's per-frame pipeline with it (in lockstep
 * the frame waits for it: Table 4.1's frame). */
void rad_worker_redo(rad_worker *w);
/* Blocks until no request is pending or running (lockstep mode, tests). */
void rad_worker_wait(rad_worker *w);
/* Calls fn with the newest publication when it is newer than *seen (then updates *seen): the
 * geometry (valid during the call), whether it differs from the one of the publication last taken,
 * and B0 (3 floats per node). Holds the worker's lock during the call. */
typedef void (*rad_take_fn)(void *ctx, const rad_geometry *g, uint64_t geometry_id, const float *b0);
bool rad_worker_take(rad_worker *w, uint64_t *seen, rad_take_fn fn, void *ctx);
void rad_worker_get_stats(rad_worker *w, rad_worker_stats *out);

#endif
