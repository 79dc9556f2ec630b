/* The GL headers the renderer uses: GLES 3.2 declarations (3.2 entry points are only called after
 * a capability check, see gk_gl_caps) plus the EXT enums. */
#ifndef GK_RENDER_GL_H
#define GK_RENDER_GL_H

#include <GLES3/gl32.h>
#include <GLES2/gl2ext.h>
#include <stdbool.h>

/* What the context offers, after the --gles 3.1 mask: with gles_version 31 every 3.2-core feature
 * is reported absent even on a 3.2 driver, so the portable path runs on llvmpipe too. */
typedef struct gk_gl_caps {
    int gles;                  /* 31 or 32 (the effective level) */
    bool color_buffer_half;    /* RGBA16F colour-renderable (EXT_color_buffer_half_float/float, or 3.2) */
    bool color_buffer_float;   /* RGBA32F colour-renderable (EXT_color_buffer_float) */
    bool float_linear;         /* OES_texture_float_linear */
    bool timer_query;          /* EXT_disjoint_timer_query */
    bool debug_labels;         /* KHR_debug (3.2 core) */
    int max_draw_buffers;      /* GL_MAX_DRAW_BUFFERS (GLES 3.1 guarantees 4): the G-buffer's 5th target needs 5 */
} gk_gl_caps;

void gk_gl_caps_query(gk_gl_caps *caps, int gles_version);
bool gk_gl_has_extension(const char *name);

#endif
