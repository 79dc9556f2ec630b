/* Per-pass timing. CPU mode (llvmpipe, or when timer queries are not trustworthy): wall clock
 * around glFinish() at each pass end — exact for a software rasterizer, and it serialises the
 * GPU elsewhere, so it is only the fallback. GPU mode: EXT_disjoint_timer_query per pass, read
 * GK_TIMER_LAG frames late so the CPU never waits, and a frame's results are dropped when the
 * GPU reports a disjoint event (clock change, context switch). Pass names are stable strings:
 * they become `PASS_ms` CSV columns. */
#ifndef GK_GL_TIMING_H
#define GK_GL_TIMING_H

#include <stdbool.h>

#include "gl.h"

#define GK_TIMER_LAG 3

#define GK_MAX_PASSES 16

/* Per-pass timings of one frame, in milliseconds (CPU time around a fence on llvmpipe, GPU timer
 * queries where trustworthy). Pass names are stable: they become `PASS_ms` CSV columns. */
typedef struct gk_pass_times {
    int n;
    const char *name[GK_MAX_PASSES];
    double ms[GK_MAX_PASSES];
} gk_pass_times;

typedef struct gk_timer gk_timer;

gk_timer *gk_timer_create(bool use_gpu_queries);
void gk_timer_destroy(gk_timer *t);
bool gk_timer_uses_gpu(const gk_timer *t);

void gk_timer_frame_begin(gk_timer *t);
void gk_timer_pass_begin(gk_timer *t, const char *name);  /* name: a string literal */
void gk_timer_pass_end(gk_timer *t);
/* Fills out with the newest complete measurements (CPU: this frame; GPU: GK_TIMER_LAG frames
 * ago, with zeros until the first results arrive). */
void gk_timer_frame_end(gk_timer *t, gk_pass_times *out);

#endif
