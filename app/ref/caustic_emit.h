/* Caustic photons emitted towards the specular geometry (Jensen's projection maps, "Realistic Image
 * Synthesis Using Photon Mapping" §5.1.2), for the light tracer's L S+ D E paths.
 *
 * Why: a caustic path's first vertex after the light is a delta (mirror or smooth glass) surface, so a
 * photon that leaves a light in any other direction contributes nothing to the caustic image. With the
 * light's own emission (uniform over the sphere for a point light) nearly all of them are wasted: in
 * caustic-ring the mirror ring subtends ~0.4% of the sphere seen from the lamp, and the caustic
 * reference stayed at 0.44 rel. RMSE after 39M photons.
 *
 * How: the triangles whose material may be delta (gk_ref_material_may_be_delta) are binned by
 * centroid into a grid of G^3 cells over their bounding box; each non-empty cell becomes a target
 * sphere bounding its triangles' vertices. Seen from a point or spot light each target is a cone
 * (the full sphere when the light is inside it). A photon picks a cone with probability proportional
 * to its solid angle and a direction uniformly inside it: one-sample MIS over the cones with the
 * balance heuristic, i.e. the direction's pdf is the mixture pdf sum_k p_k [d in cone_k] / Omega_k =
 * (cones covering d) / sum_k Omega_k, and the flux is I(d) / (p_light pdf(d)). Every direction that
 * can reach a delta surface first lies in some cone, so the estimator is unbiased: it only stops
 * spending photons where no caustic can start. Spot lights drop the cones outside their outer cone;
 * a light that sees no target emits no caustic photons at all.
 *
 * Area lights, directional lights and suns keep their own emission (gk_light_photon_of): their
 * photons start from a spread of points, and the caustic scenes of the showcase use point lamps. */
#ifndef GK_REF_CAUSTIC_EMIT_H
#define GK_REF_CAUSTIC_EMIT_H

#include <stdbool.h>

#include "base/err.h"
#include "ref_scene.h"
#include "sample.h"

enum { GK_CAUSTIC_EMIT_LIGHT = 0, GK_CAUSTIC_EMIT_GUIDED = 1 };
/* Cells per axis of the target grid. Measured on caustic-ring, 160x120, 32 spp, same run: noise floor
   inside the caustic mask 0.097 / 0.116 / 0.125 with 1 / 2 / 4 cells per axis at equal time — finer
   cells hug the ring better but overlap, and the 1/(cones covering d) weights add variance. */
#define GK_CAUSTIC_GRID_DEFAULT 1

typedef struct gk_caustic_cone {
    vec3 axis;          /* unit, from the light towards the target's centre */
    float cos_max;      /* -1: the light is inside the target, the cone is the whole sphere */
    float solid_angle;  /* 2 pi (1 - cos_max) */
} gk_caustic_cone;

typedef struct gk_caustic_emitter {
    int n_targets;
    vec3 *target_centre;
    float *target_radius;
    int n_lights;
    bool *guided;       /* per light: emits towards the targets (point and spot lights) */
    int *first_cone;    /* per light, n_lights + 1: its cones are [first_cone[l], first_cone[l + 1]) */
    gk_caustic_cone *cones;
    float *cone_cdf;    /* per cone: cumulative solid angle within its light (last = the light's total) */
} gk_caustic_emitter;

/* Builds the targets (grid: cells per axis, >= 1) and every point/spot light's cones. A scene without
 * delta surfaces gets no targets and no guided light. */
int gk_caustic_emitter_build(gk_caustic_emitter *em, const gk_ref_scene *rs, int grid, gk_err *e);
void gk_caustic_emitter_free(gk_caustic_emitter *em);

/* One caustic photon: like gk_light_photon (same light choice by power), but a guided light's
 * direction is drawn from its cones. Returns false when no photon is emitted (no lights, or a guided
 * light that sees no target). */
bool gk_caustic_photon(const gk_ref_scene *rs, const gk_caustic_emitter *em, gk_rng *rng, vec3 *o, vec3 *d,
                       vec3 *flux, int *light);

#endif
