/* Geometry helpers for the procedural scene builders: quads, boxes, cylinders and grids appended
 * to a gkw_geom, plus the rotations the builders need for lights and cameras. */
#ifndef GK_BUILD_GEOM_H
#define GK_BUILD_GEOM_H

#include "scene/gltf_write.h"

void gkb_free(gkw_geom *g);
/* Appends a vertex; returns its index. */
uint32_t gkb_vertex(gkw_geom *g, vec3 p, vec3 n, float u, float v);
void gkb_tri(gkw_geom *g, uint32_t a, uint32_t b, uint32_t c);
/* A planar quad a-b-c-d (in order around its edge), flat-shaded, wound so that its normal points
 * along `facing` (the order given does not matter). */
void gkb_quad(gkw_geom *g, vec3 a, vec3 b, vec3 c, vec3 d, vec3 facing);
/* A flat-shaded triangle wound so that its normal points along `facing`. */
void gkb_triangle(gkw_geom *g, vec3 a, vec3 b, vec3 c, vec3 facing);
/* The same quad split into nu x nv cells (for light maps and per-vertex lighting). */
void gkb_quad_grid(gkw_geom *g, vec3 a, vec3 b, vec3 c, vec3 d, vec3 facing, int nu, int nv);
/* Axis-aligned box; inward = true gives the inside faces (a room), else the outside. */
void gkb_box(gkw_geom *g, vec3 lo, vec3 hi, bool inward);
/* Open cylinder around +Y from y0 to y1, smooth normals (outward, or inward), `seg` sides. */
void gkb_cylinder(gkw_geom *g, vec3 base, float radius, float y0, float y1, int seg, int stacks, bool inward);
/* Flat annulus facing up at height y between radii r0 < r1. */
/* A closed UV sphere with smooth normals: seg segments around y, rings bands from pole to pole
   (poles are single vertices, so no triangle is degenerate), wound outwards. */
void gkb_sphere(gkw_geom *g, vec3 centre, float radius, int seg, int rings);
void gkb_annulus(gkw_geom *g, vec3 centre, float y, float r0, float r1, int seg);

/* The rotation that turns the node's -Z to `forward` and its +Y as close as possible to `up`. */
quat gkb_look_rotation(vec3 forward, vec3 up);
quat gkb_axis_angle(vec3 axis, float radians);

/* Adds g as a mesh with the material and a root node drawing it (identity transform), then frees
 * g. Returns the node index. */
int gkb_object(gkw_doc *d, const char *name, gkw_geom *g, int material);
/* Adds a light node at pos whose -Z looks along dir; returns the node index. */
int gkb_light_node(gkw_doc *d, const gkw_light *l, vec3 pos, vec3 dir, vec3 up);
/* Adds a perspective camera node at eye looking at target; returns the node index. */
int gkb_camera_node(gkw_doc *d, vec3 eye, vec3 target, double yfov, double znear, double zfar);

/* The scene builders (build_*.c): each writes DIR/NAME.gltf + .bin. */
typedef struct gk_scene_builder {
    const char *name;
    int (*build)(const char *dir, gk_err *e);
} gk_scene_builder;
extern const gk_scene_builder gk_scene_builders[];
extern const int gk_n_scene_builders;

int gk_build_cornell(const char *dir, gk_err *e);
int gk_build_cornell_spot(const char *dir, gk_err *e);
int gk_build_cornell_spot_anim(const char *dir, gk_err *e);
int gk_build_shadow_planes(const char *dir, gk_err *e);
int gk_build_shadow_planes_stacked(const char *dir, gk_err *e);
int gk_build_light_leak(const char *dir, gk_err *e);
int gk_build_caustic_ring(const char *dir, gk_err *e);
int gk_build_caustic_ring_fog(const char *dir, gk_err *e);
int gk_build_atrium(const char *dir, gk_err *e);
int gk_build_furnace(const char *dir, gk_err *e);
int gk_build_glass(const char *dir, gk_err *e);
int gk_build_env_studio(const char *dir, gk_err *e);
int gk_build_glass_fog(const char *dir, gk_err *e);

#endif
