/* The `radiosity` GI method (seed 001 ch. 4, Dong et al. 2007, "Interactive global illumination
 * using implicit visibility"; research dong-001.md §2): hierarchical radiosity in which every node
 * keeps, per cube-map bin, only its shortest link, so visibility needs no ray casting.
 *   at a scene's first frame, on a worker thread: refined mesh, charts, surfels (rad_mesh.h) ->
 *   per-chart quadtrees (rad_tree.h) -> links: creation, refinement, push-down (rad_links.h) ->
 *   direct light at the surfels (rad_direct.h), again whenever a light moves -> B0 published
 *   (rad_worker.h);
 *   every frame on the GPU: upload of what is new -> bounces (gather at the leaves, pull-up one
 *   level per dispatch) -> per-vertex indirect irradiance -> added to the HDR image through the
 *   pixel's diffuse BRDF (rad_gpu.c, shaders_gles/radiosity/).
 * Meshes that move are refit every tick (UpdateElements) and relinked at the link update rate on the
 * worker (rad_worker.h). Environment light through empty bins is
 * not built (no scene of ours has an environment and interreflection together).
 * This header is the method's own (tests); the renderer sees only `gk_gi_radiosity` (gi.h). */
#ifndef GK_GI_RADIOSITY_H
#define GK_GI_RADIOSITY_H

#include "../gi.h"
#include "rad_worker.h"

extern const gk_gi_method gk_gi_radiosity;

typedef struct gk_radiosity_stats {
    rad_worker_stats worker;     /* as of this frame */
    bool shown;                  /* the frame added indirect light (a publication existed) */
    int bounces;                 /* run this frame */
    uint64_t uploads;            /* publications uploaded */
} gk_radiosity_stats;

const gk_radiosity_stats *gk_radiosity_get_stats(const void *self);
/* The surfels (vertices) the method refines scene s into at the radiosity_tess knob's level
 * (-1: its default), as `gikiosk scenes` lists them; -1 when the scene is refused (too many
 * vertices, no triangles: e->msg says why). s: evaluated. */
int gk_radiosity_refined_vertices(const gk_scene *s, int tess_level, gk_err *e);
/* The radiosity_tess knob's value at a level (-1: the default) and its number of levels. */
float gk_radiosity_tess(int tess_level);
int gk_radiosity_tess_levels(void);
/* The leaves' indirect irradiance after this frame's bounces (read back from the GPU: tests),
 * 3 floats a leaf into out (room for cap leaves); returns the leaf count, -1 before any result. */
int gk_radiosity_read_irradiance(void *self, float *out, int cap);

#endif
