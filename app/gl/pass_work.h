/* A pass's useful work (#21, the bench's efficiency): the fetches its algorithm needs at its
 * parameters -- counted where the count depends on the data (a cone stops at opacity), modelled
 * where it does not -- by the kind of fetch the roofline measures (app/bench/roofline.h), so that
 * efficiency = (fetches / the pass's time) / the machine's limit for that kind. Each model lives
 * beside the pass it describes (app/gi/vct/vct_work.c, ...). */
#ifndef GK_PASS_WORK_H
#define GK_PASS_WORK_H

#define GK_MAX_PASS_WORK 48 /* a frame's lines: the renderer's passes (up to 23: the shadow maps 1,
                                 the VSSM and CSSM prefilters' 3 and 4 where the environment's lights
                                 use the other family, the G-buffer 1, the direct pass's 5 kinds,
                                 glass 2, the cross-fade's copy, hold and blend 3, the occlusion 2,
                                 blend 1, compose 1) and a method's (ispm: 21, vpl's 12 and its
                                 caustic passes' 9; lgv: 14) */

typedef struct gk_pass_work {
    const char *pass;   /* dotted frame-report path: "gi.vct_trace" (a string literal) */
    const char *kind;   /* a roofline.csv name: "tex3d_rgba16f_trilinear" (a string literal) */
    double fetches;     /* useful fetches in the last frame */
} gk_pass_work;

#endif
