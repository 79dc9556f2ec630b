/* Render targets: textures, FBOs with completeness checks that name the target and the reason. */
#ifndef GK_GL_TARGET_H
#define GK_GL_TARGET_H

#include "base/err.h"
#include "gl.h"

#define GK_TARGET_MAX_COLOR 5

typedef struct gk_target {
    GLuint fbo;
    GLuint color[GK_TARGET_MAX_COLOR];
    GLenum color_format[GK_TARGET_MAX_COLOR];
    int n_color;
    GLuint depth;            /* depth texture (DEPTH_COMPONENT32F), 0 if none */
    int width, height;
} gk_target;

/* Immutable 2D texture with clamp-to-edge wrapping and the given min/mag filter. */
GLuint gk_texture_2d(GLenum internal_format, int width, int height, GLenum filter);

/* Creates an FBO with n colour textures of the given formats (filter: NEAREST or LINEAR) and an
 * optional depth texture; checks completeness. what names it in errors ("gbuffer"). */
int gk_target_create(gk_target *t, const char *what, int width, int height, int n_color, const GLenum *formats,
                     GLenum filter, bool with_depth, gk_err *e);
void gk_target_destroy(gk_target *t);

/* GL_FRAMEBUFFER_COMPLETE or a GK_ERUNTIME naming what and the status. */
int gk_fbo_check(const char *what, gk_err *e);
const char *gk_gl_error_name(GLenum err);

#endif
