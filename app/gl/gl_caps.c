/* Capability queries with the --gles 3.1 mask (DESIGN §3: the portable path must be testable on a
 * 3.2 driver). Extensions a typical GLES 3.1 board offers stay visible under the mask. */
#include "gl.h"

#include <string.h>

bool gk_gl_has_extension(const char *name)
{
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *ext = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (ext && strcmp(ext, name) == 0)
            return true;
    }
    return false;
}

void gk_gl_caps_query(gk_gl_caps *caps, int gles_version)
{
    memset(caps, 0, sizeof *caps);
    GLint major = 3, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    int driver = major * 10 + minor;
    caps->gles = (gles_version == 31 || driver < 32) ? 31 : 32;
    bool ext_float = gk_gl_has_extension("GL_EXT_color_buffer_float");
    caps->color_buffer_float = ext_float;
    caps->color_buffer_half = ext_float || gk_gl_has_extension("GL_EXT_color_buffer_half_float") || caps->gles >= 32;
    caps->float_linear = gk_gl_has_extension("GL_OES_texture_float_linear");
    caps->timer_query = gk_gl_has_extension("GL_EXT_disjoint_timer_query");
    caps->debug_labels = caps->gles >= 32;
    GLint draw_buffers = 4, attachments = 4;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
    glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &attachments);
    caps->max_draw_buffers = draw_buffers < attachments ? draw_buffers : attachments;
}
