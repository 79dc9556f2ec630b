/* Frame statistics, per-scene summary and the --stats CSV (see stats.h). */
#include "stats.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/csv.h"
#include "base/log.h"
#include "base/outfile.h"

void gk_recent_clear(gk_recent *r) { memset(r, 0, sizeof *r); }

void gk_recent_push(gk_recent *r, float ms)
{
    r->ms[r->head] = ms;
    r->head = (r->head + 1) % GK_RECENT_FRAMES;
    if (r->count < GK_RECENT_FRAMES)
        r->count++;
}

float gk_recent_at(const gk_recent *r, int i)
{
    int oldest = (r->head - r->count + GK_RECENT_FRAMES) % GK_RECENT_FRAMES;
    return r->ms[(oldest + i) % GK_RECENT_FRAMES];
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double gk_percentile(double *v, long n, double q)
{
    if (n <= 0)
        return 0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    long rank = (long)(q * (double)n + 0.999999); /* nearest rank: ceil(q n), at least 1 */
    if (rank < 1)
        rank = 1;
    if (rank > n)
        rank = n;
    return v[rank - 1];
}

float gk_recent_percentile(const gk_recent *r, float q)
{
    double v[GK_RECENT_FRAMES];
    for (int i = 0; i < r->count; i++)
        v[i] = r->ms[i];
    return (float)gk_percentile(v, r->count, q);
}

/* ---- per-scene summary ---------------------------------------------------------------------- */

/* A kiosk runs for days: keep at most this many frame times per scene (8 MB) for the percentiles;
 * the frame count goes on. */
#define SUMMARY_MAX_SAMPLES (1L << 20)

void gk_summary_init(gk_summary *s) { memset(s, 0, sizeof *s); }

void gk_summary_at_floor(gk_summary *s, const char *scene, double frame_ms, double target_ms)
{
    for (int i = 0; i < s->n; i++) {
        gk_scene_summary *e = &s->scenes[i];
        if (strcmp(e->scene, scene) != 0)
            continue;
        if (e->floor_best_ms == 0 || frame_ms < e->floor_best_ms)
            e->floor_best_ms = frame_ms;
        e->target_ms = target_ms;
        if (frame_ms > target_ms)
            e->over_at_floor++;
    }
}

void gk_summary_add(gk_summary *s, const char *scene, const char *method, double frame_ms, bool judged,
                    const gk_budget *b)
{
    gk_scene_summary *e = NULL;
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->scenes[i].scene, scene))
            e = &s->scenes[i];
    if (!e) {
        if (s->n == GK_MAX_PLAYLIST)
            return;
        e = &s->scenes[s->n++];
        snprintf(e->scene, sizeof e->scene, "%s", scene);
    }
    snprintf(e->method, sizeof e->method, "%s", method);
    gk_budget_format_active(b, method, e->budgets, sizeof e->budgets);
    e->frames++;
    if (!judged) {
        e->warmup++;
        if (frame_ms > e->warmup_max_ms)
            e->warmup_max_ms = frame_ms;
        return;
    }
    if (e->n_ms == e->cap_ms && e->cap_ms < SUMMARY_MAX_SAMPLES) {
        long cap = e->cap_ms ? e->cap_ms * 2 : 256;
        double *m = realloc(e->ms, (size_t)cap * sizeof *m);
        if (m) {
            e->ms = m;
            e->cap_ms = cap;
        }
    }
    if (e->n_ms < e->cap_ms)
        e->ms[e->n_ms++] = frame_ms;
}

void gk_summary_print(gk_summary *s, FILE *f)
{
    for (int i = 0; i < s->n; i++) {
        gk_scene_summary *e = &s->scenes[i];
        double med = gk_percentile(e->ms, e->n_ms, 0.5);
        double p95 = gk_percentile(e->ms, e->n_ms, 0.95);
        double p99 = gk_percentile(e->ms, e->n_ms, 0.99);
        fprintf(f, "scene %s: %ld frames (%ld warm-up, max %.2f ms), judged: median %.2f ms, p95 %.2f ms, "
                   "p99 %.2f ms, method %s, budgets %s\n",
                e->scene, e->frames, e->warmup, e->warmup_max_ms, med, p95, p99, e->method,
                e->budgets[0] ? e->budgets : "-");
        if (e->over_at_floor > 0)
            fprintf(f, "scene %s: cannot meet the %.0f ms target: %ld judged frames over it with every knob at its "
                       "floor (the fastest at the floor %.2f ms)\n",
                    e->scene, e->target_ms, e->over_at_floor, e->floor_best_ms);
    }
}

void gk_summary_free(gk_summary *s)
{
    for (int i = 0; i < s->n; i++)
        free(s->scenes[i].ms);
    gk_summary_init(s);
}

/* ---- CSV ------------------------------------------------------------------------------------ */

#define MAX_PASS_NAMES 64
/* A spool that exists is a previous run's rows (a run killed by SIGKILL): never overwritten; the
   next free name FILE.part-2 ... FILE.part-99 is used instead. */
