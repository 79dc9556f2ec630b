/* Approximated illumination maps (seed 004 §3; photon-mapping-000-004.md B.1.4, B.7 #3): the
 * irradiance at each light-map texel of a surface from its N nearest photon-hits, in a small
 * kd-tree built when the surface is updated from its own hits and those of the surfaces that
 * could contribute to it (lm_atlas.h). "The total energy of
 * these photons is divided by the area that they span": E = ΣΦ / (π r_N²), r_N the distance to
 * the N-th hit, the area never taken larger than the surface's own; a surface with at most N hits
 * spreads their energy over its whole area.
 *
 * Surfaces are updated when their Δ_f exceeds LM_DELTA_REL of the energy they hold (research B.2's
 * recommendation: the seed says only "a small threshold"), in the order Δ_f / area, while the
 * per-frame texel budget lasts (at least one surface a frame). */
#ifndef GK_LM_AIM_H
#define GK_LM_AIM_H

#include "lm_atlas.h"
#include "lm_photons.h"

#define LM_KNN 100           /* the seed's Table 1 */
#define LM_DELTA_REL 0.02

typedef struct lm_kdtree {
    vec3 *pts;
    vec3 *pow;
    unsigned char *axis;
    int n, cap;
} lm_kdtree;

/* From the hits of the kinds in kind_mask (1 << LM_HIT_*) of n_stores surfaces. */
void lm_kdtree_build(lm_kdtree *t, const lm_store *const *stores, int n_stores, unsigned kind_mask);
void lm_kdtree_free(lm_kdtree *t);
/* Sum of the k nearest hits' power to p and the distance to the k-th (k = min(k, n)). */
vec3 lm_kdtree_knn(const lm_kdtree *t, vec3 p, int k, float *r_k);

/* Fills chart ci's interior texels of irr (RGBA floats per atlas texel: E in rgb, a = 1) and its
 * gutter, from the hits of the kinds in kind_mask (1 << LM_HIT_*) of the chart and its contributors (lm_atlas.h); the area
 * cap and the few-hits case use their summed area. world: the chart's node world matrix. */
void lm_aim_update_chart(const lm_atlas *a, const lm_photons *ph, int ci, mat4 world, lm_kdtree *tree, float *irr,
                         unsigned kind_mask);

/* The surfaces due for an update, in Δ_f/area order, within a budget of texels (the first one
 * always): writes their indices to out (room for n_charts), returns the count. */
int lm_aim_select(const lm_atlas *a, const lm_photons *ph, int texel_budget, int *out);

#endif
