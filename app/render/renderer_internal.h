/* The renderer's state, shared by renderer.c (lifetime, scene, knobs), render_frame.c (the passes)
 * and render_capture.c. Not part of the public API. */
#ifndef GK_RENDERER_INTERNAL_H
#define GK_RENDERER_INTERNAL_H

#include "gl/gl.h"
#include "gl/gl_program.h"
#include "gl/gl_target.h"
#include "gl/gl_timing.h"
#include "renderer.h"
#include "scene_gpu.h"
#include "shadow/shadow.h"

#define GK_MAX_SHADOW_METHODS 16 /* entries of gk_shadow_methods[]; a static assert in shadow_methods.c keeps them in step */

/* Texture units of the lighting passes. */
enum { UNIT_ALBEDO = 0, UNIT_NORMAL = 1, UNIT_EMISSION = 2, UNIT_DEPTH = 3, UNIT_SPECULAR = 4, UNIT_SHADOW = 5,
       UNIT_LTC = 15 /* the last unit GLES 3.1 guarantees a fragment shader: after every shadow method's */ };

/* The renderer's knobs, read each frame through handles (no names in the frame loop). */
typedef struct gk_render_knobs {
    gk_knob scale, shadow, shadow_map, shadow_subdiv;
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
} gk_frame_knobs;

/* The shadow maps of a static scene are kept while this stays the same (compared by value). */
typedef struct gk_shadow_cache_key {
    unsigned scene_generation;  /* 0: nothing cached */
    const gk_shadow_method *method;
    int map_size, subdiv;
} gk_shadow_cache_key;

struct gk_renderer {
    gk_render_opts opts;
    char *shader_dir;
    gk_gl_caps caps;
    gk_program_cache *progs;
    gk_timer *timer;
    GLuint empty_vao;           /* full-screen passes draw gl_VertexID-only triangles */
    GLuint ltc_tex;             /* RGBA32F GK_LTC_N x 2 GK_LTC_N: rect lights' GGX (ltc_table.h) */

    gk_scene *scene;
    unsigned scene_generation;  /* bumped by every set_scene: caches compare this, not pointers */
    gk_scene_gpu gpu;
    bool have_gpu;

    gk_target gbuf;             /* RT0 albedo+metallic RGBA8, RT1 normal+roughness RGBA16F, RT2 emission RGBA16F,
                                   RT3 specular (sqrt c0, weight) RGBA8, depth 32F */
    gk_target hdr;              /* RGBA16F scene radiance at render scale */
    int render_w, render_h;     /* render size (output * render_scale) */

    struct gk_render_gi *gi;    /* GI methods (render_gi.c) */
    gk_render_knobs knobs;      /* handles of the renderer's knobs (renderer_knobs.c) */
    gk_shadow_cache_key shadow_cache; /* what the maps now in shadow_state were rendered for */
    void *shadow_state[GK_MAX_SHADOW_METHODS]; /* per method of gk_shadow_methods[], created on first use */

    float exposure;             /* display scale, fixed per scene (tonemap.h) */
    bool exposure_known;
    bool have_frame;            /* hdr holds a finished frame for capture */
};

/* renderer_knobs.c: handles set up at creation; the frame's values from budget b (NULL: defaults). */
void gk_render_knobs_init(gk_render_knobs *k);
void gk_render_knobs_read(gk_render_knobs *k, const gk_budget *b, gk_frame_knobs *out);

/* Light kind numbers of shaders_gles/common/lights.glsl. */
int gk_render_light_kind(const gk_light *l);

/* Draws the full-screen triangle with the bound program. */
void gk_render_fullscreen(gk_renderer *r);

/* Compose pass into fbo (w x h): tonemapped, or linear when linear_out. */
int gk_render_compose(gk_renderer *r, GLuint fbo, int w, int h, bool linear_out, gk_err *e);

#endif
