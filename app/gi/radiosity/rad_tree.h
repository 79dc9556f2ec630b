/* The geometric hierarchy (seed 001 ch. 4, research dong-001.md §2.2): one quadtree per chart whose
 * leaves are the chart's surfels, kept without pointers.
 *
 * Index [doc, 0-based]: nodes are numbered leaves first, then level by level towards the roots
 * (the seed's full 3-level tree of 21 nodes: leaves 0-15, level 1 16-19, root 20). Within a level
 * the charts follow each other, and inside a chart the level's nodes are its previous level's nodes
 * taken four at a time in order (the leaves are in Morton order, rad_mesh.h, so on a regular
 * 2^k x 2^k grid this is exactly the quadtree; elsewhere it is the Z-order grouping). So, for node j
 * of chart c at level l (local index j, offsets off(c, l)):
 *     parent     = off(c, l + 1) + j / 4
 *     children   = off(c, l - 1) + 4 j ... + min(4, count(c, l - 1) - 4 j) - 1
 * and a chart's root is the one node of its top level. Per node only its chart and level are kept
 * (to find off and count); the GPU gets each node's first child and child count, derived once from
 * the same arithmetic (rad_tree_children).
 *
 * Node data [doc]: position = average of the children's, normal = average (normalised), area = sum.
 * UpdateElements [doc, Algorithm 1 step 1, "similar to BVH refit"]: every frame a mesh moved,
 * rad_mesh_refit moves the leaves and rad_tree_refit recomputes positions and normals bottom up;
 * areas are not recomputed (the seed: they vary very little). The hierarchy itself (which vertices
 * group) is the build pose's, as in the seed ("precomputed once, not adapted to deformation"). */
#ifndef GK_RAD_TREE_H
#define GK_RAD_TREE_H

#include "rad_mesh.h"

#define RAD_MAX_LEVELS 16 /* 4^15 leaves per chart is far past any mesh we accept */

typedef struct rad_tree {
    int n_nodes, n_leaves;      /* leaves = the mesh's vertices, same index */
    int n_levels;               /* of the deepest chart */
    int level_first[RAD_MAX_LEVELS + 1]; /* first node of each level (all charts); [n_levels] = n_nodes */
    int n_charts;
    int *chart_levels;          /* levels of each chart (1 = a single-vertex chart: the leaf is the root) */
    int (*off)[RAD_MAX_LEVELS]; /* off[c][l]: first node of chart c at level l */
    int (*cnt)[RAD_MAX_LEVELS]; /* cnt[c][l]: its node count at level l */
    int *node_chart;
    unsigned char *node_level;
    vec3 *pos, *nrm;            /* per node; a leaf's pos is its surfel's centre (rad_mesh.h) */
    float *area;
    int *roots;                 /* the charts' roots, n_charts of them */
} rad_tree;

int rad_tree_build(rad_tree *t, const rad_mesh *m, gk_err *e);
void rad_tree_free(rad_tree *t);
/* Bottom-up refit of positions and normals from the mesh's current pose (areas kept). */
void rad_tree_refit(rad_tree *t, const rad_mesh *m);

/* Index arithmetic (see above). Parent: -1 for a root. Children: returns the count (0 for a leaf)
 * and the first child in *first. */
int rad_tree_parent(const rad_tree *t, int node);
int rad_tree_children(const rad_tree *t, int node, int *first);

#endif
