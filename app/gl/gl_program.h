/* A program cache over shader files: a program is (vertex file, fragment file, #define prelude) or
 * (compute file, prelude), compiled on first use and kept until the cache is destroyed. Variants
 * (shadow method, light kind, GLES 3.1 vs 3.2 paths) come from one file through the prelude.
 * Compile and link errors are GK_ERUNTIME with "shaders_gles/FILE:LINE: message". */
#ifndef GK_GL_PROGRAM_H
#define GK_GL_PROGRAM_H

#include "base/err.h"
#include "gl.h"

typedef struct gk_program_cache gk_program_cache;

/* shader_dir NULL: embedded shaders. gles: 31 or 32 (the #version written). */
gk_program_cache *gk_program_cache_create(const char *shader_dir, int gles);
void gk_program_cache_destroy(gk_program_cache *c);

/* Returns 0 (and fills e) on failure. defines: "#define A 1\n#define B\n" or NULL. */
GLuint gk_program_get(gk_program_cache *c, const char *vert, const char *frag, const char *defines, gk_err *e);
GLuint gk_program_get_compute(gk_program_cache *c, const char *comp, const char *defines, gk_err *e);

/* Uniform helpers that ignore names the program optimised away. */
void gk_uniform_1i(GLuint prog, const char *name, int v);
void gk_uniform_1f(GLuint prog, const char *name, float v);
void gk_uniform_2f(GLuint prog, const char *name, float x, float y);
void gk_uniform_3f(GLuint prog, const char *name, float x, float y, float z);
void gk_uniform_4f(GLuint prog, const char *name, float x, float y, float z, float w);
void gk_uniform_mat4(GLuint prog, const char *name, const float *m);
void gk_uniform_mat4v(GLuint prog, const char *name, int count, const float *m);

#endif
