#include "gl_program.h"

#include <ctype.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shader_source.h"

/* The cache grows as it must: a fixed cap of 96 ran out in one renderer's cache in a `bench --sweep
   each --rebuild-gi` over cornell, caustic-ring and glass-fog once the bench's counting variants (#21)
   were added, and a program past a cap has no uniforms (gk_program_uniforms fails), so a kiosk that
   meets more variants than a cap (scenes x methods x knob levels over a long run) would lose a pass.
   The variants are finite (shader files x their defines), so the cache is bounded by them. */
#define FIRST_CAPACITY 64
#define MAX_UNIFORM_BLOCKS 4 /* uniform structs per program (a program shared by two passes) */

typedef struct uniform_block {
    const gk_uniform_field *fields;
    void *values;
} uniform_block;

typedef struct cached_program {
    char *key;
    GLuint prog;
    char *source;       /* every stage's expanded source: the misspelt-uniform check reads it */
    uniform_block block[MAX_UNIFORM_BLOCKS];
} cached_program;

struct gk_program_cache {
    char *shader_dir;
    int gles;
    int n, capacity;
    cached_program *p; /* n of capacity in use; grown by doubling (remember) */
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
        free(c->p[i].source);
        for (int b = 0; b < MAX_UNIFORM_BLOCKS; b++)
            free(c->p[i].block[b].values);
    }
    free(c->p);
    free(c->shader_dir);
    free(c);
}

/* Appends text to *acc (malloc'd); best effort: the check it serves is skipped when it fails. */
static void append_source(char **acc, const char *text)
{
    size_t a = *acc ? strlen(*acc) : 0, b = strlen(text);
    char *s = realloc(*acc, a + b + 2);
    if (!s)
        return;
    memcpy(s + a, text, b);
    s[a + b] = '\n';
    s[a + b + 1] = '\0';
    *acc = s;
}

static GLuint compile(gk_program_cache *c, GLenum stage, const char *path, const char *defines, char **source,
                      gk_err *e)
{
    gk_shader_text t;
    if (gk_shader_expand(c->shader_dir, path, c->gles, defines, &t, e) != 0)
        return 0;
    append_source(source, t.text);
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

static GLuint remember(gk_program_cache *c, const char *key, GLuint prog, char *source)
{
    if (prog && c->n == c->capacity) {
        int grown = c->capacity ? 2 * c->capacity : FIRST_CAPACITY;
        cached_program *p = realloc(c->p, (size_t)grown * sizeof *p);
        if (p) {
            c->p = p;
            c->capacity = grown;
        }
    }
    if (prog && c->n < c->capacity) {
        memset(&c->p[c->n], 0, sizeof c->p[c->n]);
        c->p[c->n].key = strdup(key);
        c->p[c->n].prog = prog;
        c->p[c->n].source = source;
        c->n++;
    } else {
        free(source);
    }
    /* Only when memory runs out is a program not remembered: it still draws, but is compiled again
       next time and its uniforms fail with a message naming it (gk_program_uniforms). */
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
    char *source = NULL;
    if (!(sh[0] = compile(c, GL_VERTEX_SHADER, vert, defines, &source, e))) {
        free(source);
        return 0;
    }
    if (!(sh[1] = compile(c, GL_FRAGMENT_SHADER, frag, defines, &source, e))) {
        glDeleteShader(sh[0]);
        free(source);
        return 0;
    }
    char what[300];
    snprintf(what, sizeof what, "%s + %s", vert, frag);
    return remember(c, key, link_program(sh, 2, what, e), source);
}

GLuint gk_program_get_compute(gk_program_cache *c, const char *comp, const char *defines, gk_err *e)
{
    char key[1024];
    snprintf(key, sizeof key, "%s|%s", comp, defines ? defines : "");
    GLuint prog = lookup(c, key);
    if (prog)
        return prog;
    GLuint sh[1];
    char *source = NULL;
    if (!(sh[0] = compile(c, GL_COMPUTE_SHADER, comp, defines, &source, e))) {
        free(source);
        return 0;
    }
    return remember(c, key, link_program(sh, 1, comp, e), source);
}

/* True when the identifier `name` (up to '[') occurs in source as a whole word. */
static bool names_in_source(const char *source, const char *name)
{
    size_t len = strcspn(name, "[");
    char ident[128];   /* the identifier alone: "u_x[0]" is declared as "u_x[N]" */
    if (len >= sizeof ident)
        return false;
    memcpy(ident, name, len);
    ident[len] = '\0';
    for (const char *p = source; (p = strstr(p, ident)) != NULL; p++) {
        bool start = p == source || !(isalnum((unsigned char)p[-1]) || p[-1] == '_');
        char after = p[len];
        bool end = !(isalnum((unsigned char)after) || after == '_');
        if (start && end && strncmp(p, name, len) == 0)
            return true;
    }
    return false;
}

int gk_uniforms_resolve(GLuint prog, const char *source, const gk_uniform_field *fields, int n, void *out, gk_err *e)
{
    for (int i = 0; i < n; i++) {
        if (source && !names_in_source(source, fields[i].name))
            return gk_fail(e, GK_ERUNTIME, "uniform '%s' occurs nowhere in program %u's shaders (misspelt?)",
                           fields[i].name, prog);
        GLint loc = glGetUniformLocation(prog, fields[i].name);
        memcpy((char *)out + fields[i].offset, &loc, sizeof loc);
    }
    return 0;
}

const void *gk_program_uniforms(gk_program_cache *c, GLuint prog, const gk_uniform_field *fields, int n, size_t size,
                                gk_err *e)
{
    cached_program *p = NULL;
    for (int i = 0; i < c->n && !p; i++)
        if (c->p[i].prog == prog)
            p = &c->p[i];
    if (!p) {
        gk_fail(e, GK_ERUNTIME, "uniforms: program %u is not in this cache", prog);
        return NULL;
    }
    int free_slot = -1;
    for (int b = 0; b < MAX_UNIFORM_BLOCKS; b++) {
        if (p->block[b].fields == fields)
            return p->block[b].values;
        if (!p->block[b].fields && free_slot < 0)
            free_slot = b;
    }
    if (free_slot < 0) {
        gk_fail(e, GK_ERUNTIME, "uniforms: more than %d uniform structs for program %s", MAX_UNIFORM_BLOCKS, p->key);
        return NULL;
    }
    void *values = malloc(size ? size : 1);
    if (!values) {
        gk_fail(e, GK_ERUNTIME, "uniforms: out of memory");
        return NULL;
    }
    memset(values, 0xff, size); /* every GLint -1: a field the table does not list is "absent" */
    if (gk_uniforms_resolve(prog, p->source, fields, n, values, e) != 0) {
        gk_fail_prefix(e, "%s: ", p->key);
        free(values);
        return NULL;
    }
    p->block[free_slot].fields = fields;
    p->block[free_slot].values = values;
    return values;
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
