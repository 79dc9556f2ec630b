/* The `lightmap` GI method (seed 004, Larsen & Christensen; photon-mapping-000-004.md Part B):
 *   light-map atlas of the scene's planar surfaces (lm_atlas.h, at scene load) ->
 *   CPU photon tracing on a worker pool with selective redistribution (lm_photons.h, lm_worker.h)
 *   -> approximated illumination maps from the 100 nearest photon-hits per texel, in Δ order under
 *   a texel budget (lm_aim.h) -> uploaded as textures -> GPU final gather per queued texel into
 *   the indirect illumination map, blended (lm_gather.h, lm_display.c) -> added to the renderer's
 *   direct light as diffuse BRDF x indirect irradiance at the pixel's light-map UV.
 * lightmap_iim=0 shows the AIM's indirect part (photons that bounced diffusely) instead of the IIM.
 * Caustics: Halton caustic photons toward the specular generators on the same workers, retraced
 * over W frames (lm_caustics.h), counted as points and filtered 7x7 in the tiles an occlusion
 * query finds photons in (lm_caustic_gpu.h), added as eq. (5) says.
 * This header is the method's own (tests); the renderer sees only `gk_gi_lightmap` (gi.h). */
#ifndef GK_GI_LIGHTMAP_H
#define GK_GI_LIGHTMAP_H

#include "../gi.h"
#include "lm_worker.h"

extern const gk_gi_method gk_gi_lightmap;

typedef struct gk_lightmap_stats {
    lm_worker_stats worker;      /* the pool's, as of this frame */
    int atlas_w, atlas_h, charts;
    int wall_cuts;               /* surfaces cut along walls standing across them (scene/wall_split.h) */
    float texel_size;            /* metres */
    int threads;
    uint64_t uploads;            /* atlases uploaded to the GPU */
    int gathered;                /* IIM texels gathered this frame */
    uint64_t gathered_total;
    long queued;                 /* IIM texels waiting */
    bool shown;                  /* the frame added indirect light (a result existed) */
    /* caustics, this frame */
    int caustic_points;          /* photons drawn */
    int caustic_tiles, caustic_tiles_total; /* tiles filtered, of all */
    long caustic_pixels;         /* pixels filtered */
} gk_lightmap_stats;

const gk_lightmap_stats *gk_lightmap_get_stats(const void *self);
/* Worker threads for the next scene (0: [cpu] workers of the config, else cores - 1). */
void gk_lightmap_set_threads(void *self, int threads);
/* Filter the caustics only in the tiles with photons (the default) or over the whole screen. */
void gk_lightmap_set_caustic_cull(void *self, bool cull);

#endif
