/* The radiosity of one scene at one setting, and its bounces on the CPU.
 *
 * rad_geometry bundles what the worker builds once per scene and setting (mesh, hierarchy, links,
 * per-leaf albedo and emission) -- what the GPU passes upload. rad_solve_cpu runs the same bounces
 * as the GPU passes (shaders_gles/radiosity/): the tests' oracle for them and the furnace series
 * without a GPU.
 *
 * Bounces [doc, Algorithm 1 steps 5-6]: every node holds the radiance it has not yet shot,
 * starting from B0 = Le + ρ/π E_direct at the leaves (rad_direct.h), pulled up the tree. A bounce:
 *   ComputeIlluminateLeafNodes  E_k(leaf)    = Σ_links w · unshot(target)     (rad_links.h: w)
 *                               E_ind(leaf) += E_k
 *                               unshot(leaf) = ρ/π · E_k
 *   PullupEnergy                unshot(parent) = Σ_children unshot(child) · A_child / A_parent,
 *                               one level at a time, leaves up.
 * E_ind (irradiance) is what the display adds, through the pixel's diffuse BRDF: the renderer
 * already draws direct light and emission. */
#ifndef GK_RAD_SOLVE_H
#define GK_RAD_SOLVE_H

#include "rad_links.h"

typedef struct rad_geometry {
    rad_mesh mesh;
    rad_tree tree;
    rad_links links;
    float *albedo;     /* 3 per leaf: the diffuse albedo ρ (base colour x (1 - metallic)) */
    float *emission;   /* 3 per leaf: Le (nits), light proxies excluded (not in the mesh) */
    float edge;
    int n_face;
    rad_weight weight;
    uint64_t links_id;   /* which link set it carries (the worker numbers them; the GPU re-uploads the
                            links only when it changes, the vertices when the geometry does) */
} rad_geometry;

/* s: evaluated. Errors as rad_mesh_build (input: too many vertices) and out of memory. */
int rad_geometry_build(rad_geometry *g, const gk_scene *s, float edge, int max_verts, int n_face, rad_weight weight,
                       gk_err *e);
/* The same over a scene cut along its walls (rad_mesh_build_regions). */
int rad_geometry_build_regions(rad_geometry *g, const gk_scene *s, const gk_wall_regions *regions, float edge,
                               int max_verts, int n_face, rad_weight weight, gk_err *e);
void rad_geometry_free(rad_geometry *g);
/* A deep copy (the worker refits a copy while the frame reads the published one). -1: out of memory. */
int rad_geometry_clone(rad_geometry *dst, const rad_geometry *src);
/* UpdateElements [doc, Algorithm 1 step 1]: the animated charts to the pose of `worlds` (the scene's
 * node world matrices), then the hierarchy bottom up (rad_mesh_refit, rad_tree_refit). Returns the
 * number of charts that moved. */
int rad_geometry_refit(rad_geometry *g, const mat4 *worlds, int n_worlds);
/* The links at the current pose, the static pairs from `cache` (rad_links_update; NULL: every pair
 * linked anew). */
int rad_geometry_relink(rad_geometry *g, rad_link_cache *cache, gk_err *e);
/* Charts that move (animated nodes) in g. */
int rad_geometry_moving_charts(const rad_geometry *g);

/* Fills the inner nodes of v (3 floats per node) from its leaves by area ratio. */
void rad_pullup(const rad_tree *t, float *v);
/* B0 for every node (3 per node): Le + ρ/π E_direct at the leaves, pulled up. e_direct: 3 per leaf. */
void rad_initial_radiance(const rad_geometry *g, const float *e_direct, float *b0);
/* `bounces` bounces from b0 (3 per node); E_ind (3 per leaf) into e_ind. Returns -1 when out of
 * memory. */
int rad_solve_cpu(const rad_geometry *g, const float *b0, int bounces, float *e_ind);

#endif
