/* Selective photon emission (seed 004 §2; photon-mapping-000-004.md B.1.3, B.7 #9): the CPU part
 * of the lightmap method, independent of threads and GL.
 *
 * G groups of P = 40 photons (the seed's 77 x 40 by default). Photon k of the whole set has fixed
 * emission numbers (Halton, bases 2..13: the light pick and gk_light_photon_of's five uniforms);
 * the set is ordered by light and by a Hilbert index of the emission direction's two uniforms and
 * cut into groups of P consecutive photons, so a group holds photons of similar initial direction.
 * A photon's bounces draw from its own PCG stream (seeded by its index), so retracing it in an
 * unchanged scene reproduces its path bit for bit (B.7 #9: the same Russian-roulette numbers).
 *
 * Each path is stored; each of its hits on a surface that has a non-delta lobe is also stored in
 * that surface's list (a chart of lm_atlas.h), with a back index, so removing a path's hits is
 * O(1) per hit (swap with the list's last). Every hit added or removed adds its energy to the
 * surface's Δ_f, and to Δ_i when the photon had bounced diffusely before.
 *
 * Per tick (one per frame), a valid group retraces one photon, round robin; a group whose photon
 * came back with another surface sequence, or any hit more than tau from its stored position, is
 * invalidated and retraced completely in the next tick. Russian roulette at every bounce: survival
 * min(0.95, max of the BSDF weight). */
#ifndef GK_LM_PHOTONS_H
#define GK_LM_PHOTONS_H

#include <stdbool.h>
#include <stdint.h>

#include "base/err.h"
#include "ref/ref_scene.h"

#define LM_PHOTONS_PER_GROUP 40
#define LM_MAX_HITS 16

/* What lit a stored hit, in the reference's path classes (ref/trace.h): the light directly (L D),
 * through delta surfaces only (L S+ D: caustics), or after a non-delta bounce (indirect). Light
 * from emissive meshes counts as indirect from the first hit: the renderer's direct pass does not
 * compute it. */
enum { LM_HIT_DIRECT = 0, LM_HIT_CAUSTIC = 1, LM_HIT_INDIRECT = 2 };

typedef struct lm_hit {
    vec3 pos;                /* world */
    vec3 power;              /* flux the photon brings (already divided by the photon count) */
    int photon;              /* owner */
    uint8_t index;           /* its hit number in the owner's path */
    uint8_t kind;            /* LM_HIT_* */
} lm_hit;

typedef struct lm_store {    /* the photon-hits of one surface */
    lm_hit *hits;
    int n, cap;
    double delta_f, delta_i; /* energy added or removed since the surface's last AIM update */
    double delta_g;          /* Δ_i since the surface's texels were last queued for the final gather */
    double energy;           /* luminance power stored now */
} lm_store;

typedef struct lm_path_hit {
    int surface;             /* chart hit (-1: uncharted); the divergence test compares these */
    int slot;                /* index in the surface's list, -1 when not stored (no non-delta lobe) */
    vec3 pos, power;
    uint8_t kind;
    bool stored;
} lm_path_hit;

typedef struct lm_path {
    int n;
    lm_path_hit h[LM_MAX_HITS];
} lm_path;

typedef struct lm_emit {
    int light;               /* -1: the photon emits nothing */
    float prob;              /* of picking that light */
    float u[5];
} lm_emit;

typedef struct lm_group {
    int cursor;              /* next photon to retrace */
    bool invalid;            /* retrace every photon in the next tick */
    unsigned invalidations;  /* times a retraced path diverged */
} lm_group;

typedef struct lm_photons {
    int n_groups, per_group, n_photons;
    lm_emit *emit;           /* photon g * per_group + j is photon j of group g */
    lm_path *paths;
    lm_group *groups;
    lm_store *stores;
    int n_stores;
    float tau;               /* path-divergence tolerance (m) */
    float scale;             /* 1 / n_photons */
} lm_photons;

/* Emission numbers and groups for the lights of rs; every group starts invalid (traced in full at
 * the first tick). n_surfaces: the atlas's charts. */
int lm_photons_init(lm_photons *ph, const gk_ref_scene *rs, int n_groups, int n_surfaces, float tau, gk_err *e);
void lm_photons_free(lm_photons *ph);

/* Traces photon k through rs (thread-safe: reads only). ref_chart maps rs's triangles to charts. */
void lm_trace_photon(const lm_photons *ph, const gk_ref_scene *rs, const int *ref_chart, int k, lm_path *out);
/* A retraced path diverges: another sequence of surfaces, or a hit moved more than tau. */
bool lm_path_diverges(const lm_path *stored, const lm_path *fresh, float tau);
/* Replaces photon k's stored path (its hits leave their surfaces, the new ones join theirs). */
void lm_photons_replace(lm_photons *ph, int k, const lm_path *fresh);

/* Radical inverse of i in a prime base, in [0, 1). */
float lm_halton(uint32_t i, uint32_t base);

#endif
