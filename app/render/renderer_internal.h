/* The renderer's state, shared by renderer.c (lifetime, scene, knobs), render_frame.c (the passes)
 * and render_capture.c. Not part of the public API. */
#ifndef GK_RENDERER_INTERNAL_H
#define GK_RENDERER_INTERNAL_H

#include "gl/gl_counters.h"
#include "gl/gl.h"
#include "gl/gl_program.h"
#include "gl/gl_target.h"
#include "gl/gl_timing.h"
#include "renderer.h"
#include "scene_gpu.h"
#include "shadow/shadow.h"
#include "shadow/shadow_prefilter_work.h"

#define GK_MAX_SHADOW_METHODS 16 /* entries of gk_shadow_methods[]; a static assert in shadow_methods.c keeps them in step */

/* Texture units of the lighting passes. */
enum { UNIT_ALBEDO = 0, UNIT_NORMAL = 1, UNIT_EMISSION = 2, UNIT_DEPTH = 3, UNIT_SPECULAR = 4, UNIT_SHADOW = 5,
       UNIT_GEOM_NORMAL = 14, /* after every shadow method's (CSSM, the most, ends at 5 + 8) */
       UNIT_LTC = 15 /* the last unit GLES 3.1 guarantees a fragment shader: after every shadow method's */ };

/* The renderer's knobs, read each frame through handles (no names in the frame loop). */
typedef struct gk_render_knobs {
    gk_knob scale, shadow, shadow_map, shadow_subdiv, gi_blend;
    gk_knob env_lights;
    const gk_shadow_method *shadow_of_level[GK_MAX_KNOB_VALUES]; /* knob `shadow` level -> method */
    const gk_knob_def *shadow_table_def; /* the definition shadow_of_level was built from */
    const gk_shadow_method *shadow_without_budget;               /* PCSS, the framework reference */
} gk_render_knobs;

/* The renderer's knob values for one frame. */
typedef struct gk_frame_knobs {
    float render_scale;
    const gk_shadow_method *shadow;
    int shadow_map;
    int shadow_subdiv;          /* level of shadow_subdiv (VSSM) */
    int gi_blend;               /* frames a GI change is cross-faded over (0: off) */
    int env_lights;             /* environment area lights drawn (render_env.h) */
} gk_frame_knobs;

/* Cross-fade of the GI result when the method or a budget changes (render_gi_blend.c): the
 * visitor sees the indirect light slide from the old to the new over gi_blend frames instead of a
 * jump. What is faded is the GI's contribution -- the frame after GI minus the frame before it --
 * so direct light never ghosts; the contribution of the last frame before the change is held. */
typedef struct gk_gi_blend {
    gk_target pre;              /* this frame's HDR image before the GI pass (render size) */
    gk_target held;             /* GI contribution shown in the last frame before the change (its size) */
    gk_target out;              /* the blended image composed during a transition */
    bool pre_valid;             /* pre holds the last frame's image before GI (it ran the gi pass) */
    int frames;                 /* frames of the running transition (the gi_blend knob when it began) */
    int frames_left;            /* blended frames still to draw (0: no transition) */
    char method[32];            /* what the last frame ran: method and every knob level */
    int n_levels;
    int levels[GK_MAX_KNOBS];
    bool have_last;
    /* the bench's counting frame (render_work.c): this frame's texels the copy and the blend read,
       and at a transition's first frame the hold's lookups (2 a texel of the last frame's size) */
    double work_hold, work_blend, work_capture;
} gk_gi_blend;

/* The shadow maps of a static scene are kept while this stays the same (compared by value). */
typedef struct gk_shadow_cache_key { /* compared with memcmp: no padding (fields ordered to fill it) */
    unsigned scene_generation;  /* 0: nothing cached */
    int env_lights;             /* the environment's lights shadowed (render_env.h) */
    const gk_shadow_method *method;
    int map_size, subdiv;
} gk_shadow_cache_key;
_Static_assert(sizeof(gk_shadow_cache_key) == 4 * sizeof(int) + sizeof(void *), "gk_shadow_cache_key has padding");

/* The lighting pass's two-draw split (render_split.c): an FBO of the HDR colour and a stencil. */
typedef struct gk_light_split {
    GLuint fbo, stencil;
    GLuint color;               /* the HDR texture it was made for (the target is re-made on resize) */
    int w, h;
    bool unavailable;           /* the colour + stencil framebuffer was refused: one draw from then on */
} gk_light_split;

struct gk_renderer {
    gk_render_opts opts;
    char *shader_dir;
    gk_gl_caps caps;
    gk_program_cache *progs;
    gk_timer *timer;
    double time_s;               /* the frame's animation time (gk_frame_params), lent to the GI method */
    GLuint empty_vao;           /* full-screen passes draw gl_VertexID-only triangles */
    GLuint ltc_tex;             /* RGBA32F GK_LTC_N x 2 GK_LTC_N: rect lights' GGX (ltc_table.h) */

