/* Pure C part of the `vpl` GI method (seed 001 ch. 6, Dong; summary dong-001.md §4): Halton
 * sampling, the k-means clustering of virtual point lights (VPLs) into virtual area lights (VALs)
 * with the thesis's distance, the VPL -> VAL mapping C(i), each VAL's frame and area, and our
 * additions (adaptive M, warm-start mode kept only as the F9 regression oracle). No GL here, so it
 * is unit-tested directly (tests/unit/test_vpl_cluster.c). */
#ifndef GK_VPL_CLUSTER_H
#define GK_VPL_CLUSTER_H

#include <stdbool.h>
#include <stdint.h>

#include "../../core/vecmath.h"

#define GK_VPL_MAX_N 1024
#define GK_VPL_MAX_M 32

/* One VPL as read back from the RSM. flux = reflected flux Φ_i (W) already carrying the Monte-Carlo
 * weight (RSM texels per VPL); area = surface area the VPL stands for (m²), used by the clamp. */
typedef struct gk_vpl {
    vec3 pos, nrm, flux;
    float area;
} gk_vpl;

/* One VAL: centre = mean VPL position, normal = normalised mean normal, (t, b) completes the frame;
 * the area is the 2D bounding rectangle of the VPLs projected on the plane perpendicular to the mean
 * normal (thesis §6.3.1); size Δ = the rectangle's longer side (the thesis leaves Δ open; a line of
 * VPLs keeps its length this way, where sqrt(area) would give 0). */
typedef struct gk_val {
    vec3 centre, normal, t, b;
    vec3 origin;         /* the member VPL nearest to the centre: where its map is rendered from
                            unless the faithful centroid is asked for (a centroid can lie inside
                            geometry, e.g. between a floor and a box top: measured in F11) */
    vec3 flux;           /* Σ of member fluxes */
    float area, size;    /* m², m */
    float rect[4];       /* smin, smax, tmin, tmax in the (t, b) frame around centre */
    int count;           /* members; 0 = empty cluster (keeps its seed) */
} gk_val;

/* Distance weights of the thesis (w_x = 0.7, w_n = 0.3); Δx is divided by the scene diameter so
 * both terms are O(1) (dong-001.md §4.3: the thesis does not normalise; we do and say so). */
typedef struct gk_kmeans_opts {
    float w_pos, w_nrm;      /* 0.7, 0.3 */
    float scene_diam;        /* m, > 0 */
    int max_iters;           /* stops earlier when no label changes */
    bool warm_start;         /* F9 oracle only: start from the previous centres (thesis Fig. 6.7) */
} gk_kmeans_opts;

typedef struct gk_kmeans_result {
    int m;                   /* clusters used */
    int iters;               /* iterations run */
    int empty;               /* clusters that ended with no member */
    double error;            /* Σ over valid VPLs of dist(VPL, its centre) / valid count */
} gk_kmeans_result;

/* Radical inverse of i in the given prime base (Halton coordinate), in [0, 1). */
float gk_halton(uint32_t i, uint32_t base);

/* The thesis's distance: w_pos·|p − cp|/scene_diam + w_nrm·angle(n, cn) (radians). */
float gk_vpl_distance(const gk_kmeans_opts *o, vec3 p, vec3 n, vec3 cp, vec3 cn);

/* Nested seed order: seed k is VPL bitreverse(k) over log2(n) bits (n a power of two), so for
 * power-of-two M the seed set is exactly the thesis's {k·N/M}, and the seeds of M are a prefix of
 * the seeds of any larger M, whatever M is (no popping when M changes). Invalid VPLs (zero flux) are
 * skipped: the next unused valid VPL in that order takes their place. Writes m indices. */
int gk_vpl_nested_seeds(const gk_vpl *vpl, int n, int m, int *seeds);

/* k-means of n VPLs into m clusters (thesis §6.4.1), restarted every frame from the nested seeds
 * unless opts->warm_start (then vals[] must hold last frame's centres). Deterministic: fixed order,
 * strict '<' tie-break. Fills labels[n] (the mapping C; -1 for zero-flux VPLs, which are mapped to
 * their nearest centre afterwards in labels_all if given) and vals[m] with frame and area. */
gk_kmeans_result gk_vpl_kmeans(const gk_vpl *vpl, int n, int m, const gk_kmeans_opts *o, int *labels,
                               gk_val *vals);

/* Adaptive M (beyond the thesis): tries M = m_min, 2·m_min, ... ≤ m_max (nested seeds, so each step
 * only adds clusters) and stops at the first doubling whose relative error drop
 * (E(M/2) − E(M)) / E(M/2) is below rel_drop; the previous M is kept within a hysteresis band so
 * the choice does not flip from frame to frame (prev_m <= 0: none). Returns the result of the
 * chosen M with labels/vals filled. */
gk_kmeans_result gk_vpl_kmeans_adaptive(const gk_vpl *vpl, int n, int m_min, int m_max, float rel_drop,
                                        int prev_m, const gk_kmeans_opts *o, int *labels, gk_val *vals);

/* Frame (t, b from the normal), bounding rectangle and area of one cluster's members. */
void gk_val_frame_area(const gk_vpl *vpl, int n, const int *labels, int k, gk_val *val);

/* Mean spacing of the VPLs' surface samples: sqrt(Σ area_i / n_valid); the clamp distance unit. */
float gk_vpl_mean_spacing(const gk_vpl *vpl, int n);

#endif
