/* One interface for every GI method (DESIGN §5). A method adds indirect light on top of the
 * renderer's direct light; it reads the G-buffer, the shadow maps and the scene through the
 * renderer and never calls another method. The scheduler sees a method only through its knobs and
 * its measured pass times.
 *
 * Life cycle: applies() -> create() -> set_scene() -> [render() per frame]* -> destroy().
 * Budgets change between frames: render() reads the knob values it needs from frame->budget each
 * frame and reallocates lazily when a size knob changed. */
#ifndef GK_GI_H
#define GK_GI_H

#include <stdbool.h>

#include "base/err.h"
#include "../core/vecmath.h"
#include "../scene/scene.h"
#include "../sched/budget.h"
#include "gl/gbuffer_bind.h"
#include "gl/pass.h"
#include "gl/pass_work.h"

/* What the renderer lends a method for its whole life. */
typedef struct gk_gi_context {
    gk_program_cache *programs;  /* load shaders by path under shaders_gles/ (app/gl/gl_program.h) */
    int gles_version;            /* 31: portable path only; 32: capability-checked fast paths allowed */
    int cpu_workers;             /* worker threads a method may run on the CPU ([cpu] workers of the
                                    config); 0: its default (cores - 1) */
} gk_gi_context;

/* For a method made without the renderer (tests, tools): when ctx has no program cache, creates one
 * at ctx's GLES version (31 when unset) and puts it in ctx. Returns the cache the method then owns
 * and destroys, or NULL when ctx already had one. */
gk_program_cache *gk_gi_context_own_programs(gk_gi_context *ctx);

/* One light as the renderer sees it this frame, with its shadow map (for light injection,
 * reflective shadow maps and visibility). */
typedef struct gk_gi_light {
    int scene_light;             /* index into scene->lights */
    int node;                    /* node carrying the light */
    vec3 position, direction;    /* world; direction = emission axis (-Z of the node) */
    vec3 axis_u, axis_v;         /* rectangle axes (unit) */
    vec3 radiant;                /* colour * intensity */
    unsigned shadow_depth_tex;   /* depth texture (2D) of the light's shadow map, 0 if none */
    mat4 shadow_view_proj;       /* world -> shadow clip space for shadow_depth_tex */
    bool shadow_is_perspective;
    float shadow_near, shadow_far;
} gk_gi_light;

/* Everything a method needs for one frame. Textures are GL names; sizes in pixels. */
typedef struct gk_gi_frame {
    /* The renderer's pass context: the one clock (a method marks each of its passes with
       gk_pass_begin/gk_pass_end; they nest under the renderer's `gi` pass in the frame report and
       the method never times itself), programs, capabilities, knobs. NULL when a test drives a
       method without a renderer: the passes then run untimed. */
    const gk_pass_ctx *pass;
    const gk_scene *scene;       /* evaluated at time_s (node world matrices valid) */
    double time_s;
    bool scene_changed;          /* first frame of a new scene or geometry moved (dirty regions) */
    int width, height;           /* internal render size (after render_scale) */
    mat4 view, proj, view_proj, inv_view_proj;
    vec3 eye;
    /* The renderer's G-buffer (app/render/render_frame.c), at width x height:
       gbuf_depth    DEPTH_COMPONENT32F window depth of proj (reconstruct world position with
                     inv_view_proj: ndc = (uv, depth) * 2 - 1);
       gbuf_albedo   RGBA8: base colour rgb, a = METALLIC;
       gbuf_normal   RGBA16F: world normal xyz (unit), w = ROUGHNESS;
       gbuf_emission RGBA16F: emitted radiance rgb (nits);
       gbuf_specular RGBA8: KHR_materials_specular, rgb = sqrt(c0) (the dielectric F0 colour,
                     brdf_spec.md), a = SPECULAR WEIGHT (0: pure Lambert);
       gbuf_geom_normal RGBA16F: xyz = the GEOMETRIC normal (before the normal map), facing the
                     viewer; 0 when the driver has no 5th draw buffer or a test leaves it out: then
                     gbuf_normal stands in (gk_gbuffer_bind_geom_normal). */
    unsigned gbuf_depth;
    unsigned gbuf_normal;
    unsigned gbuf_albedo;
    unsigned gbuf_emission;
    unsigned gbuf_specular;
    unsigned gbuf_geom_normal;
    unsigned direct_tex;         /* RGBA16F: direct light (linear, before exposure) */
    unsigned hdr_fbo;            /* FBO whose colour attachment 0 is the HDR image the method adds to
                                    (additive blending is the method's job: glBlendFunc(ONE, ONE)) */
    int n_lights;
    const gk_gi_light *lights;
    const gk_budget *budget;
    /* Draws every mesh of the scene with `program` (bound, and from gk_gi_context.programs); sets
       the uniform `u_model` (mat4) per node and `u_base_color` (vec4), `u_emissive` (vec3),
       `u_metallic_roughness` (vec2), `u_mat_flags` (int), `u_specular` (vec4, scene_gpu.h) per
       material: the program's source must declare all six (the compiler may drop the ones it does not use). Returns -1 with e filled
       when it does not. A program that also declares `u_glass` (vec2) gets (KHR_materials_ior's ior,
       KHR_materials_transmission's factor) per material, and one that declares `u_node_mesh` (ivec2)
       the (node, mesh) indices of each draw. One that includes common/alpha_mask.glsl
       gets what its alphaMode MASK test reads (u_base_tex on unit 0, u_alpha_cutoff, u_tex_xf,
       u_tex_uv1). Attribute locations: 0 position, 1 normal, 2 uv, 3 COLOR_0, 5 TEXCOORD_1. */
    int (*draw_scene)(void *draw_ctx, unsigned program, gk_err *e);
    void *draw_ctx;
    /* The bench's counting frame (#21, gk_gi_method.pass_work): passes whose work depends on the
       data run their counting variants (atomic adds: never in a timed frame). */
    bool count_work;
} gk_gi_frame;

