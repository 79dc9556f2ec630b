/* lgv's photon tracer (shaders_gles/lgv/tracer.glsl: lgv_trace, angle-partition ITP and secant, no
 * seeing-map search) replayed on the CPU on the distance maps read back from the GPU
 * (gk_lgv_read_maps), counting the distance texels it reads: tests check the shader's own count
 * (TRACE_COUNT_FETCHES) against it. */
#ifndef GKT_LGV_REPLAY_H
#define GKT_LGV_REPLAY_H

#include <stdbool.h>
#include <stdint.h>

#include "gi/lgv/lgv.h"

typedef struct gkt_lgv_replay {
    const uint32_t *maps;    /* gk_lgv_read_maps' texels */
    gk_lgv_maps_info info;
    const float *centres;    /* gk_lgv_centres: xyz, w per map */
    bool bounds_hits;        /* gk_lgv_debug.bounds_hits */
    long fetches;            /* distance texels read so far */
} gkt_lgv_replay;

/* The direction (not unit) from a map's centre through image-plane point (u, v) in [-1, 1] of face f
 * (lgv/common.glsl's face mapping): texel (x, y) of a res^2 face is u = (x + 0.5) / res * 2 - 1. */
vec3 gkt_lgv_face_dir(int f, float u, float v);

/* Where ray x + d r first meets the scene by the maps (the hit distance, or -1), as lgv_trace. */
float gkt_lgv_replay_trace(gkt_lgv_replay *R, vec3 x, vec3 r);

#endif
