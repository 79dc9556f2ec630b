/* State shared by the lightmap method's files (not for other modules). */
#ifndef GK_LM_INTERNAL_H
#define GK_LM_INTERNAL_H

#include "gl/gl.h"
#include "gl/gl_program.h"
#include "lightmap.h"
#include "lm_atlas.h"

#define LM_KNOBS 4

typedef struct lm_state {
    gk_gi_context ctx;
    gk_program_cache *own_cache;
    gk_knob knob[LM_KNOBS];
    gk_lightmap_stats st;
    int threads_override;
    /* the scene: the method's own copy loaded from the scene's file (the worker threads read it
       while the renderer's may be freed), or borrowed when the scene has no file (tests) */
    gk_scene *own_scene;
    const gk_scene *scene;       /* what the atlas and the worker were built from */
    const gk_scene *source;      /* the renderer's scene it stands for */
    lm_atlas atlas;
    bool have_atlas;
    lm_worker *worker;
    uint64_t seen;               /* the worker's last publication uploaded */
    /* GPU */
    GLuint vao, vbo, empty_vao;
    GLuint irr_tex;
    float irr_scale;             /* the texture holds E / irr_scale */
    GLuint uv_fbo, uv_tex, uv_depth;
    int uv_w, uv_h;
} lm_state;

/* lm_display.c */
int lm_display_setup(lm_state *s, gk_err *e);       /* VBO of the atlas vertices, irradiance texture */
void lm_display_upload(void *state, const float *irr);
int lm_display_draw(lm_state *s, const gk_gi_frame *f, gk_err *e);
void lm_display_free(lm_state *s);

#endif
