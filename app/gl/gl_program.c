#include "gl_program.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shader_source.h"

#define MAX_PROGRAMS 96

typedef struct cached_program {
    char *key;
    GLuint prog;
} cached_program;

struct gk_program_cache {
    char *shader_dir;
    int gles;
    int n;
    cached_program p[MAX_PROGRAMS];
};

gk_program_cache *gk_program_cache_create(const char *shader_dir, int gles)
{
    gk_program_cache *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->shader_dir = shader_dir ? strdup(shader_dir) : NULL;
    c->gles = gles;
    return c;
}

void gk_program_cache_destroy(gk_program_cache *c)
{
    if (!c)
        return;
    for (int i = 0; i < c->n; i++) {
        glDeleteProgram(c->p[i].prog);
        free(c->p[i].key);
    }
    free(c->shader_dir);
    free(c);
}

static GLuint compile(gk_program_cache *c, GLenum stage, const char *path, const char *defines, gk_err *e)
{
    gk_shader_text t;
    if (gk_shader_expand(c->shader_dir, path, c->gles, defines, &t, e) != 0)
        return 0;
    GLuint sh = glCreateShader(stage);
    const char *src = t.text;
    glShaderSource(sh, 1, &src, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096], mapped[4096];
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        gk_shader_map_log(&t, log, mapped, sizeof mapped);
        size_t n = strlen(mapped);
        while (n && (mapped[n - 1] == '\n' || mapped[n - 1] == ' '))
            mapped[--n] = '\0';
        gk_fail(e, GK_ERUNTIME, "shader compile failed (%s): %.900s", path, mapped);
        glDeleteShader(sh);
        sh = 0;
    }
    gk_shader_text_free(&t);
    return sh;
}

static GLuint link_program(GLuint *shaders, int n, const char *what, gk_err *e)
{
    GLuint prog = glCreateProgram();
    for (int i = 0; i < n; i++)
        glAttachShader(prog, shaders[i]);
    glLinkProgram(prog);
    for (int i = 0; i < n; i++)
        glDeleteShader(shaders[i]);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetProgramInfoLog(prog, sizeof log, NULL, log);
        gk_fail(e, GK_ERUNTIME, "shader link failed (%s): %s", what, log);
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}

static GLuint lookup(gk_program_cache *c, const char *key)
{
    for (int i = 0; i < c->n; i++)
        if (strcmp(c->p[i].key, key) == 0)
            return c->p[i].prog;
    return 0;
}

static GLuint remember(gk_program_cache *c, const char *key, GLuint prog)
{
    if (prog && c->n < MAX_PROGRAMS) {
        c->p[c->n].key = strdup(key);
        c->p[c->n].prog = prog;
        c->n++;
    }
    /* Past MAX_PROGRAMS the program still works; it is just compiled again next time (and
       leaked until the context goes): a hint that variants are exploding, not a failure. */
    return prog;
}

GLuint gk_program_get(gk_program_cache *c, const char *vert, const char *frag, const char *defines, gk_err *e)
{
    char key[1024];
    snprintf(key, sizeof key, "%s|%s|%s", vert, frag, defines ? defines : "");
    GLuint prog = lookup(c, key);
    if (prog)
        return prog;
    GLuint sh[2];
    if (!(sh[0] = compile(c, GL_VERTEX_SHADER, vert, defines, e)))
        return 0;
    if (!(sh[1] = compile(c, GL_FRAGMENT_SHADER, frag, defines, e))) {
        glDeleteShader(sh[0]);
        return 0;
    }
    char what[300];
    snprintf(what, sizeof what, "%s + %s", vert, frag);
    return remember(c, key, link_program(sh, 2, what, e));
}

GLuint gk_program_get_compute(gk_program_cache *c, const char *comp, const char *defines, gk_err *e)
{
    char key[1024];
    snprintf(key, sizeof key, "%s|%s", comp, defines ? defines : "");
    GLuint prog = lookup(c, key);
    if (prog)
        return prog;
    GLuint sh[1];
    if (!(sh[0] = compile(c, GL_COMPUTE_SHADER, comp, defines, e)))
        return 0;
    return remember(c, key, link_program(sh, 1, comp, e));
}

void gk_uniform_1i(GLuint prog, const char *name, int v) { glUniform1i(glGetUniformLocation(prog, name), v); }
void gk_uniform_1f(GLuint prog, const char *name, float v) { glUniform1f(glGetUniformLocation(prog, name), v); }
void gk_uniform_2f(GLuint prog, const char *name, float x, float y) { glUniform2f(glGetUniformLocation(prog, name), x, y); }
void gk_uniform_3f(GLuint prog, const char *name, float x, float y, float z)
{
    glUniform3f(glGetUniformLocation(prog, name), x, y, z);
}
void gk_uniform_4f(GLuint prog, const char *name, float x, float y, float z, float w)
{
    glUniform4f(glGetUniformLocation(prog, name), x, y, z, w);
}
void gk_uniform_mat4(GLuint prog, const char *name, const float *m)
{
    glUniformMatrix4fv(glGetUniformLocation(prog, name), 1, GL_FALSE, m);
}
void gk_uniform_mat4v(GLuint prog, const char *name, int count, const float *m)
{
    glUniformMatrix4fv(glGetUniformLocation(prog, name), count, GL_FALSE, m);
}
