/* The roofline of this machine (`gikiosk bench --roofline`): the rate at which its GPU does the
 * fetches the GI methods are made of -- trilinear 3D texture fetches at the voxel formats, 2D
 * fetches at the shadow/SAT formats (RGBA32F, depth, R32F, R32UI, R16F unfiltered), 3D image
 * loads -- and the fragments a flat shader fills per second (the raster kind, roofline_fill.c) --
 * measured by a compute shader that does a
 * known number of fetches per invocation (shaders_gles/bench/roofline.comp), timed by the
 * renderer's one clock (app/gl/gl_timing.c). A pass's useful fetches per second divided by the
 * limit of its kind of fetch is how close it runs to what the machine can do. */
#ifndef GK_BENCH_ROOFLINE_H
#define GK_BENCH_ROOFLINE_H

#include <stdint.h>

#include "base/err.h"
#include "gl/gl_program.h"

#define GK_ROOFLINE_MAX_CASES 16

typedef struct gk_roofline_opts {
    int invocations;   /* per dispatch, a multiple of 64 */
    int fetches;       /* per invocation */
    int reps;          /* timed dispatches per case (the median is kept), after one untimed */
} gk_roofline_opts;

typedef struct gk_roofline_result {
    const char *name;        /* "tex3d_rgba16f_trilinear": the kind of fetch, a CSV key */
    const char *format;      /* "rgba16f" */
    int size;                /* level-0 side in texels */
    double fetches;          /* per dispatch: invocations x fetches, what the host asked for (the
                                raster kind: fragments, invocations pixels x fetches triangles) */
    uint64_t counted;        /* what the shader counted over all timed dispatches; the raster
                                kind: its counting variant over one more, untimed run (0 where
                                fragment shaders cannot write storage buffers) */
    double expected;         /* what counted should be: fetches x timed dispatches (raster: fetches) */
    const char *unit;        /* "fetches", or "fragments" for the raster kind */
    double median_ms;        /* of one dispatch */
    double fetches_per_s;    /* fetches / median time: the machine's limit for this kind */
} gk_roofline_result;

/* Sensible defaults: enough work that a dispatch takes milliseconds even on llvmpipe. */
void gk_roofline_opts_defaults(gk_roofline_opts *o);

/* Measures every case on the current GL context. Returns the number of results (<= max) or -1
 * with e filled (a shader that fails to build, a GL error). */
int gk_roofline_measure(gk_program_cache *programs, const gk_roofline_opts *o, gk_roofline_result *out,
                        int max, gk_err *e);

/* DIR/roofline.csv: name,format,size,fetches,median_ms,fetches_per_s (one row per case). */
int gk_roofline_write_csv(const gk_roofline_result *r, int n, const char *path, gk_err *e);

#endif
