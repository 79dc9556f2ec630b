/* The kiosk's progressive ground truth (issue 19): worker threads run the reference path tracer
 * (app/ref/) on the scene and view now shown, at a reduced resolution, and accumulate samples while
 * the view stays put, so the live error of the real-time method can be measured against it.
 *
 * Accumulation: the image is cut into 16x16 tiles and rendered in passes of one sample per pixel,
 * pass-major (every tile gets pass p before any tile gets pass p + 1), so the whole image sharpens
 * evenly. A truth pixel stands for sub x sub frame pixels (sub = frame size / truth size): pass p
 * traces through the centre of frame pixel p mod sub^2 of them, so a cycle of sub^2 passes visits
 * each once, and the cycle's mean is one sample of what the box-downsampled frame holds (the
 * rasterizer samples pixel centres, as a reference does) -- without the variance a random pick
 * among the sub-pixels would add at every edge (the light's edge: 0.68 rel noise at 16 spp at
 * sub = 2, against 0.13 for pixel centres). At sub = 1 it is the reference's own estimator. Per
 * pixel and channel the sum and the sum of squares of the cycle means are kept, so the estimate's
 * own noise is known at every moment:
 *   noise = sqrt(mean over pixels and RGB of s^2 / n) / (mean over pixels and RGB of the estimate),
 * s^2 the sample variance of the n cycle means of the pixel: the expected rel RMSE of the estimate
 * against its own limit (the same quantity as a reference's gikiosk:noise_floor, render.h). spp
 * counts complete cycles: samples per frame pixel, as a reference at the frame's size counts them.
 *
 * Mirrors and glass: caustics seen directly (L S+ D E, and L S+ V E in a medium) come from the
 * reference's light pass, which eye paths leave to it (trace.h); the truth runs it too, split as the
 * reference splits it (gk_ref_light_terms) with the same guided emission. Each pass then has a
 * second set of items, one per tile: a light path per pixel of the tile (its own random stream),
 * splatted where it lands on the frame and box-filtered into the truth pixel there, so a cycle
 * traces one path per frame pixel, as a reference's sample does. The light image is the sum of the
 * splats over the paths traced (every path is an estimate of the whole image); per truth pixel and
 * channel the sums of each path's contribution x and of x^2 give the variance of that mean, s^2/N,
 * which adds to the eye estimate's (the two are independent). spp is the smaller of the eye cycles
 * and the light paths per frame pixel.
 *
 * Restarts: gk_truth_restart installs a new view (a flattened scene, owned from then on) under a new
 * generation; gk_truth_stop retires the current one. Workers read the generation before every
 * sample and leave a retired view's tile at once, so after a restart or stop each worker finishes at
 * most the one sample it had begun (tiles left part-way are counted: gk_truth_stats.aborted_tiles). A fixed image (a committed
 * reference of the same view and size) can stand in for the tracer (gk_truth_use_fixed).
 *
 * Threads: the render thread never waits for a worker. Workers take the mutex only to pick a tile
 * and to add a finished tile into the sums (a few microseconds); the render thread takes it to
 * copy the sums (gk_truth_snapshot). Workers run at the lowest priority (SCHED_IDLE where the
 * kernel allows it, else nice 19), so a core the renderer needs is theirs only when idle. */
#ifndef GK_KIOSK_TRUTH_H
#define GK_KIOSK_TRUTH_H

#include <stdbool.h>
#include <stdint.h>

#include "base/err.h"
#include "../ref/ref_scene.h"

/* The largest truth image by default ([truth] size): the frame is divided by the smallest integer
 * that brings it inside this box (1280x720 -> 160x90, 640x480 -> 160x120, the committed
 * references' size). */
#define GK_TRUTH_MAX_W 160
#define GK_TRUTH_MAX_H 120

typedef struct gk_truth gk_truth;

/* The truth as of one moment (gk_truth_snapshot). */
typedef struct gk_truth_view {
    int width, height;
    float *rgb;           /* width * height * 3, the estimate (mean of the samples), top row first */
    long spp;             /* complete cycles every pixel has (samples per frame pixel); for a fixed
                             image its spp */
    double noise;         /* expected rel RMSE of rgb against its limit (see above); NAN below 2 spp */
    uint64_t generation;  /* the view it belongs to; 0 when there is none */
    bool fixed;           /* a committed reference, not the tracer */
} gk_truth_view;

typedef struct gk_truth_stats {
    uint64_t samples;       /* samples added to the current or earlier views */
    uint64_t aborted_tiles; /* tiles left part-way because their view was retired */
    uint64_t samples_after_stop; /* samples that finished after their view was retired: at most one
                                    per worker and retirement (the one in flight) */
    uint64_t retired_views; /* views retired (by a restart, a stop or the end) */
    int workers;
    bool low_priority;      /* the workers run at SCHED_IDLE or nice 19 */
} gk_truth_stats;

/* The worker count of a [truth] workers value: 0 = online cores - 1, at least 1. */
int gk_truth_worker_count(int configured);
/* The truth size for a frame of fw x fh inside max_w x max_h (see GK_TRUTH_MAX_W); returns sub,
 * the divisor (the
 * frame's last fw - w * sub columns and fh - h * sub rows are left out of the comparison). */
int gk_truth_size(int fw, int fh, int max_w, int max_h, int *w, int *h);

/* Starts workers threads (idle until a restart). */
gk_truth *gk_truth_create(int workers, gk_err *e);
/* Stops and joins the workers, frees every view. */
void gk_truth_destroy(gk_truth *t);
/* A new view: rs (built at the frame's size with gk_ref_scene_build, so its pixels are the
 * frame's) is owned by the truth from now on; width x height and sub as gk_truth_size returned:
 * truth pixel (x, y) traces the centres of frame pixels (x sub + i, y sub + j), 0 <= i, j < sub. seed: the random streams (each sample's own, as the reference renderer's). Returns the new
 * generation. */
uint64_t gk_truth_restart(gk_truth *t, gk_ref_scene *rs, int width, int height, int sub, uint64_t seed);
/* A fixed image stands for the truth (copied): a committed reference at the view and size. */
uint64_t gk_truth_use_fixed(gk_truth *t, const float *rgb, int width, int height, long spp, double noise);
/* Retires the current view: workers drop it (without waiting for them). */
void gk_truth_stop(gk_truth *t);
/* Copies the current estimate into v (its rgb reallocated as needed; zero v before the first call).
 * Returns false when there is no view or no complete pass yet. */
bool gk_truth_snapshot(gk_truth *t, gk_truth_view *v);
void gk_truth_view_free(gk_truth_view *v);
void gk_truth_get_stats(gk_truth *t, gk_truth_stats *s);
/* True while any worker is inside a tile (for tests: how soon workers leave a retired view). */
bool gk_truth_busy(gk_truth *t);

#endif
