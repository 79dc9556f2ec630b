/* Button script parser; see script.h. */
#include "script.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const button_names[GK_BTN_COUNT] = {"next", "prev", "mode", "info"};

int gk_button_from_name(const char *name)
{
    for (int i = 0; i < GK_BTN_COUNT; i++)
        if (strcmp(name, button_names[i]) == 0)
            return i;
    return -1;
}

const char *gk_button_name(enum gk_button b)
{
    return (unsigned)b < GK_BTN_COUNT ? button_names[b] : "?";
}

static int push_edge(gk_script *s, int *cap, double t, int button, bool pressed, gk_err *e)
{
    if (s->count == *cap) {
        int ncap = *cap ? *cap * 2 : 32;
        gk_raw_edge *grown = realloc(s->edges, (size_t)ncap * sizeof *grown);
        if (!grown)
            return gk_fail(e, GK_ERUNTIME, "out of memory reading the button script");
        s->edges = grown;
        *cap = ncap;
    }
    s->edges[s->count++] = (gk_raw_edge){.time_s = t, .button = (enum gk_button)button, .pressed = pressed};
    return 0;
}

/* Stable insertion sort by time: scripts are short, and stability keeps "release, then press" of
 * the same instant in the order the script wrote them. */
static void sort_edges(gk_script *s)
{
    for (int i = 1; i < s->count; i++) {
        gk_raw_edge x = s->edges[i];
        int j = i - 1;
        while (j >= 0 && s->edges[j].time_s > x.time_s) {
            s->edges[j + 1] = s->edges[j];
            j--;
        }
        s->edges[j + 1] = x;
    }
}

/* Splits the next whitespace-separated token off *p into tok (NUL-terminated copy). */
static bool next_token(const char **p, char *tok, size_t size)
{
    const char *s = *p;
    while (*s == ' ' || *s == '\t' || *s == '\r')
        s++;
    if (!*s)
        return false;
    size_t n = 0;
    while (*s && *s != ' ' && *s != '\t' && *s != '\r') {
        if (n + 1 < size)
            tok[n++] = *s;
        s++;
    }
    tok[n] = '\0';
    *p = s;
    return true;
}

static int parse_line(const char *line, const char *name, int lineno, double *prev_t, gk_script *s,
                      int *cap, gk_err *e)
{
    char tok_time[64], tok_button[64], tok_action[64], tok_ms[64], tok_extra[64];
    const char *p = line;
    if (!next_token(&p, tok_time, sizeof tok_time))
        return 0; /* blank */
    char *end;
    errno = 0;
    double t = strtod(tok_time, &end);
    if (*end || errno || !isfinite(t) || t < 0)
        return gk_fail(e, GK_EINPUT, "%s:%d: bad time '%s' (seconds >= 0 expected)", name, lineno, tok_time);
    if (t < *prev_t)
        return gk_fail(e, GK_EINPUT, "%s:%d: time %s goes backwards (previous event at %g s)", name, lineno,
                       tok_time, *prev_t);
    if (!next_token(&p, tok_button, sizeof tok_button))
        return gk_fail(e, GK_EINPUT, "%s:%d: missing button after the time (next, prev, mode, info)", name,
                       lineno);
    int button = gk_button_from_name(tok_button);
    if (button < 0)
        return gk_fail(e, GK_EINPUT, "%s:%d: unknown button '%s' (next, prev, mode, info)", name, lineno,
                       tok_button);
    if (!next_token(&p, tok_action, sizeof tok_action))
        return gk_fail(e, GK_EINPUT, "%s:%d: missing action (click, press, release, hold MS)", name, lineno);
    double release_after = -1;
    bool press = true;
    if (strcmp(tok_action, "click") == 0) {
        release_after = GK_SCRIPT_CLICK_S;
    } else if (strcmp(tok_action, "press") == 0) {
    } else if (strcmp(tok_action, "release") == 0) {
        press = false;
    } else if (strcmp(tok_action, "hold") == 0) {
        if (!next_token(&p, tok_ms, sizeof tok_ms))
            return gk_fail(e, GK_EINPUT, "%s:%d: hold needs a duration in ms ('hold 800')", name, lineno);
        errno = 0;
        long ms = strtol(tok_ms, &end, 10);
        if (*end || errno || ms <= 0 || ms > 3600 * 1000)
            return gk_fail(e, GK_EINPUT, "%s:%d: bad hold duration '%s' (milliseconds > 0 expected)", name,
                           lineno, tok_ms);
        release_after = ms / 1000.0;
    } else {
        return gk_fail(e, GK_EINPUT, "%s:%d: unknown action '%s' (click, press, release, hold MS)", name,
                       lineno, tok_action);
    }
    if (next_token(&p, tok_extra, sizeof tok_extra))
        return gk_fail(e, GK_EINPUT, "%s:%d: trailing garbage '%s'", name, lineno, tok_extra);
    *prev_t = t;
    if (push_edge(s, cap, t, button, press, e))
        return -1;
    if (release_after > 0 && push_edge(s, cap, t + release_after, button, false, e))
        return -1;
    return 0;
}

int gk_script_parse(const char *text, const char *name, gk_script *out, gk_err *e)
{
    memset(out, 0, sizeof *out);
    int cap = 0, lineno = 0;
    double prev_t = 0;
    char line[512];
    for (const char *p = text; *p;) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        lineno++;
        if (len >= sizeof line) {
            gk_script_free(out);
            return gk_fail(e, GK_EINPUT, "%s:%d: line too long", name, lineno);
        }
        memcpy(line, p, len);
        line[len] = '\0';
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        if (parse_line(line, name, lineno, &prev_t, out, &cap, e)) {
            gk_script_free(out);
            return -1;
        }
        p += len + (nl ? 1 : 0);
    }
    sort_edges(out);
    return 0;
}

int gk_script_load(const char *path, gk_script *out, gk_err *e)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "rb");
    if (!f)
        return gk_fail(e, GK_EINPUT, "%s: cannot read the button script: %s", path, strerror(errno));
    char *text = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 4096 + 1 > cap) {
            cap = cap ? cap * 2 : 8192;
            if (cap > (64u << 20)) {
                free(text);
                fclose(f);
                return gk_fail(e, GK_EINPUT, "%s: button script larger than 64 MiB", path);
            }
            char *grown = realloc(text, cap);
            if (!grown) {
                free(text);
                fclose(f);
                return gk_fail(e, GK_ERUNTIME, "%s: out of memory", path);
            }
            text = grown;
        }
        size_t n = fread(text + len, 1, 4096, f);
        len += n;
        if (n < 4096)
            break;
    }
    bool failed = ferror(f);
    fclose(f);
    if (failed) {
        free(text);
        return gk_fail(e, GK_EINPUT, "%s: read error", path);
    }
    text[len] = '\0';
    if (memchr(text, '\0', len)) {
        free(text);
        return gk_fail(e, GK_EINPUT, "%s: not a text file (contains NUL bytes)", path);
    }
    int rc = gk_script_parse(text, path, out, e);
    free(text);
    return rc;
}

void gk_script_free(gk_script *s)
{
    free(s->edges);
    s->edges = NULL;
    s->count = s->next = 0;
}
