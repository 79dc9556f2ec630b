/* A small glTF 2.0 writer in C for the procedural scenes (build_*.c): JSON written by hand with a
 * fixed number format, one .bin buffer, so every build writes the same bytes. It writes only what
 * the builders need: triangle meshes (POSITION, NORMAL, optional TEXCOORD_0, u16/u32 indices),
 * metallic-roughness materials with the KHR emissive-strength/transmission/ior/specular extensions,
 * KHR_lights_punctual with gikiosk extras, perspective cameras, TRS nodes, linear/step animations
 * and the scene's gikiosk extras. */
#ifndef GK_GLTF_WRITE_H
#define GK_GLTF_WRITE_H

#include <stdbool.h>
#include <stdint.h>

#include "base/err.h"
#include "core/vecmath.h"

/* Triangle geometry under construction (build_geom.c fills it). */
typedef struct gkw_geom {
    float *pos, *nrm, *uv;     /* uv NULL unless geom.with_uv */
    uint32_t *idx;
    uint32_t nv, nt, cap_v, cap_t;
    bool with_uv;
} gkw_geom;

typedef struct gkw_material {
    const char *name;
    double base[4];            /* linear RGBA */
    double metallic, roughness;
    double emissive[3];        /* emissiveFactor (0..1) */
    double emissive_strength;  /* KHR_materials_emissive_strength (nits = factor * strength); 0: omitted */
    double transmission, ior;  /* written when transmission > 0 / ior != 0 */
    bool double_sided, light_proxy;
    const char *base_color_uri; /* image file next to the .gltf, or NULL */
    /* KHR_materials_specular, written when with_specular (specularFactor 0 = pure Lambert, as the
       Cornell box and the furnace are by definition); textures are not written. */
    bool with_specular;
    double specular, specular_color[3];
} gkw_material;

typedef struct gkw_light {
    const char *name;
    const char *type;          /* "point", "spot", "directional" */
    double color[3], intensity;
    double inner_cone, outer_cone;
    double radius;             /* extras gikiosk.radius, 0: none */
    double size[2];            /* extras gikiosk.size, 0: none */
} gkw_light;

typedef struct gkw_node {
    const char *name;
    int parent;                /* -1: a root of the scene */
    vec3 t; quat r; vec3 s;
    int mesh, light, camera;   /* -1: none */
} gkw_node;

typedef struct gkw_doc gkw_doc;

gkw_doc *gkw_new(const char *name);
void gkw_free(gkw_doc *d);
int gkw_add_material(gkw_doc *d, const gkw_material *m);
int gkw_add_mesh(gkw_doc *d, const char *name, const gkw_geom *g, int material);
int gkw_add_light(gkw_doc *d, const gkw_light *l);
int gkw_add_camera(gkw_doc *d, double yfov, double znear, double zfar);
/* A node with identity transform and nothing attached; fill the returned struct's fields. */
gkw_node *gkw_node_add(gkw_doc *d, const char *name, int *index_out);
/* path: "translation", "rotation", "scale"; interp: "LINEAR" or "STEP"; values n*3 or n*4. */
int gkw_add_channel(gkw_doc *d, int node, const char *path, const char *interp, int n, const float *times,
                const float *values);
void gkw_description(gkw_doc *d, const char *description, const char *methods);
void gkw_exposure(gkw_doc *d, double ev);
/* The scene medium in extras.gikiosk.medium (scene.h, gk_medium), filling all space. */
void gkw_medium(gkw_doc *d, const double sigma_s[3], const double sigma_a[3], double g);
/* ... limited to the box [lo, hi] (extras.gikiosk.medium.bounds). */
void gkw_medium_bounds(gkw_doc *d, const double lo[3], const double hi[3]);
/* The scene environment in extras.gikiosk.environment (scene.h, gk_environment): an image next to
   the scene file, written by the builder itself. */
void gkw_environment(gkw_doc *d, const char *uri, double intensity);
/* A named number list in extras.gikiosk.params (up to 4 values). */
void gkw_param(gkw_doc *d, const char *key, int n, const double *v);
/* Writes DIR/NAME.gltf and DIR/NAME.bin. */
int gkw_write(gkw_doc *d, const char *dir, gk_err *e);

#endif