    gk_scene *scene;
    unsigned scene_generation;  /* bumped by every set_scene: caches compare this, not pointers */
    gk_scene_gpu gpu;
    bool have_gpu;

    gk_target gbuf;             /* RT0 albedo+metallic RGBA8, RT1 normal+roughness RGBA16F, RT2 emission RGBA16F,
                                   RT3 specular (sqrt c0, weight) RGBA8, RT4 geometric normal RGBA16F when the
                                   driver has 5 draw buffers (gk_render_geom_normal_target), depth 32F */
    gk_target hdr;              /* RGBA16F scene radiance at render scale */
    gk_target glass;            /* RGBA16F: hdr (or the GI blend) with the glass drawn over it (render_glass.c) */
    gk_light_split split;       /* the HDR colour + a stencil for the lighting pass's two draws (render_split.c) */
    int render_w, render_h;     /* render size (output * render_scale) */

    struct gk_render_gi *gi;    /* GI methods (render_gi.c) */
    gk_render_knobs knobs;      /* handles of the renderer's knobs (renderer_knobs.c) */
    gk_budget ran;              /* this frame's knob levels as they ran (pass.h: gk_pass_ctx.ran) */
    bool have_ran;
    gk_gi_blend blend;          /* GI cross-fade state (render_gi_blend.c) */
    GLuint shown;               /* the HDR texture compose shows this frame: hdr, or blend.out */
    gk_shadow_cache_key shadow_cache; /* what the maps now in shadow_state were rendered for */
    void *shadow_state[GK_MAX_SHADOW_METHODS]; /* per method of gk_shadow_methods[], created on first use */

    GLuint env_tex;             /* the scene environment's lat-long map (render_env.c), RGBA32F */
    GLuint blend_fbo;           /* the blend pass's: the shown HDR image + the G-buffer's depth (render_blend.c) */
    unsigned env_tex_generation; /* scene generation env_tex was uploaded for */
    float exposure;             /* display scale, fixed per scene (tonemap.h) */
    bool exposure_known;
    bool have_frame;            /* hdr holds a finished frame for capture */

    /* The bench's counts of the renderer's passes' work (render_work.c, #21) */
    bool count_work;            /* this frame's passes use their counting variants (the G-buffer's
                                   fragments, the lighting pass's shadow lookups, the compose's
                                   HDR lookups; the GI method's, gk_gi_frame.count_work) */
    gk_counters gbuffer_fragments; /* one: the G-buffer draws' fragments */
    gk_counters depth_fragments; /* one: the shadow maps' depth draws' fragments */
    gk_counters shadow_fetches; /* five: the shadow lookups by format (render_work.c's kinds) */
    gk_counters compose_fetches; /* one: the compose's bilinear HDR lookups */
    gk_counters glass_fetches;  /* two: the glass draws' G-buffer depth reads and bilinear lookups of
                                   the image behind (glass/refract.frag) */
    long glass_copy_lookups;    /* the glass pass's copy of the shown image: one lookup a pixel */
    gk_counters blend_fragments; /* one: the alpha-blended draws' fragments (blend/forward.frag) */
    double occlusion_pixels;    /* the occlusion pass's pixels (one pre-GI texel and one depth read each) */
    gk_pf_frame_work prefilter_work; /* VSSM's and CSSM's prefilters' modelled fetches
                                   (shadow_prefilter_work.h), added by the counting frame's shadow
                                   maps, zeroed before them */
};

/* render_work.c: around the direct pass's lights, when r->count_work: zero and bind the
 * counter before them (returns the define the shadowed lights' programs add, "" when not counting),
 * read it back after them. The same around the shadow maps, the G-buffer pass and the frame's compose. */
const char *gk_render_work_begin(gk_renderer *r);
void gk_render_work_end(gk_renderer *r);
const char *gk_render_work_shadow_begin(gk_renderer *r);
void gk_render_work_shadow_end(gk_renderer *r);
const char *gk_render_work_gbuffer_begin(gk_renderer *r);
void gk_render_work_gbuffer_end(gk_renderer *r);
const char *gk_render_work_glass_begin(gk_renderer *r);
void gk_render_work_glass_end(gk_renderer *r, long copy_lookups);
const char *gk_render_work_compose_begin(gk_renderer *r);
void gk_render_work_compose_end(gk_renderer *r);
const char *gk_render_work_blend_begin(gk_renderer *r);
void gk_render_work_blend_end(gk_renderer *r);
void gk_render_work_destroy(gk_renderer *r);

/* render_split.c: a splitting shadow method's light in two draws (gk_shadow_method.split). first
   binds the split FBO, clears its stencil and sets draw 1's stencil state; second sets draw 2's;
   end restores the state and binds the HDR target. enabled: GK_SHADOW_ONE_DRAW is unset or 0. */
bool gk_render_split_enabled(void);
bool gk_render_split_first(gk_renderer *r);
void gk_render_split_second(void);
void gk_render_split_end(gk_renderer *r);
void gk_render_split_destroy(gk_renderer *r);

