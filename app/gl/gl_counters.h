/* Work counters a shader adds to (#21: the bench's counting variants): a few uints in a storage
 * buffer, zeroed and bound before a pass, read back after it (a stall: bench frames only). */
#ifndef GK_GL_COUNTERS_H
#define GK_GL_COUNTERS_H

#include <stdbool.h>

#include "gl.h"

#define GK_COUNTERS_MAX 8

typedef struct gk_counters {
    int n;                  /* counters (uints) the shader's buffer block holds */
    GLuint binding;         /* its binding point */
    GLuint ssbo;            /* made on first use */
    bool counting;          /* this frame's pass runs its counting variant */
    bool counted;           /* value holds the last counted pass's */
    double value[GK_COUNTERS_MAX];
} gk_counters;

/* Before a pass: when `on` and fragment shaders may write storage buffers (GLES 3.1 allows none),
 * zeroes and binds the counters and returns true (the pass then runs its counting variant). */
bool gk_counters_begin(gk_counters *c, bool on);
/* gk_counters_begin for a pass with a counting variant: n counters at `binding`; returns `define`
 * (the variant's #define) when the pass counts this frame, else NULL. */
const char *gk_counters_variant(gk_counters *c, bool on, int n, GLuint binding, const char *define);
/* After it: reads the counters back when the pass counted. */
void gk_counters_end(gk_counters *c);
void gk_counters_free(gk_counters *c);
/* True when fragment shaders may write storage buffers. */
bool gk_counters_in_fragment_shaders(void);

#endif