#define MAX_SPOOL_TRIES 99

struct gk_stats_csv {
    char *path, *spool_path;
    FILE *spool;
    bool truth;                /* the error and truth_spp columns (the kiosk's ground truth runs) */
    double error;              /* for the next row: NAN = none yet */
    long truth_spp;
    int n_pass;
    char pass[MAX_PASS_NAMES][GK_PASS_PATH_LEN];
};

static void csv_free(gk_stats_csv *c)
{
    if (c->spool)
        fclose(c->spool);
    free(c->path);
    free(c->spool_path);
    free(c);
}

/* The spool: a CSV of its own (RFC 4180), one row per frame, flushed at every row, so whatever
   ends the run (SIGKILL, a power cut, a full disk at the end) its rows stay readable:
   frame,time_s,scene,method,frame_ms,passes_ms,budgets with passes_ms = "PATH=MS PATH=MS ..." and
   budgets = "KNOB=VALUE ...". The wide CSV is made from it at the end, when the pass union is known. */
static const char SPOOL_HEADER[] = "frame,time_s,scene,method,frame_ms,passes_ms,budgets\n";
/* With the ground truth, an eighth field: "error=X truth_spp=N" (empty values while there is none). */
static const char SPOOL_HEADER_TRUTH[] = "frame,time_s,scene,method,frame_ms,passes_ms,budgets,truth\n";

static FILE *create_spool(gk_stats_csv *c, gk_err *e)
{
    size_t len = strlen(c->path) + 16;
    if (!(c->spool_path = malloc(len)))
        return NULL;
    for (int i = 1; i <= MAX_SPOOL_TRIES; i++) {
        if (i == 1)
            snprintf(c->spool_path, len, "%s.part", c->path);
        else
            snprintf(c->spool_path, len, "%s.part-%d", c->path, i);
        int fd = open(c->spool_path, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            FILE *f = fdopen(fd, "w+");
            if (!f)
                close(fd);
            return f;
        }
        if (errno != EEXIST)
            break;
    }
    gk_fail(e, GK_ERUNTIME, "--stats: cannot write '%s': %s", c->spool_path, strerror(errno));
    return NULL;
}

gk_stats_csv *gk_stats_csv_open(const char *path, gk_err *e) { return gk_stats_csv_open_truth(path, false, e); }

gk_stats_csv *gk_stats_csv_open_truth(const char *path, bool truth, gk_err *e)
{
    gk_stats_csv *c = calloc(1, sizeof *c);
    if (!c || !(c->path = strdup(path))) {
        free(c);
        gk_fail(e, GK_ERUNTIME, "--stats: out of memory");
        return NULL;
    }
    c->truth = truth;
    c->error = NAN;
    /* The spool is created beside the CSV now, so a directory that cannot be written fails before
       the run; the CSV itself is not touched until the run's rows are complete (an existing one
       stays as it was when this run fails). */
    if (!(c->spool = create_spool(c, e))) {
        if (e && !e->code)
            gk_fail(e, GK_ERUNTIME, "--stats: cannot write '%s': %s", path, strerror(errno));
        csv_free(c);
        return NULL;
    }
    if (fputs(truth ? SPOOL_HEADER_TRUTH : SPOOL_HEADER, c->spool) == EOF || fflush(c->spool) != 0) {
        gk_fail(e, GK_ERUNTIME, "--stats: cannot write '%s': %s", c->spool_path, strerror(errno));
        fclose(c->spool);
        c->spool = NULL;
        remove(c->spool_path);
        csv_free(c);
        return NULL;
    }
    gk_log("stats: rows spooled to %s until the run ends", c->spool_path);
    return c;
}

const char *gk_stats_csv_spool_path(const gk_stats_csv *c) { return c ? c->spool_path : NULL; }

static int pass_index(gk_stats_csv *c, const char *name)
{
    for (int i = 0; i < c->n_pass; i++)
        if (!strcmp(c->pass[i], name))
            return i;
    if (c->n_pass == MAX_PASS_NAMES)
        return -1;
    snprintf(c->pass[c->n_pass], sizeof c->pass[0], "%s", name);
    return c->n_pass++;
}

/* frame_ms is the report's total (the sum of its top-level passes); every pass of the report is
 * a column named by its dotted path ("gi.vct_trace"), so a nested pass is never mistaken for a
 * top-level one. */
