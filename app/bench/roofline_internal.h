/* Shared by the roofline's cases (roofline.c: the fetch kinds; roofline_fill.c: the raster kind). */
#ifndef GK_BENCH_ROOFLINE_INTERNAL_H
#define GK_BENCH_ROOFLINE_INTERNAL_H

#include "roofline.h"

/* The median time in ms of o->reps timed runs of run(ctx), after one untimed run (which compiles
 * the JIT code); after_warmup (may be NULL) runs between the untimed run and the timed ones. */
double gk_roofline_time(const gk_roofline_opts *o, void (*run)(void *ctx), void (*after_warmup)(void *ctx), void *ctx);

/* Fills r for a case of o->invocations x o->fetches units of work done in median_ms. */
void gk_roofline_result_set(gk_roofline_result *r, const char *name, const char *format, int size,
                            const gk_roofline_opts *o, double median_ms);

/* The raster kind: fragments a flat shader writes per second (roofline_fill.c). */
int gk_roofline_fill(gk_program_cache *programs, const gk_roofline_opts *o, const char *name, const char *format,
                     gk_roofline_result *r, gk_err *e);

#endif
