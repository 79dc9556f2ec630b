/* Work counters a shader adds to (#21: the bench's counting variants): a few uints in a storage
 * buffer, zeroed and bound before a pass, read back after it (a stall: bench frames only). */
#ifndef GK_GL_COUNTERS_H
#define GK_GL_COUNTERS_H

#include <stdbool.h>

#include "gl.h"

#define GK_COUNTERS_MAX 4

/* True when fragment shaders may write storage buffers (GLES 3.1 allows none). */
bool gk_counters_in_fragment_shaders(void);
/* Zeroes n counters of *ssbo (made on first use) and binds them at `binding`. */
void gk_counters_reset(GLuint *ssbo, int n, GLuint binding);
/* Reads n counters into out; false (out untouched) when the buffer cannot be mapped. */
bool gk_counters_read(GLuint ssbo, int n, double *out);

#endif
