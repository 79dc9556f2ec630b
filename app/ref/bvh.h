/* Bounding volume hierarchy over world-space triangles for the reference path tracer: binned SAH
 * build (12 bins per axis), a flattened node array (children stored as adjacent pairs),
 * Moller-Trumbore intersection with precomputed edges, closest-hit and any-hit (shadow) queries. */
#ifndef GK_REF_BVH_H
#define GK_REF_BVH_H

#include <stdbool.h>
#include <stdint.h>

#include "base/err.h"
#include "core/vecmath.h"

typedef struct gk_bvh_node {
    float bmin[3], bmax[3];
    uint32_t offset;   /* leaf: first index into prim order; interior: left child (right = offset + 1) */
    uint16_t count;    /* leaf: number of triangles (> 0); interior: 0 */
    uint16_t axis;     /* interior: split axis, to visit the nearer child first */
} gk_bvh_node;

typedef struct gk_bvh {
    gk_bvh_node *nodes;
    uint32_t n_nodes;
    uint32_t n_tris;
    uint32_t *prim;    /* leaf order -> caller's triangle index */
    vec3 *v0, *e1, *e2; /* per leaf-ordered triangle: vertex 0 and the two edges */
    /* Optional any-hit test, set by the caller after gk_bvh_build: a triangle whose flag in
       `tested` (by caller's index) is set counts as hit only where accept(accept_ctx, tri, u, v)
       says so: alpha-masked materials' cut-outs let every ray through. NULL: every hit counts. */
    const uint8_t *tested;
    bool (*accept)(const void *ctx, uint32_t tri, float u, float v);
    const void *accept_ctx;
} gk_bvh;

typedef struct gk_bvh_hit {
    float t, u, v;     /* distance and barycentrics of vertices 1 and 2 */
    uint32_t tri;      /* caller's triangle index */
} gk_bvh_hit;

/* verts: 3 vertices per triangle. Returns 0, or -1 with e set (out of memory). */
int gk_bvh_build(gk_bvh *b, const vec3 *verts, uint32_t n_tris, gk_err *e);
void gk_bvh_free(gk_bvh *b);

/* Closest hit with tmin < t < tmax; fills hit and returns true when something is hit. */
bool gk_bvh_intersect(const gk_bvh *b, vec3 o, vec3 d, float tmin, float tmax, gk_bvh_hit *hit);
/* True when anything lies between tmin and tmax (shadow rays stop at the first hit). */
bool gk_bvh_occluded(const gk_bvh *b, vec3 o, vec3 d, float tmin, float tmax);

#endif
