/* RFC 4180 fields (see csv.h). */
#include "csv.h"

#include <stdlib.h>
#include <string.h>

bool gk_csv_needs_quotes(const char *s) { return s && strpbrk(s, ",\"\r\n") != NULL; }

void gk_csv_field(FILE *f, const char *s)
{
    if (!s)
        return;
    if (!gk_csv_needs_quotes(s)) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static int put(gk_csv_record *r, char c)
{
    if (r->len + 1 >= r->cap) {
        size_t cap = r->cap ? r->cap * 2 : 256;
        char *b = realloc(r->buf, cap);
        if (!b)
            return -1;
        r->buf = b;
        r->cap = cap;
    }
    r->buf[r->len++] = c;
    return 0;
}

static int begin_field(gk_csv_record *r)
{
    if (r->n == r->cap_fields) {
        int cap = r->cap_fields ? r->cap_fields * 2 : 16;
        size_t *s = realloc(r->start, (size_t)cap * sizeof *s);
        if (!s)
            return -1;
        r->start = s;
        r->cap_fields = cap;
    }
    r->start[r->n++] = r->len;
    return 0;
}

int gk_csv_read(FILE *f, gk_csv_record *r)
{
    r->len = 0;
    r->n = 0;
    int c = getc(f);
    if (c == EOF)
        return 0;
    if (begin_field(r))
        return -1;
    bool quoted = false, at_start = true;
    for (;; c = getc(f)) {
        if (c == EOF) {
            if (quoted)
                return -1;
            break;
        }
        if (quoted) {
            if (c == '"') {
                int next = getc(f);
                if (next != '"') { /* the closing quote */
                    quoted = false;
                    if (next != EOF)
                        ungetc(next, f);
                    continue;
                }
            }
            if (put(r, (char)c))
                return -1;
            continue;
        }
        if (c == '"' && at_start) {
            quoted = true;
            at_start = false;
            continue;
        }
        if (c == '\r') {
            int next = getc(f);
            if (next == '\n')
                break;
            if (next != EOF)
                ungetc(next, f);
        }
        if (c == '\n')
            break;
        if (c == ',') {
            if (put(r, '\0') || begin_field(r))
                return -1;
            at_start = true;
            continue;
        }
        at_start = false;
        if (put(r, (char)c))
            return -1;
    }
    return put(r, '\0') ? -1 : 1;
}

const char *gk_csv_get(const gk_csv_record *r, int i) { return i >= 0 && i < r->n ? r->buf + r->start[i] : ""; }

void gk_csv_record_free(gk_csv_record *r)
{
    free(r->buf);
    free(r->start);
    memset(r, 0, sizeof *r);
}
