/* Shader source assembly, independent of GL (so tools and tests can expand shaders without a
 * context): `#version`, a `#define` prelude, then the file with every `#include "path"` replaced
 * by that file (paths relative to the shaders_gles/ root; each file included once per program;
 * cycles and depth > 16 are errors). `#line N K` directives keep compiler messages mappable to the
 * file K of `files` and its line N. Sources come from --shader-dir when given, else from the table
 * embedded in the binary. */
#ifndef GK_SHADER_SOURCE_H
#define GK_SHADER_SOURCE_H

#include "base/err.h"

#define GK_SHADER_MAX_FILES 32

typedef struct gk_shader_text {
    char *text;                               /* malloc'd, NUL-terminated */
    int n_files;
    char files[GK_SHADER_MAX_FILES][128];     /* file index -> path, as used in #line */
} gk_shader_text;

/* gles: 31 -> "#version 310 es", 32 -> "#version 320 es"; defines: extra prelude lines or NULL. */
int gk_shader_expand(const char *shader_dir, const char *path, int gles, const char *defines,
                     gk_shader_text *out, gk_err *e);
void gk_shader_text_free(gk_shader_text *t);

/* Rewrites "K:LINE" locations in a compiler log into "path:LINE" (best effort). */
void gk_shader_map_log(const gk_shader_text *t, const char *log, char *out, int out_len);

#endif
