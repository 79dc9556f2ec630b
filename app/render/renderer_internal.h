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
enum { UNIT_ALBEDO = 0, UNIT_NORMAL = 1, UNIT_EMISSION = 2, UNIT_DEPTH = 3, UNIT_SHADOW = 4 };

struct gk_renderer {
    gk_render_opts opts;
    char *shader_dir;
    gk_gl_caps caps;
    gk_program_cache *progs;
    gk_timer *timer;
    GLuint empty_vao;           /* full-screen passes draw gl_VertexID-only triangles */

    gk_scene *scene;
    unsigned scene_generation;  /* bumped by every set_scene: caches compare this, not pointers */
    gk_scene_gpu gpu;
    bool have_gpu;

    gk_target gbuf;             /* RT0 albedo+metallic RGBA8, RT1 normal+roughness RGBA16F, RT2 emission RGBA16F, depth 32F */
    gk_target hdr;              /* RGBA16F scene radiance at render scale */
    int render_w, render_h;     /* render size (output * render_scale) */

    struct gk_render_gi *gi;    /* GI methods (render_gi.c) */
    char shadow_cache_key[512]; /* scene|method|size|knobs of the maps now in shadow_state ("" = none) */
    void *shadow_state[GK_MAX_SHADOW_METHODS]; /* per method of gk_shadow_methods[], created on first use */

    float exposure;             /* display scale, fixed per scene (tonemap.h) */
    bool exposure_known;
    bool have_frame;            /* hdr holds a finished frame for capture */
};

/* Light kind numbers of shaders_gles/common/lights.glsl. */
int gk_render_light_kind(const gk_light *l);

/* Draws the full-screen triangle with the bound program. */
void gk_render_fullscreen(gk_renderer *r);

/* Compose pass into fbo (w x h): tonemapped, or linear when linear_out. */
int gk_render_compose(gk_renderer *r, GLuint fbo, int w, int h, bool linear_out, gk_err *e);

#endif
