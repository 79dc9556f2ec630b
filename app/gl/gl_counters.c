/* Work counters (gl_counters.h). */
#include "gl_counters.h"

#include <stddef.h>

bool gk_counters_in_fragment_shaders(void)
{
    GLint blocks = 0;
    glGetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &blocks);
    return blocks > 0;
}

bool gk_counters_begin(gk_counters *c, bool on)
{
    c->counted = false;
    c->counting = on && c->n > 0 && c->n <= GK_COUNTERS_MAX && gk_counters_in_fragment_shaders();
    if (!c->counting)
        return false;
    static const GLuint zero[GK_COUNTERS_MAX] = {0};
    if (!c->ssbo) {
        glGenBuffers(1, &c->ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, c->ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)sizeof zero, zero, GL_DYNAMIC_READ);
    } else {
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, c->ssbo);
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)sizeof zero, zero);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, c->binding, c->ssbo);
    return true;
}

const char *gk_counters_variant(gk_counters *c, bool on, int n, GLuint binding, const char *define)
{
    c->n = n;
    c->binding = binding;
    return gk_counters_begin(c, on) ? define : NULL;
}

void gk_counters_end(gk_counters *c)
{
    if (!c->counting)
        return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, c->ssbo);
    const GLuint *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)sizeof(GLuint) * c->n, GL_MAP_READ_BIT);
    if (p) {
        for (int i = 0; i < c->n; i++)
            c->value[i] = p[i];
        glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    c->counted = p != NULL;
}

void gk_counters_free(gk_counters *c)
{
    if (c->ssbo)
        glDeleteBuffers(1, &c->ssbo);
    c->ssbo = 0;
    c->counted = c->counting = false;
}
