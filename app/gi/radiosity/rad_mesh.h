/* The radiosity method's geometry (seed 001 ch. 4; research dong-001.md §2.2): the scene's drawn,
 * non-proxy triangles in world space at the pose the method was built with, refined to a target
 * edge length, grouped into charts, with one surfel (vertex disc) per welded vertex.
 *
 * Tessellation [ours, documented in the README]: the technique needs vertices where light changes
 * (research 2.4: 792 vertices leak, ~2.5k-5k are fine), and scenes such as cornell are too coarse
 * (a wall is one quad). Every source triangle is cut into n² similar triangles, n = ceil(longest
 * edge / target edge), by the uniform barycentric grid. Triangles of one regular grid (a quad's two
 * halves, the furnace's 4x4 faces) get the same n, so their shared edges get the same vertices and
 * weld; where neighbours differ in size a T-junction remains (the display may show a hairline there;
 * the radiosity itself only sees vertices).
 *
 * Charts [ours: the seed uses the artists' UV segments, which our scenes do not have]: connected
 * regions of coplanar triangles (face normals within 1°, sharing an edge, one material, one scene node). Each chart
 * has its own vertices (a room's corner has one vertex per wall), so a surfel has one normal and one
 * albedo. Within a chart the vertices are sorted in Morton (Z) order of their plane coordinates,
 * which is what lets the quadtree group them four by four (rad_tree.h).
 *
 * Surfels [doc, after Bunnell 2005]: a vertex's disc has the vertex's position, the chart's normal
 * and 1/3 of the area of the refined triangles that share it (so the areas sum to the surface's).
 * The disc sits at the centroid of that area [ours]: inside a chart it is the vertex itself (on a
 * regular grid exactly), on a chart's border it moves half a triangle inwards. At the vertex, a
 * border surfel would lie in the plane of the neighbouring chart (a room's corner), which it then
 * sees exactly edge-on: measured on the furnace (1,014 vertices, 6x8²) the border surfels gathered
 * from 12% of their hemisphere. */
#ifndef GK_RAD_MESH_H
#define GK_RAD_MESH_H

#include <stdbool.h>
#include <stdint.h>

#include "base/err.h"
#include "core/vecmath.h"
#include "scene/scene.h"
#include "scene/wall_split.h"

typedef struct rad_chart {
    vec3 normal;            /* unit, world, at the pose of the last refit */
    vec3 tu, tv;            /* plane axes (unit) at the build pose, for the Morton order */
    int first_vert, n_verts;/* its vertices: a contiguous range, in Morton order */
    int material;
    int node;               /* the scene node drawing it (charts never span nodes: each moves rigidly) */
    bool moving;            /* its node is animated (scene.h): refit every frame */
    vec3 rest_normal;       /* the normal at the build pose */
    mat4 pose;              /* world now x world at build, as of the last refit (identity: built) */
    bool refit_moved;       /* the last refit moved it */
} rad_chart;

typedef struct rad_mesh {
    int n_verts;
    vec3 *pos;              /* world, at the pose the mesh was built with */
    float *area;            /* surfel area: 1/3 of the adjacent refined triangles' area */
    vec3 *centre;           /* the surfel's centre: the centroid of that area (see below) */
    int *chart;             /* per vertex */
    int n_tris;
    uint32_t *tris;         /* 3 per refined triangle, into the vertices */
    int n_charts;
    rad_chart *charts;
    int n_source_tris;      /* triangles of the scene taken (drawn, not light proxies) */
    float edge;             /* target edge length used (world units) */
    double surface_area;    /* sum of the source triangles' areas */
    /* the build ("rest") pose, which every refit starts from, so frames never accumulate drift */
    vec3 *rest_pos, *rest_centre;
    int n_scene_nodes;
    mat4 *rest_world_inv;   /* per scene node: the inverse of its world matrix at build */
} rad_mesh;

/* Builds the refined mesh of scene s (evaluated: node world matrices valid). edge > 0 is the target
 * edge length. max_verts bounds the result: a scene whose refinement would exceed it is a GK_EINPUT
 * error naming the scene and the count (a coarser edge fits). */
int rad_mesh_build(rad_mesh *m, const gk_scene *s, float edge, int max_verts, gk_err *e);
/* The same where walls cut s's surfaces (scene/wall_split.h; regions NULL: none): triangles of
 * different labels go to different charts, so no element straddles a wall and no vertex's radiance
 * is interpolated across one. */
int rad_mesh_build_regions(rad_mesh *m, const gk_scene *s, const gk_wall_regions *regions, float edge, int max_verts,
                           gk_err *e);
void rad_mesh_free(rad_mesh *m);

/* UpdateElements' first half [doc, Algorithm 1 step 1]: moves the vertices, surfel centres and chart
 * normals of every chart whose node is animated to the pose of `worlds` (the scene's node world
 * matrices, n_worlds of them), from the rest pose by world_now x world_at_build^-1 (normals by its
 * inverse transpose). Surfel areas stay (the seed: area "varies very little"; under a node's scale
 * animation they are those of the rest pose). Sets each chart's refit_moved; returns how many moved. */
int rad_mesh_refit(rad_mesh *m, const mat4 *worlds, int n_worlds);

/* The number of segments a triangle edge of length `len` is cut into for target edge `edge`
 * (exposed for the tests: the refinement rule in one place). */
int rad_mesh_segments(float len, float edge);

#endif
