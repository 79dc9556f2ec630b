/* Shadows for direct light: one file per method behind one small interface.
 *
 *   a light  --gk_shadow_view_for_light-->  gk_shadow_view (how the light sees the scene: 1
 *   perspective face for spot lights with cones up to 60 degrees, 6 cube faces in the light's
 *   frame for point/sphere/rect/disc lights, 1 orthographic face for directional lights, plus the
 *   light's size for soft shadows)
 *   method->render(self, ctx, slot, view)   renders what the method needs for that light into its
 *                                           per-slot storage (maps persist between frames)
 *   method->bind(self, progs, slot, view, prog, unit, e)  binds it for the lighting program `prog`
 *                                           (from `progs`, which resolves its uniform locations)
 *   GLSL: the lighting pass is compiled with method->glsl_define and calls
 *         highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal)
 *         from shaders_gles/shadow/<method>.glsl (selected in shaders_gles/shadow/shadow.glsl).
 *
 * Methods: hard, pcss (brute force, the framework reference of dong-001.md §1.2). VSSM and CSSM
 * are added as shadow_vssm.c / shadow_cssm.c + shaders_gles/shadow/{vssm,cssm}.glsl, a line in
 * gk_shadow_methods[] (shadow_methods.c), the #elif in shadow.glsl, and the knob value in
 * renderer_knobs.c. The depth maps (shadow_depth.c) are shared: a method may use them as is
 * (hard, pcss) or derive its own data from them. */
#ifndef GK_SHADOW_H
#define GK_SHADOW_H

#include <stdbool.h>

#include "base/err.h"
#include "../../scene/scene.h"
#include "../../sched/budget.h"
#include "gl/gl.h"
#include "gl/gl_program.h"
#include "gl/pass.h"
#include "../scene_gpu.h"

#define GK_SHADOW_MAX_LIGHTS 40  /* per method: lights past this are unshadowed (8 of the scene's own +
                                    the environment's GK_ENV_MAX_LIGHTS = 32 split lights, CSSM) */
#define GK_SHADOW_MAX_FACES 6

typedef struct gk_shadow_view {
    int n_faces;                  /* 1 or 6 (cube faces +b0 -b0 +b1 -b1 +b2 -b2 of basis) */
    int skip_face;                /* a cube face not rendered (one-sided emitters' back), or -1 */
    vec3 basis[3];                /* the light's u (node X), v (node Y), dir (node -Z) */
    bool ortho;                   /* directional light */
    mat4 viewproj[GK_SHADOW_MAX_FACES];
    vec3 pos;                     /* light centre (ortho: the map's eye point) */
    vec3 axis;                    /* face axis of a 1-face map (the light's -Z) */
    float znear, zfar;            /* linear depth range along the face axis */
    float tan_half_fov;           /* perspective; ortho: half extent (m) */
    float size_u, size_v;         /* light size along map u, v (m); ortho: 2 tan(sun angular radius); 0: point */
    int map_size;                 /* texels per face side */
} gk_shadow_view;

/* What a method may use from the renderer while rendering its maps. */
typedef struct gk_shadow_ctx {
    gk_program_cache *progs;
    const gk_scene *scene;
    const gk_scene_gpu *gpu;
    const gk_gl_caps *caps;
    int subdiv;                   /* level of the knob shadow_subdiv (VSSM), resolved by the renderer */
    const gk_pass_ctx *pass;      /* the renderer's pass context: a method's sub-passes (depth maps,
                                     prefilters) nest under `shadow` on its clock; NULL in tests */
    const char *count_define;     /* the depth draws' counting variant (the bench's counting frame,
                                     app/render/render_work.c), NULL or "" in every other frame */
    struct gk_pf_frame_work *prefilter_work; /* where a prefilter adds its modelled fetches in that counting
                                     frame (shadow_prefilter_work.h), NULL in every other frame */
} gk_shadow_ctx;

typedef struct gk_shadow_method {
    const char *name;             /* knob value: "hard", "pcss" */
    const char *glsl_define;      /* prelude line(s) for the lighting pass: "#define SHADOW_PCSS 1\n" */
    /* The lighting pass draws each of the method's lights twice (render_split.c): "#define
       SHADOW_SPLIT 1" adds and stencil-marks the pixels with no light and those its GLSL's
       highp float shadow_settle(highp vec3 world_pos) settles (>= 0), then "2" draws the rest with
       shadow_visibility (direct/light.frag). false: one draw with shadow_visibility. */
    bool split;
    void *(*create)(void);
    void (*destroy)(void *self);
    int (*render)(void *self, const gk_shadow_ctx *ctx, int slot, const gk_shadow_view *v, gk_err *e);
    int (*bind)(void *self, gk_program_cache *progs, int slot, const gk_shadow_view *v, GLuint prog, int unit,
                gk_err *e);
} gk_shadow_method;

/* The methods, NULL-terminated (shadow_methods.c). */
extern const gk_shadow_method *const gk_shadow_methods[];
const gk_shadow_method *gk_shadow_method_find(const char *name);

/* Builds the view of the light on node `node` (after gk_scene_evaluate). Returns false for
 * lights that cast no shadow map (none at present). scene bounds set far planes and the
 * directional map's extent. */
bool gk_shadow_view_for_light(const gk_scene *s, int node, int map_size, gk_shadow_view *v);

/* Shared depth maps: a DEPTH_COMPONENT32F 2D array per slot (n_faces layers). */
typedef struct gk_shadow_maps {
    GLuint tex[GK_SHADOW_MAX_LIGHTS];
    int size[GK_SHADOW_MAX_LIGHTS], layers[GK_SHADOW_MAX_LIGHTS];
    GLuint fbo;
} gk_shadow_maps;

int gk_shadow_maps_render(gk_shadow_maps *m, const gk_shadow_ctx *ctx, int slot, const gk_shadow_view *v, gk_err *e);
/* Binds the slot's map on `unit` and sets the u_shadow_* uniforms of shaders_gles/shadow/common.glsl
 * in `prog` (a program of `progs`). Returns -1 with e filled when they do not resolve. */
int gk_shadow_maps_bind(const gk_shadow_maps *m, gk_program_cache *progs, int slot, const gk_shadow_view *v,
                        GLuint prog, int unit, gk_err *e);
void gk_shadow_maps_free(gk_shadow_maps *m);

#endif
