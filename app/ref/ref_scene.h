/* The reference path tracer's own flattened view of a gk_scene at one instant: world-space
 * triangles in a BVH, analytic area lights, delta lights, emissive triangles as one mesh light,
 * and the pinhole camera of gk_scene_camera (rays through pixel centres, as the rasterizer samples).
 *
 * Light semantics follow scene.h (binding): radius/size turn point and spot lights into sphere,
 * disc (masked by the spot cone) or one-sided rectangle emitters with radiance I/(pi R^2) or
 * I/(W H); light_proxy meshes are skipped because their area light stands in for them; a
 * directional light with radius R > 0 is a sun disc of angular radius R. Area-light geometry is
 * opaque and black apart from its emission: rays that hit it stop there. */
#ifndef GK_REF_SCENE_H
#define GK_REF_SCENE_H

#include <stdbool.h>
#include <stdint.h>

#include "bvh.h"
#include "medium.h"
#include "ref_env.h"
#include "scene/scene.h"

enum gk_ref_light_kind {
    GK_REF_POINT, GK_REF_SPOT, GK_REF_DIRECTIONAL, /* deltas: only light sampling or light tracing finds them */
    GK_REF_SUN, GK_REF_SPHERE, GK_REF_DISC, GK_REF_RECT, GK_REF_MESH,
    GK_REF_ENV         /* the scene's environment map (ref_env.h), at infinity like a sun */
};

typedef struct gk_ref_light {
    enum gk_ref_light_kind kind;
    vec3 pos;          /* centre */
    vec3 axis;         /* emission direction: the node's -Z (directional: direction light travels) */
    vec3 u, v;         /* rectangle axes (unit) */
    vec3 intensity;    /* colour * intensity: cd (point/spot/area) or lux (directional/sun) */
    vec3 radiance;     /* area lights and sun: emitted radiance (on the axis for a masked disc) */
    float radius, half_w, half_h, area;
    float range;       /* 0 = infinite */
    float cos_inner, cos_outer;
    bool spot_mask;    /* spot and disc-from-spot: directional cone falloff */
    float sun_cos_max; /* sun: cos of the angular radius */
    float power;       /* luminance power, for choosing lights in proportion */
} gk_ref_light;

typedef struct gk_ref_tri {
    vec3 p[3], n[3];
    float uv[3][2];
    float uv1[3][2];   /* TEXCOORD_1 per corner; TEXCOORD_0's without one (as the G-buffer binds it) */
    float color[3][4]; /* COLOR_0 per corner, white without one */
    float tangent[3][4]; /* world-space tangent xyz + handedness w per corner; zero without one */
    vec3 ng;           /* unit geometric normal (front face by winding) */
    float area;
    int material;
    int emissive;      /* index into the emissive list, -1 if not emissive */
} gk_ref_tri;

typedef struct gk_ref_scene {
    gk_ref_tri *tris;
    uint32_t n_tris;
    gk_bvh bvh;
    uint8_t *alpha_tested;  /* per triangle: its material is alpha-masked (the BVH's any-hit test), or NULL */
    const gk_material *materials; int n_materials; /* borrowed from the gk_scene */
    const gk_texture *textures; int n_textures;
    gk_ref_light *lights; int n_lights;
    float *light_cdf;      /* n_lights + 1, by power: next-event estimation picks one light */
    float *delta_cdf;      /* n_lights + 1, over delta lights only: light tracing picks one */
    uint32_t *emissive_tris; float *emissive_cdf; int n_emissive; /* the mesh light's triangles */
    int mesh_light;        /* index of the GK_REF_MESH light or -1 */
    gk_ref_env env;        /* the environment's sampling tables; env.env NULL without one */
    int env_light;         /* index of the GK_REF_ENV light or -1 (the scene's env_part lights, the
                              rasterizer's split of the same map, are not lights here) */
    bool has_delta_lights, has_delta_surfaces;
    /* Test hook (white-furnace tests of the transport): every surface pure Lambert (metallic,
       transmission and the KHR_materials_specular weight 0), so a surface's albedo is exactly its
       base colour and a closed box has a closed-form answer, whatever the materials say. */
    bool diffuse_only;
    vec3 centre;
    float radius;          /* bounding sphere of the geometry */
    gk_ref_medium medium;  /* the scene's participating medium (medium.h); present = false: vacuum */
    /* camera */
    int width, height;
    vec3 eye, right, up, fwd;
    float tan_x, tan_y;    /* half extents of the image plane at distance 1 */
} gk_ref_scene;

/* Flattens s, which the caller has evaluated (gk_scene_evaluate) at the wanted time; view/proj/eye
 * come from gk_scene_camera for the image's aspect. s must outlive rs (materials are borrowed). */
int gk_ref_scene_build(gk_ref_scene *rs, const gk_scene *s, mat4 view, mat4 proj, vec3 eye,
                       int width, int height, gk_err *e);
void gk_ref_scene_free(gk_ref_scene *rs);

/* True when a surface of this material can have a delta lobe somewhere (mirror: metallic > 0.5 and
 * roughness < 0.05; smooth dielectric: transmission > 0 and roughness < 0.05, as materials.h). */
bool gk_ref_material_may_be_delta(const gk_material *mt);

/* Primary ray through the centre of pixel (x, y), y = 0 at the top. */
vec3 gk_ref_camera_dir(const gk_ref_scene *rs, float px, float py);

#endif
