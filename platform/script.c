/* Button script parser; see script.h. */
#include "script.h"
#include "base/readfile.h"

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

/* Stable merge sort by time, O(n log n) whatever the overlap: presses come in the script's order,
 * but a long hold's release lands after every later press, and the insertion sort this replaces
 * went quadratic on such scripts (200k lines: 25 s). Stability keeps "release, then press" of the
 * same instant in the order the script wrote them. Returns the number of comparisons (tested). */
long gk_script_sort_edges(gk_raw_edge *edges, int n)
{
    long comparisons = 0;
    if (n < 2)
        return 0;
    gk_raw_edge *tmp = malloc((size_t)n * sizeof *tmp);
    if (!tmp) { /* out of memory: fall back to the insertion sort, still correct */
        for (int i = 1; i < n; i++) {
            gk_raw_edge x = edges[i];
            int j = i - 1;
            while (j >= 0 && (comparisons++, edges[j].time_s > x.time_s)) {
                edges[j + 1] = edges[j];
                j--;
            }
            edges[j + 1] = x;
        }
        return comparisons;
    }
    gk_raw_edge *src = edges, *dst = tmp;
    for (int width = 1; width < n; width *= 2) {
        for (int lo = 0; lo < n; lo += 2 * width) {
            int mid = lo + width < n ? lo + width : n, hi = lo + 2 * width < n ? lo + 2 * width : n;
            int i = lo, j = mid, k = lo;
            while (i < mid && j < hi) /* <=: the left run first on ties (stable) */
                dst[k++] = (comparisons++, src[j].time_s < src[i].time_s) ? src[j++] : src[i++];
            while (i < mid)
                dst[k++] = src[i++];
            while (j < hi)
                dst[k++] = src[j++];
        }
        gk_raw_edge *t = src;
        src = dst;
        dst = t;
    }
    if (src != edges)
        memcpy(edges, src, (size_t)n * sizeof *edges);
    free(tmp);
    return comparisons;
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
    gk_script_sort_edges(out->edges, out->count);
    return 0;
}

/* A script of 64 MiB is over a million events; a larger file is a mistake (or /dev/zero). */
#define SCRIPT_MAX_BYTES ((size_t)64 << 20)

int gk_script_load(const char *path, gk_script *out, gk_err *e)
{
    memset(out, 0, sizeof *out);
    char *text;
    size_t len;
    if (gk_read_text_file(path, "button script", SCRIPT_MAX_BYTES, &text, &len, e))
        return -1;
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