int gk_stats_csv_row(gk_stats_csv *c, long frame, double time_s, const char *scene, const char *method,
                     const gk_frame_report *report, const gk_budget *b, gk_err *e)
{
    FILE *f = c->spool;
    fprintf(f, "%ld,%.6f,", frame, time_s);
    gk_csv_field(f, scene);
    fputc(',', f);
    gk_csv_field(f, method);
    fprintf(f, ",%.3f,", report->total_ms);
    for (int i = 0; i < report->n; i++) {
        char path[GK_PASS_PATH_LEN];
        gk_frame_report_path(report, i, path, sizeof path);
        pass_index(c, path);
        fprintf(f, "%s%s=%.3f", i ? " " : "", path, report->pass[i].ms);
    }
    fputc(',', f);
    /* knob values hold no comma, quote, space or '=' (budget.h's value strings are tokens) */
    for (int i = 0; i < b->n; i++)
        fprintf(f, "%s%s=%s", i ? " " : "", b->def[i]->name, b->def[i]->values[b->level[i]]);
    if (c->truth) {
        fputs(",error=", f);
        if (isfinite(c->error))
            fprintf(f, "%.6g", c->error);
        fputs(" truth_spp=", f);
        if (c->truth_spp > 0)
            fprintf(f, "%ld", c->truth_spp);
    }
    fputc('\n', f);
    /* flushed at every row: a row in the spool survives SIGKILL */
    if (fflush(f) != 0 || ferror(f))
        return gk_fail(e, GK_ERUNTIME, "--stats: cannot write '%s': %s", c->spool_path, strerror(errno));
    return 0;
}

void gk_stats_csv_truth(gk_stats_csv *c, double error, long truth_spp)
{
    c->error = error;
    c->truth_spp = truth_spp;
}

/* "NAME=VALUE NAME=VALUE": the value of name, or NULL. Writes the value's length to *len. */
static const char *pair_value(const char *list, const char *name, size_t *len)
{
    size_t n = strlen(name);
    for (const char *p = list; p && *p;) {
        while (*p == ' ')
            p++;
        const char *end = strchr(p, ' ');
        if (!end)
            end = p + strlen(p);
        if ((size_t)(end - p) > n && !strncmp(p, name, n) && p[n] == '=') {
            *len = (size_t)(end - p - (ptrdiff_t)n - 1);
            return p + n + 1;
        }
        p = end;
    }
    return NULL;
}

static void write_wide_csv(gk_stats_csv *c, const gk_budget *b, FILE *out, gk_csv_record *rec)
{
    fputs("frame,time_s,scene,method,frame_ms", out);
    for (int i = 0; i < c->n_pass; i++)
        fprintf(out, ",%s_ms", c->pass[i]);
    for (int i = 0; i < b->n; i++)
        fprintf(out, ",%s", b->def[i]->name);
    if (c->truth)
        fputs(",error,truth_spp", out);
    fputc('\n', out);
    rewind(c->spool);
    bool header = true;
    while (gk_csv_read(c->spool, rec) == 1) {
        if (header || rec->n < 7) { /* the spool's header; a row cut short by a crash */
            header = false;
            continue;
        }
        for (int i = 0; i < 5; i++) {
            if (i)
                fputc(',', out);
            gk_csv_field(out, gk_csv_get(rec, i));
        }
        for (int i = 0; i < c->n_pass; i++) {
            size_t len;
            const char *v = pair_value(gk_csv_get(rec, 5), c->pass[i], &len);
            fprintf(out, ",%.*s", v ? (int)len : 0, v ? v : ""); /* empty: the pass did not run */
        }
        for (int i = 0; i < b->n; i++) {
            size_t len;
            const char *v = pair_value(gk_csv_get(rec, 6), b->def[i]->name, &len);
            fprintf(out, ",%.*s", v ? (int)len : 0, v ? v : "");
        }
        for (int i = 0; c->truth && i < 2; i++) {
            size_t len;
            const char *v = rec->n > 7 ? pair_value(gk_csv_get(rec, 7), i ? "truth_spp" : "error", &len) : NULL;
            fprintf(out, ",%.*s", v ? (int)len : 0, v ? v : ""); /* empty: no truth yet */
        }
        fputc('\n', out);
    }
}

int gk_stats_csv_close(gk_stats_csv *c, const gk_budget *b, gk_err *e)
{
    if (!c)
        return 0;
    gk_outfile out;
    gk_csv_record rec = {0};
    int rc = gk_outfile_open(&out, c->path, e);
    if (rc == 0) {
        write_wide_csv(c, b, out.f, &rec);
        if (ferror(c->spool)) {
            gk_fail(e, GK_ERUNTIME, "--stats: cannot read back '%s': %s", c->spool_path, strerror(errno));
            gk_outfile_discard(&out);
            rc = -1;
        } else {
            rc = gk_outfile_commit(&out, e);
        }
    }
    gk_csv_record_free(&rec);
    if (rc == 0) {
        remove(c->spool_path);
    } else {
        /* The rows are not lost: the spool stays, a CSV of its own, and the message says where. */
        if (e) { /* the spool's name first: it is what must not be cut off */
            char why[sizeof e->msg];
            snprintf(why, sizeof why, "%s", e->msg);
            if (snprintf(e->msg, sizeof e->msg, "--stats: the rows are kept in '%s' (%s)", c->spool_path, why) < 0)
                e->msg[0] = '\0';
        }
    }
    csv_free(c);
    return rc;
}