typedef struct gk_gi_method {
    const char *name;                                      /* "vct", "vpl", ... */
    bool (*applies)(const gk_scene *s);                    /* does this scene need it */
    void (*declare_knobs)(gk_budget *b);                   /* knobs with cost priors */
    void *(*create)(const gk_gi_context *ctx, gk_err *e);
    int (*set_scene)(void *self, const gk_scene *s, gk_err *e);  /* static data (voxelize once...) */
    int (*render)(void *self, const gk_gi_frame *f, gk_err *e);
    /* Bytes of GPU memory held at the current budget (reported and asserted in tests). */
    long (*memory_bytes)(const void *self);
    /* Optional: a soft-shadow mask for light `light` (an index into f->lights) traced through the
       method's own scene representation, for the renderer's direct pass to multiply in instead of
       its shadow maps (vct: the shadow cone, knob vct_shadow). Called after the G-buffer pass and
       before the direct pass, so the method brings what it traces through up to date for this
       frame first (the later render() then finds it done). *tex: a texture of f->width x
       f->height whose red channel is the visibility per G-buffer pixel, or 0 when the method does
       not shadow this light this frame (the shadow maps stay). Returns -1 with e filled on failure. */
    int (*shadow_mask)(void *self, const gk_gi_frame *f, int light, unsigned *tex, gk_err *e);
    /* With shadow_mask: whether budget b asks the method for masks at all. Only then does the
       renderer make the method ready before the direct pass (its set-up stays in the gi pass else). */
    bool (*wants_shadow_mask)(const gk_budget *b);
    /* Optional: forget the work cached between frames (vct: voxels and injected light), so the next
       render redoes it; the bench's --rebuild-gi times those passes with it. */
    void (*invalidate)(void *self);
    /* Optional (the bench's efficiency, #21): the useful fetches of the last frame's passes
       (app/gl/pass_work.h); up to max entries, returns how many. It may read GPU counters back (a
       stall), so only the bench calls it, after a frame. */
    int (*pass_work)(void *self, gk_pass_work *out, int max);
    void (*destroy)(void *self);
} gk_gi_method;

/* The registry of implemented methods (app/gi/gi_registry.c). */
const gk_gi_method *const *gk_gi_methods(int *count);
const gk_gi_method *gk_gi_find(const char *name);

/* The frame's G-buffer for gk_gbuffer_bind (app/gl/gbuffer_bind.h; the GLSL side is
 * shaders_gles/common/gbuffer.glsl). */
static inline gk_gbuffer_view gk_gi_gbuffer(const gk_gi_frame *f)
{
    return (gk_gbuffer_view){.albedo = f->gbuf_albedo, .normal = f->gbuf_normal, .emission = f->gbuf_emission,
                             .depth = f->gbuf_depth, .specular = f->gbuf_specular,
                             .geom_normal = f->gbuf_geom_normal, .width = f->width, .height = f->height, .view = f->view,
                             .proj = f->proj, .view_proj = f->view_proj, .inv_view_proj = f->inv_view_proj,
                             .eye = f->eye};
}

#endif
