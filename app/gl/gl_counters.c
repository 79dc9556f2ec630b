/* Work counters (gl_counters.h). */
#include "gl_counters.h"

#include <stddef.h>

bool gk_counters_in_fragment_shaders(void)
{
    GLint blocks = 0;
    glGetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &blocks);
    return blocks > 0;
}

void gk_counters_reset(GLuint *ssbo, int n, GLuint binding)
{
    static const GLuint zero[GK_COUNTERS_MAX] = {0};
    GLsizeiptr bytes = (GLsizeiptr)sizeof(GLuint) * (n < GK_COUNTERS_MAX ? n : GK_COUNTERS_MAX);
    if (!*ssbo) {
        glGenBuffers(1, ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, *ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)sizeof zero, zero, GL_DYNAMIC_READ);
    } else {
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, *ssbo);
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes, zero);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, *ssbo);
}

bool gk_counters_read(GLuint ssbo, int n, double *out)
{
    if (!ssbo)
        return false;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, ssbo);
    const GLuint *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)sizeof(GLuint) * n, GL_MAP_READ_BIT);
    if (p) {
        for (int i = 0; i < n; i++)
            out[i] = p[i];
        glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    return p != NULL;
}
