/* The one GL/EGL fixture of the GPU tests (tests/gpu/): an EGL surfaceless GLES context set up
 * through platform/egl.h as the mock platform does, offscreen framebuffers (gk_target), the
 * tests' shader root (shaders_gles/ and tests/shaders/ side by side, so test-only shaders can
 * #include the production ones), and in-memory scenes built with the scene builders' own geometry
 * and rotation helpers (app/scene/build_geom.h): no glTF file, so a test pins exactly the
 * geometry its analytic answer assumes. Compiled into every unit and gpu test (TESTLIB_SRCS). */
#ifndef GK_TEST_GL_FIXTURE_H
#define GK_TEST_GL_FIXTURE_H

#include <stdbool.h>

#include "gl/gl.h"
#include "gl/gl_program.h"
#include "gl/gl_target.h"
#include "platform/egl.h"
#include "scene/build_geom.h"
#include "scene/scene.h"

/* ---- context ------------------------------------------------------------------------------- */
typedef struct gkt_gl {
    gk_egl egl; /* egl.gles_version: 31 or 32, the context obtained (3.2 asked, 3.1 accepted) */
} gkt_gl;

/* Opens the surfaceless display and makes a context current; prints why not and returns -1. */
int gkt_gl_open(gkt_gl *g);
void gkt_gl_close(gkt_gl *g);

/* ---- offscreen framebuffers ------------------------------------------------------------------ */
/* gk_target_create with NEAREST filtering; prints why not and returns -1. */
int gkt_target(gk_target *t, const char *what, int w, int h, int n_color, const GLenum *formats, bool depth);
/* Reads colour attachment `attachment` of t as RGBA of `type` (GL_FLOAT or GL_UNSIGNED_BYTE). */
void gkt_read_rgba(const gk_target *t, int attachment, GLenum type, void *out);

/* ---- shaders --------------------------------------------------------------------------------- */
/* The directory the GPU tests load shaders from: a copy of shaders_gles/ with tests/shaders/ laid
 * over it (made by the Makefile next to the test binaries; GK_TEST_SHADER_DIR overrides). */
const char *gkt_shader_dir(void);
/* A program cache over gkt_shader_dir() (gles 31 or 32: the #version written). */
gk_program_cache *gkt_programs(int gles);

/* ---- a shipped scene for the renderer ----------------------------------------------------------- */
typedef struct gkt_shipped {
    gkt_gl gl;
    gk_target fb;       /* RGBA8, the size asked */
    gk_scene *scene;    /* loaded from a glTF file (config/scenes/...) */
} gkt_shipped;

/* Opens the context, a w x h RGBA8 framebuffer and the scene at gltf; prints why not and returns -1. */
int gkt_shipped_open(gkt_shipped *t, const char *gltf, int w, int h);
void gkt_shipped_close(gkt_shipped *t);

/* ---- scenes ---------------------------------------------------------------------------------- */
#define GKT_MAX_MESH 64
#define GKT_MAX_LIGHT 8
#define GKT_MAX_NODE (GKT_MAX_MESH + GKT_MAX_LIGHT + 1)

typedef struct gkt_scene {
    gk_scene s;
    gk_mesh meshes[GKT_MAX_MESH];
    gkw_geom geom[GKT_MAX_MESH]; /* the meshes' vertex data */
    gk_material mats[GKT_MAX_MESH];
    gk_light lights[GKT_MAX_LIGHT];
    gk_node nodes[GKT_MAX_NODE];
    gk_camera cam;
} gkt_scene;

/* An empty scene without camera (camera_node -1). */
void gkt_scene_init(gkt_scene *t, const char *name);
void gkt_scene_free(gkt_scene *t);
/* A material without textures (ior 1.5); returns its index. */
int gkt_material(gkt_scene *t, vec3 base, float metallic, float roughness);
/* A Lambertian material (KHR_materials_specular specularFactor 0, roughness 1): albedo exactly
 * base, as analytic answers of the form rho / pi E assume. */
int gkt_material_lambert(gkt_scene *t, vec3 base);
/* Adds g as a mesh with a root node drawing it (identity transform and world matrix); the scene
 * takes g's arrays (g is left empty). Returns the node index. */
int gkt_object(gkt_scene *t, gkw_geom *g, int material);
/* One planar quad a-b-c-d as an object (gkb_quad: wound and shaded to face `facing`). */
int gkt_quad(gkt_scene *t, vec3 a, vec3 b, vec3 c, vec3 d, vec3 facing, int material);
/* The rotation turning -Z to dir with +Y towards world +y (towards -z when dir is near vertical). */
quat gkt_look_rotation(vec3 dir);
/* A perspective camera node at eye looking at target (aspect from the render size). */
void gkt_camera(gkt_scene *t, vec3 eye, vec3 target, float yfov);
/* A light node at pos whose -Z looks along dir; white, cone 45 degrees. */
gk_light *gkt_light(gkt_scene *t, enum gk_light_type type, enum gk_light_shape shape, float intensity, vec3 pos,
                    vec3 dir);
/* Bounds and triangle count from the mesh nodes' world matrices. */
void gkt_scene_bounds(gkt_scene *t);

#endif
