#include "shader_source.h"

#include <ctype.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shader_embed.h"

typedef struct strbuf {
    char *p;
    size_t len, cap;
} strbuf;

static int sb_add(strbuf *b, const char *s, size_t n)
{
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap * 2 : 4096;
        while (cap < b->len + n + 1)
            cap *= 2;
        char *p = realloc(b->p, cap);
        if (!p)
            return -1;
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->len, s, n);
    b->len += n;
    b->p[b->len] = '\0';
    return 0;
}

static int sb_printf(strbuf *b, const char *fmt, int a, int c)
{
    char tmp[64];
    int n = snprintf(tmp, sizeof tmp, fmt, a, c);
    return sb_add(b, tmp, (size_t)n);
}

/* Returns a malloc'd copy of the file's text, or NULL. */
static char *load_file(const char *shader_dir, const char *path)
{
    if (shader_dir) {
        char full[1024];
        snprintf(full, sizeof full, "%s/%s", shader_dir, path);
        FILE *f = fopen(full, "rb");
        if (!f)
            return NULL;
        fseek(f, 0, SEEK_END);
        long n = ftell(f);
        fseek(f, 0, SEEK_SET);
        char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
        if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
            free(s);
            s = NULL;
        }
        fclose(f);
        if (s)
            s[n] = '\0';
        return s;
    }
    for (int i = 0; i < gk_embedded_shader_count; i++)
        if (strcmp(gk_embedded_shaders[i].path, path) == 0)
            return strdup(gk_embedded_shaders[i].source);
    return NULL;
}

/* Parses `#include "x"` (leading blanks allowed); writes x into name. */
static int parse_include(const char *line, size_t n, char *name, size_t name_len)
{
    size_t i = 0;
    while (i < n && (line[i] == ' ' || line[i] == '\t'))
        i++;
    if (n - i < 8 || strncmp(line + i, "#include", 8) != 0)
        return 0;
    i += 8;
    while (i < n && (line[i] == ' ' || line[i] == '\t'))
        i++;
    if (i >= n || line[i] != '"')
        return -1;
    size_t start = ++i;
    while (i < n && line[i] != '"')
        i++;
    if (i >= n || i - start == 0 || i - start >= name_len)
        return -1;
    memcpy(name, line + start, i - start);
    name[i - start] = '\0';
    return 1;
}

typedef struct expand_ctx {
    const char *dir;
    gk_shader_text *out;
    strbuf sb;
    const char *stack[17];
    int depth;
} expand_ctx;

static int expand_file(expand_ctx *c, const char *path, const char *from, int from_line, gk_err *e)
{
    for (int d = 0; d < c->depth; d++)
        if (strcmp(c->stack[d], path) == 0)
            return gk_fail(e, GK_ERUNTIME, "shaders_gles/%s:%d: #include cycle through '%s'", from, from_line, path);
    for (int k = 0; k < c->out->n_files; k++)
        if (strcmp(c->out->files[k], path) == 0)
            return 0; /* included once per program (a built-in guard, like #pragma once) */
    if (c->depth >= 16)
        return gk_fail(e, GK_ERUNTIME, "shaders_gles/%s:%d: #include nesting deeper than 16", from, from_line);
    if (c->out->n_files >= GK_SHADER_MAX_FILES)
        return gk_fail(e, GK_ERUNTIME, "shaders_gles/%s: more than %d included files", path, GK_SHADER_MAX_FILES);
    char *src = load_file(c->dir, path);
    if (!src) {
        if (from)
            return gk_fail(e, GK_ERUNTIME, "shaders_gles/%s:%d: cannot find included shader '%s'%s%s", from,
                           from_line, path, c->dir ? " in " : " (embedded)", c->dir ? c->dir : "");
        return gk_fail(e, GK_ERUNTIME, "shader '%s' not found%s%s", path, c->dir ? " in " : " among the embedded shaders",
                       c->dir ? c->dir : "");
    }
    int index = c->out->n_files++;
    snprintf(c->out->files[index], sizeof c->out->files[index], "%s", path);
    c->stack[c->depth++] = c->out->files[index];
    int rc = sb_printf(&c->sb, "#line 1 %d\n", index, 0);
    int line_no = 0;
    for (const char *p = src; rc == 0 && *p;) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        line_no++;
        char name[128];
        int inc = parse_include(p, n, name, sizeof name);
        if (inc < 0) {
            rc = gk_fail(e, GK_ERUNTIME, "shaders_gles/%s:%d: malformed #include (want #include \"path\")", path, line_no);
        } else if (inc > 0) {
            rc = expand_file(c, name, path, line_no, e);
            if (rc == 0)
                rc = sb_printf(&c->sb, "#line %d %d\n", line_no + 1, index);
        } else {
            rc = sb_add(&c->sb, p, n);
            if (rc == 0)
                rc = sb_add(&c->sb, "\n", 1);
        }
        p = nl ? nl + 1 : p + n;
    }
    c->depth--;
    free(src);
    return rc;
}

int gk_shader_expand(const char *shader_dir, const char *path, int gles, const char *defines, gk_shader_text *out,
                     gk_err *e)
{
    memset(out, 0, sizeof *out);
    expand_ctx c = {.dir = shader_dir, .out = out};
    char head[128];
    snprintf(head, sizeof head, "#version %s es\n#define GK_GLES %d\n", gles >= 32 ? "320" : "310", gles >= 32 ? 32 : 31);
    int rc = sb_add(&c.sb, head, strlen(head));
    if (rc == 0 && defines)
        rc = sb_add(&c.sb, defines, strlen(defines));
    if (rc == 0 && defines && defines[0] && defines[strlen(defines) - 1] != '\n')
        rc = sb_add(&c.sb, "\n", 1);
    if (rc == 0)
        rc = expand_file(&c, path, NULL, 0, e);
    if (rc != 0) {
        if (e && e->code == GK_OK)
            gk_fail(e, GK_ERUNTIME, "shaders_gles/%s: out of memory", path);
        free(c.sb.p);
        out->text = NULL;
        return -1;
    }
    out->text = c.sb.p;
    return 0;
}

void gk_shader_text_free(gk_shader_text *t)
{
    free(t->text);
    t->text = NULL;
}

void gk_shader_map_log(const gk_shader_text *t, const char *log, char *out, int out_len)
{
    int o = 0;
    out[0] = '\0';
    for (const char *p = log; *p && o < out_len - 1;) {
        /* "K:LINE" at the start of a token: Mesa writes "0:12(5): error", glslang "ERROR: 0:12:". */
        bool at_token = p == log || p[-1] == ' ' || p[-1] == '\n';
        if (at_token && isdigit((unsigned char)*p)) {
            char *end;
            long k = strtol(p, &end, 10);
            if (*end == ':' && isdigit((unsigned char)end[1]) && k >= 0 && k < t->n_files) {
                o += snprintf(out + o, (size_t)(out_len - o), "shaders_gles/%s:", t->files[k]);
                p = end + 1;
                continue;
            }
        }
        out[o++] = *p++;
        out[o] = '\0';
    }
    if (o >= out_len)
        out[out_len - 1] = '\0';
}
