/* The lightmap method's CPU side on a fixed pool of pthreads (seed 004: "the CPU's idle cores
 * trace photons while the GPU renders"): the render thread submits one tick per frame (the node
 * matrices of the frame, the budgets) and never waits; the pool's coordinator thread runs the
 * newest request -- retrace one photon per group (or every photon of an invalidated group), apply
 * the replaced paths to the surfaces' photon lists, update AIM surfaces in Δ order within the
 * texel budget -- spreading the tracing and the texels over the helper threads, and publishes the
 * irradiance atlas. Requests that arrive while a tick runs are merged into one (the newest scene);
 * the frame shows the last complete result. */
#ifndef GK_LM_WORKER_H
#define GK_LM_WORKER_H

#include <stdbool.h>
#include <stdint.h>

#include "lm_atlas.h"
#include "lm_caustics.h"
#include "lm_photons.h"

typedef struct lm_tick_settings {
    int groups;              /* photon groups (photons = groups x 40); a change re-emits them all */
    int aim_texels;          /* AIM texels per tick */
    int caustic_photons;     /* caustic photons (lm_caustics.h); 0: none. A change re-emits them */
    int caustic_window;      /* W: ticks over which each caustic photon is retraced once */
} lm_tick_settings;

typedef struct lm_worker_stats {
    uint64_t ticks;          /* completed */
    uint64_t submitted;      /* requests made (ticks + merged ones) */
    int threads;
    int groups, photons;
    /* the last tick */
    int traced;              /* photons traced */
    int invalidated;         /* groups that diverged */
    int replaced;            /* paths replaced */
    int surfaces_updated, texels_updated;
    int pending_surfaces;    /* surfaces whose Δ_f is over the threshold after it */
    /* since the start */
    uint64_t traced_total, invalidations_total, texels_total;
    uint64_t result_seq;     /* publications of the atlas */
    /* caustics (lm_caustics.h) */
    int caustic_photons;     /* shot (0: no caustic generator or light in the scene) */
    int caustic_hits;        /* of them, L S+ D photons kept, as published */
    int caustic_retraced;    /* by the last tick */
    uint64_t caustic_seq;    /* publications of the caustic list */
    bool failed;             /* the tracer could not run (message in error) */
    char error[1024];
} lm_worker_stats;

typedef struct lm_worker lm_worker;

/* scene: as loaded (meshes, materials, lights are read by the pool for its life; node matrices
 * come with each submit). atlas: kept by the caller for the worker's life. threads >= 1. */
lm_worker *lm_worker_create(const gk_scene *scene, const lm_atlas *atlas, int threads, gk_err *e);
void lm_worker_destroy(lm_worker *w);
/* Non-blocking: the frame's scene (evaluated) and settings for the next tick. */
void lm_worker_submit(lm_worker *w, const gk_scene *evaluated, const lm_tick_settings *set);
/* Blocks until no tick is pending or running (tests, lockstep mode). */
void lm_worker_wait(lm_worker *w);
/* Calls fn with the newest published atlases (RGBA floats of width x height texels: the indirect
 * and the full irradiance) and the final gather's queue (per chart: > 0 = gather its texels with
 * that priority, the surface's Δ_i; cleared once taken) when they are newer than *seen (then
 * updates *seen); returns whether it called. Holds the pool's lock only for the call (the
 * coordinator waits for it just when publishing). */
typedef void (*lm_take_fn)(void *ctx, const float *indirect, const float *full, const float *queue);
bool lm_worker_take(lm_worker *w, uint64_t *seen, lm_take_fn fn, void *ctx);
/* Calls fn with the newest published caustic photons (n points of 6 floats: world position xyz,
 * flux rgb) when they are newer than *seen (then updates *seen); returns whether it called. */
typedef void (*lm_take_caustics_fn)(void *ctx, const float *points, int n);
bool lm_worker_take_caustics(lm_worker *w, uint64_t *seen, lm_take_caustics_fn fn, void *ctx);
void lm_worker_get_stats(lm_worker *w, lm_worker_stats *out);
/* Copies each group's invalidation count (room for `cap`); returns the group count. */
int lm_worker_group_invalidations(lm_worker *w, unsigned *out, int cap);
/* Each group's first photon's first hit position (x, y, z per group; room for 3 cap); returns
 * the group count: tests relate groups to the room they light. */
int lm_worker_group_first_hits(lm_worker *w, float *out, int cap);

/* The default worker count: cores - 1, at least 1. */
int lm_default_threads(void);

#endif
