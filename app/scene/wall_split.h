/* Walls split the surfaces they stand on (seed 004 partitions surfaces by hand; M9; issue 16's
 * light-leak): lightmap's automatic charts (gi/lightmap/lm_atlas.h) are the planar parts of a mesh,
 * so a floor that runs under a thin wall from one room into the next is one chart, its photon map
 * gathers the lit room's photons for the dark room's texels, and a texel straddles the wall;
 * radiosity's refined mesh (gi/radiosity/rad_mesh.h) has elements that straddle the wall, and their
 * vertices' radiance is interpolated across it (issue 11). Both methods cut their own copy of the
 * scene with this, which is why it lives here and not in either method.
 *
 * Before the atlas (or the radiosity mesh) is built, every surface (the triangles of a mesh in one plane) is cut along the
 * plane of each triangle that stands on it and crosses it from border to border: a triangle about
 * perpendicular to the surface (within 3 degrees) with an edge lying in the surface's plane that
 * spans the surface's whole extent along that edge (light-leak's 2 cm wall: its sides cut the
 * floor, the ceiling and the two long walls into the two rooms and the strip under the wall). A
 * box standing on a floor does not cross it and cuts nothing, so the Cornell box keeps its charts.
 * The cut triangles' new vertices interpolate every attribute. Only meshes that one node draws are
 * cut (a shared mesh has one geometry for every placement), and the mesh is the method's own copy
 * of the scene (the tracer and the atlas, or the radiosity mesh and its shadow rays, read it, so
 * they agree). */
#ifndef GK_WALL_SPLIT_H
#define GK_WALL_SPLIT_H

#include "base/err.h"
#include "scene/scene.h"

/* Which side of each cut a triangle lies on: per mesh (NULL where nothing was cut), per triangle, a
 * bit per cut of its mesh (set: the cut plane's front). The atlas and the radiosity mesh keep
 * triangles of different labels in different charts (the pieces of a cut surface stay one plane). */
typedef struct gk_wall_regions {
    uint32_t **tri;
    int n_meshes;
} gk_wall_regions;

/* Cuts s's surfaces along the walls standing across them (s evaluated: node world matrices valid)
 * and labels the pieces in r. Returns the number of cuts made (>= 0) or -1 with e filled. */
int gk_split_walls(gk_scene *s, gk_wall_regions *r, gk_err *e);
void gk_wall_regions_free(gk_wall_regions *r);

#endif
