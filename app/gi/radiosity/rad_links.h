/* Links with implicit visibility (seed 001 ch. 4, research dong-001.md §2.1, §2.3): every node of
 * the hierarchy keeps a world-aligned cube map of 6 x N x N bins, and each bin only its SHORTEST
 * link -- the nearest element in that direction, which hides everything behind it ("a variant of
 * omnidirectional shadow mapping per element").
 *
 * CreateHierarchicalLinks [doc; pseudo-code research 2.3]: link(Ri, Rj) for every pair of chart
 * roots, recursively: when B seen from A subtends more than A's bin (A_B |n_B.ω| / r²) and B has
 * children, link A with each child of B; likewise for A seen from B; else store (B, r) in A's bin of
 * direction ω and (A, r) in B's bin of -ω, each side only if the bin holds no shorter link and the
 * other element lies in front of the side's plane [ours: the acceptance is per side, research 14.3;
 * an element behind a receiver's plane can neither light nor hide anything for it].
 *
 * RefineHierarchicalLinks + PushdownLinks [doc], one top-down traversal: a node inherits, per bin,
 * the link its ancestors resolved; where it has its own link too, the shorter one wins (a shorter
 * child link removes the ancestor's for this subtree only: the siblings keep it, "pushed to the
 * siblings"; a shorter ancestor link removes the child's). What reaches a leaf is its receiving link
 * list, one entry per non-empty bin.
 *
 * Gathering weight: a leaf x linked in bin b to node y receives E += L_y * w, ω and r from x to y,
 * c_x = max(0, n_x.ω), c_y = max(0, -n_y.ω) (0: a back face, which only hides: such links are
 * dropped from the list). The seed's derivation gives two readings of the bin's integral (4.3):
 *   element  eq. (4.5) as printed: w = c_x A_y c_y / r²          (the element's solid angle)
 *   bin      assumption 4 taken whole: w = c_x Ω_b              (the element fills its bin)
 * They agree only when an element subtends exactly its bin. The hierarchy stops subdividing where
 * an element subtends at most its bin (element: too low, by up to 4x), and leaves, which cannot be
 * subdivided, may subtend several bins but fill one (bin: too low). Our default [ours]:
 *   spill    w = c_x max(Ω_b, Ω_disc),  Ω_disc = 2π c_y (1 - r / sqrt(r² + A_y / π)),
 * the bin's solid angle, or the element's own where it spills over its bin (the disc formula is
 * exact on the disc's axis and stays bounded however near the element is). Measured (furnace,
 * 1,014 vertices; mean over the surfels of Σ w / π, which is 1 when the hemisphere is covered
 * once): element 0.57 (6x8²) / 0.77 (6x16²), bin 0.78 / 0.62, spill 0.97 / 0.98.
 * Ω_b = (2/N)² / (1 + u² + v²)^(3/2) at the texel's centre (research 2.3).
 *
 * Subdivision test [ours; the doc does not give the formula, research 14.3]: the element's area
 * over r², not its projected area A |n.ω| / r² (research 2.3's suggestion): a grazing element's
 * long side spans several bins even when its projection is small. */
#ifndef GK_RAD_LINKS_H
#define GK_RAD_LINKS_H

#include <stdbool.h>
#include <stdint.h>

#include "rad_tree.h"

typedef struct rad_links {
    int n_face;                /* N: 6 x N x N bins per node */
    int n_leaves;
    uint32_t *offset;          /* n_leaves + 1: leaf i's links are [offset[i], offset[i + 1]) */
    uint32_t *target;          /* node gathered from */
    float *weight;             /* irradiance per unit radiance of the target (see above) */
    /* Per leaf, its bins that hold no link after push-down, one bit a bin (bit k of word k / 64 of the
       leaf's empty_words words): the directions that escape the scene, where the seed's empty bins
       gather the environment (rad_env.h). A bin holding an occluder (a back face, weight 0) is not
       empty. */
    uint64_t *empty;
    int empty_words;           /* ceil(6 N² / 64) */
    /* what the passes did (for the tests and the HUD) */
    long created;              /* bin entries stored by link() (a displaced one counts again) */
    long displaced;            /* stored, then replaced by a shorter link in the same bin */
    long inconsistent;         /* (node, bin) where an ancestor's and the node's links met in refinement */
    long leaf_links;           /* entries in the leaf lists (weight > 0) */
    long occluder_links;       /* leaf entries dropped for weight 0 (back faces) */
    long bin_bytes;            /* the bin grid's memory (every node x 6N² x 8 bytes) */
    long pairs_linked;         /* chart-root pairs linked by this build */
    long pairs_cached;         /* chart-root pairs whose bins came from the cache (incremental) */
} rad_links;

/* The bins made by the pairs of chart roots of which neither moves (rad_links_update). */
typedef struct rad_link_cache {
    int32_t *target;
    float *len;
    size_t cells;              /* n_nodes x 6N²: a cache of another tree or N is remade */
    long static_pairs;
} rad_link_cache;
void rad_link_cache_free(rad_link_cache *c);

/* The gathering weight of a link (see above). */
typedef enum rad_weight { RAD_WEIGHT_SPILL, RAD_WEIGHT_ELEMENT, RAD_WEIGHT_BIN } rad_weight;

/* Builds the links of t at N = n_face. GK_ERUNTIME when memory runs out. */
int rad_links_build(rad_links *L, const rad_tree *t, int n_face, rad_weight weight, gk_err *e);
/* The links of t at its current pose (after rad_tree_refit), incrementally where nothing moved:
 * moving[c] says chart c moves (its node is animated); the pairs of two static charts are linked once
 * into `cache` (empty at first, kept by the caller for the same tree and N) and copied from it; the
 * pairs with a moving chart are linked anew, then refinement and push-down run over the whole grid.
 * The result is the one rad_links_build gives at this pose (tests/unit/test_radiosity_refit.c).
 * moving or cache NULL: a full build. */
int rad_links_update(rad_links *L, const rad_tree *t, int n_face, rad_weight weight, const bool *moving,
                     rad_link_cache *cache, gk_err *e);
void rad_links_free(rad_links *L);

/* The cube-map bin of a direction (6 N² bins: face +x, -x, +y, -y, +z, -z, then v-major texels),
 * and a bin's solid angle at its texel centre. */
int rad_cube_bin(vec3 d, int n_face);
float rad_bin_solid_angle(int bin, int n_face);
/* The unit direction through a point (s, t) in [0, 1]² of bin `bin` ((0.5, 0.5): its texel centre),
   the inverse of rad_cube_bin. */
vec3 rad_bin_direction(int bin, int n_face, float s, float t);
/* Whether bin k of leaf i is empty (see rad_links.empty). */
static inline int rad_leaf_bin_empty(const rad_links *L, int leaf, int k)
{
    return (int)((L->empty[(size_t)leaf * (size_t)L->empty_words + (size_t)(k >> 6)] >> (k & 63)) & 1u);
}

#endif
