/* A program cache over shader files: a program is (vertex file, fragment file, #define prelude) or
 * (compute file, prelude), compiled on first use and kept until the cache is destroyed. Variants
 * (shadow method, light kind, GLES 3.1 vs 3.2 paths) come from one file through the prelude.
 * Compile and link errors are GK_ERUNTIME with "shaders_gles/FILE:LINE: message". */
#ifndef GK_GL_PROGRAM_H
#define GK_GL_PROGRAM_H

#include "base/err.h"
#include "gl.h"

#include <stddef.h>

typedef struct gk_program_cache gk_program_cache;

/* shader_dir NULL: embedded shaders. gles: 31 or 32 (the #version written). */
gk_program_cache *gk_program_cache_create(const char *shader_dir, int gles);
void gk_program_cache_destroy(gk_program_cache *c);

/* Returns 0 (and fills e) on failure. defines: "#define A 1\n#define B\n" or NULL. */
GLuint gk_program_get(gk_program_cache *c, const char *vert, const char *frag, const char *defines, gk_err *e);
GLuint gk_program_get_compute(gk_program_cache *c, const char *comp, const char *defines, gk_err *e);

/* A program's uniform locations, resolved once after link into a struct of GLint fields, so the
 * frame loop sets uniforms by location, never by name:
 *
 *     typedef struct { GLint u_viewproj, u_eye; } gbuffer_uniforms;
 *     static const gk_uniform_field gbuffer_fields[] = {
 *         GK_UNIFORM(gbuffer_uniforms, u_viewproj), GK_UNIFORM(gbuffer_uniforms, u_eye)};
 *     const gbuffer_uniforms *u = gk_program_uniforms(cache, prog, GK_FIELDS(gbuffer_fields),
 *                                                     sizeof *u, e);
 *     glUniform3f(u->u_eye, ...);
 *
 * A name that occurs nowhere in the program's source is a misspelling and fails (GK_ERUNTIME,
 * naming the uniform and the shader files): before this, a misspelt uniform did nothing and said
 * nothing. A name the compiler optimised away (a variant that does not use it) gets location -1,
 * which glUniform* ignores. The block is resolved on the first call for (prog, fields) and cached
 * with the program: later calls are a pointer comparison. */
typedef struct gk_uniform_field {
    const char *name;   /* GLSL name; "u_x[0]" for the first element of an array */
    size_t offset;      /* of the GLint field in the caller's struct */
} gk_uniform_field;
#define GK_UNIFORM(type, field) {#field, offsetof(type, field)}
#define GK_UNIFORM_AS(type, field, glsl_name) {glsl_name, offsetof(type, field)}
#define GK_FIELDS(table) (table), (int)(sizeof(table) / sizeof((table)[0]))

/* Returns the cached block (size bytes, GLint fields) or NULL with e filled. Fields of the struct
 * that the table does not list are -1 (so a struct shared by variants, or embedding another
 * struct of locations, may leave some out). */
const void *gk_program_uniforms(gk_program_cache *c, GLuint prog, const gk_uniform_field *fields, int n,
                                size_t size, gk_err *e);
/* The same check without a cache, for a program and its source text (tests; programs built
 * outside a cache). Fills out (size bytes). */
int gk_uniforms_resolve(GLuint prog, const char *source, const gk_uniform_field *fields, int n, void *out,
                        gk_err *e);

/* Uniform helpers by name (one glGetUniformLocation per call): for tests and one-off set-up only,
 * never in the frame loop (use gk_program_uniforms there). */
void gk_uniform_1i(GLuint prog, const char *name, int v);
void gk_uniform_1f(GLuint prog, const char *name, float v);
void gk_uniform_2f(GLuint prog, const char *name, float x, float y);
void gk_uniform_3f(GLuint prog, const char *name, float x, float y, float z);
void gk_uniform_4f(GLuint prog, const char *name, float x, float y, float z, float w);
void gk_uniform_mat4(GLuint prog, const char *name, const float *m);
void gk_uniform_mat4v(GLuint prog, const char *name, int count, const float *m);

#endif
