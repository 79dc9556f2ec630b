#include "gl_target.h"

#include <string.h>

GLuint gk_texture_2d(GLenum internal_format, int width, int height, GLenum filter)
{
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, (GLint)filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, (GLint)filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    return tex;
}

const char *gk_gl_error_name(GLenum err)
{
    switch (err) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "unknown GL error";
    }
}

int gk_fbo_check(const char *what, gk_err *e)
{
    GLenum s = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (s == GL_FRAMEBUFFER_COMPLETE)
        return 0;
    const char *why = s == GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT           ? "incomplete attachment (format not renderable?)"
                      : s == GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT ? "missing attachment"
                      : s == GL_FRAMEBUFFER_UNSUPPORTED                   ? "unsupported format combination"
                      : s == GL_FRAMEBUFFER_INCOMPLETE_DIMENSIONS         ? "attachments differ in size"
                                                                          : "incomplete";
    return gk_fail(e, GK_ERUNTIME, "render target '%s': framebuffer %s (0x%04x)", what, why, s);
}

int gk_target_create(gk_target *t, const char *what, int width, int height, int n_color, const GLenum *formats,
                     GLenum filter, bool with_depth, gk_err *e)
{
    memset(t, 0, sizeof *t);
    if (n_color > GK_TARGET_MAX_COLOR || width <= 0 || height <= 0)
        return gk_fail(e, GK_ERUNTIME, "render target '%s': bad size %dx%d or %d colour targets", what, width, height,
                       n_color);
    while (glGetError() != GL_NO_ERROR) {
    }
    t->width = width;
    t->height = height;
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    GLenum bufs[GK_TARGET_MAX_COLOR];
    for (int i = 0; i < n_color; i++) {
        t->color[i] = gk_texture_2d(formats[i], width, height, filter);
        t->color_format[i] = formats[i];
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)i, GL_TEXTURE_2D, t->color[i], 0);
        bufs[i] = GL_COLOR_ATTACHMENT0 + (GLenum)i;
    }
    t->n_color = n_color;
    if (n_color)
        glDrawBuffers(n_color, bufs);
    if (with_depth) {
        t->depth = gk_texture_2d(GL_DEPTH_COMPONENT32F, width, height, GL_NEAREST);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t->depth, 0);
    }
    int rc = gk_fbo_check(what, e);
    GLenum err = glGetError();
    if (rc == 0 && err != GL_NO_ERROR)
        rc = gk_fail(e, GK_ERUNTIME, "render target '%s' %dx%d: %s", what, width, height, gk_gl_error_name(err));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (rc != 0)
        gk_target_destroy(t);
    return rc;
}

void gk_target_destroy(gk_target *t)
{
    if (t->n_color)
        glDeleteTextures(t->n_color, t->color);
    if (t->depth)
        glDeleteTextures(1, &t->depth);
    if (t->fbo)
        glDeleteFramebuffers(1, &t->fbo);
    memset(t, 0, sizeof *t);
}