/* renderer_knobs.c: handles set up at creation; the frame's values from budget b (NULL: defaults). */
void gk_render_knobs_init(gk_render_knobs *k);
void gk_render_knobs_read(gk_render_knobs *k, const gk_budget *b, gk_frame_knobs *out);

/* render_gi_blend.c. At the start of a frame, before targets are resized: notes what the frame
 * runs and, when that differs from the last frame, holds the GI contribution that frame showed. */
void gk_gi_blend_begin_frame(gk_renderer *r, const char *method, const gk_budget *b, int blend_frames);
/* True when the gi pass has work this frame though the method adds nothing (a fade to none). */
bool gk_gi_blend_active(const gk_renderer *r);
/* Inside the gi pass: before the method (keeps the image before GI), after it (the fade). */
int gk_gi_blend_before_method(gk_renderer *r, const gk_pass_ctx *ctx, int blend_frames, gk_err *e);
int gk_gi_blend_after_method(gk_renderer *r, const gk_pass_ctx *ctx, gk_err *e);
/* A new scene: nothing to fade from. */
void gk_gi_blend_reset(gk_renderer *r);

/* render_gi_occlusion.c: whether the scene has an occlusionTexture (the gi pass then keeps the image
 * before the method, as the fade does), and, after the method, its contribution scaled by the
 * G-buffer's ao (nested pass `occlusion`). */
bool gk_gi_occlusion_needed(const gk_renderer *r);
int gk_gi_occlusion_apply(gk_renderer *r, const gk_pass_ctx *ctx, gk_err *e);
void gk_gi_blend_destroy(gk_renderer *r);

/* Light kind numbers of shaders_gles/common/lights.glsl. */
int gk_render_light_kind(const gk_light *l);

/* The uniforms of one light (shaders_gles/common/lights.glsl) and the LTC table area lights read,
 * for the passes that light surfaces one light at a time (direct/light.frag, blend/forward.frag). */
typedef struct gk_light_uniforms {
    GLint u_light_pos, u_light_dir, u_light_u, u_light_v, u_light_color, u_light_range, u_light_cone,
        u_light_radius, u_light_size, u_ltc;
} gk_light_uniforms;
#define GK_LIGHT_FIELDS(type, member)                                                                                  \
    GK_UNIFORM_AS(type, member.u_light_pos, "u_light_pos"), GK_UNIFORM_AS(type, member.u_light_dir, "u_light_dir"),   \
        GK_UNIFORM_AS(type, member.u_light_u, "u_light_u"), GK_UNIFORM_AS(type, member.u_light_v, "u_light_v"),       \
        GK_UNIFORM_AS(type, member.u_light_color, "u_light_color"),                                                    \
        GK_UNIFORM_AS(type, member.u_light_range, "u_light_range"),                                                    \
        GK_UNIFORM_AS(type, member.u_light_cone, "u_light_cone"),                                                      \
        GK_UNIFORM_AS(type, member.u_light_radius, "u_light_radius"),                                                  \
        GK_UNIFORM_AS(type, member.u_light_size, "u_light_size"), GK_UNIFORM_AS(type, member.u_ltc, "u_ltc")
/* The defines of lights.glsl for light l (kind, spot) followed by `extra` (a shadow variant). */
void gk_render_light_defines(const gk_light *l, const char *extra, char *out, size_t size);
/* Sets the light of scene node `node` on the bound program, and binds the LTC table on UNIT_LTC. */
void gk_render_set_light(gk_renderer *r, const gk_light_uniforms *u, int node);

/* render_blend.c: the `blend` pass, alphaMode BLEND surfaces over the lit image (see there). */
bool gk_render_blend_needed(const gk_renderer *r);
/* count_define: forward.frag's counting variant (gk_render_work_blend_begin), "" without. */
int gk_render_blend(gk_renderer *r, const gk_gbuffer_view *gb, int env_lights, const char *count_define, gk_err *e);

/* Draws the full-screen triangle with the bound program. */
void gk_render_fullscreen(gk_renderer *r);

/* Compose pass into fbo (w x h): tonemapped, or linear when linear_out. */
/* count_define: the bench's counting variant (gk_render_work_compose_begin), NULL or "" without. */
int gk_render_compose(gk_renderer *r, GLuint fbo, int w, int h, bool linear_out, const char *count_define, gk_err *e);

/* The G-buffer's 5th target, the geometric normal, needs 5 draw buffers (GLES 3.1 guarantees 4;
 * llvmpipe, Mali Bifrost and later, Adreno have 8). Without them the shading normal stands in (the
 * normal-map defects of README "Your own glTF models" come back, logged once at start). */
static inline bool gk_render_geom_normal_target(const gk_renderer *r) { return r->caps.max_draw_buffers >= 5; }
/* The defines gbuffer/gbuffer.frag is compiled with. */
static inline const char *gk_render_gbuffer_defines(const gk_renderer *r)
{
    return gk_render_geom_normal_target(r) ? "#define GK_GEOM_NORMAL_TARGET 1\n" : "#define GK_GEOM_NORMAL_TARGET 0\n";
}

#endif
