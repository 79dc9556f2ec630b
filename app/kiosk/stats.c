/* Frame statistics, per-scene summary and the --stats CSV (see stats.h). */
#include "stats.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

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

struct gk_stats_csv {
    char path[512], spool_path[520];
    FILE *spool;
    int n_pass;
    char pass[MAX_PASS_NAMES][GK_PASS_PATH_LEN];
};

gk_stats_csv *gk_stats_csv_open(const char *path, gk_err *e)
{
    gk_stats_csv *c = calloc(1, sizeof *c);
    if (!c) {
        gk_fail(e, GK_ERUNTIME, "--stats: out of memory");
        return NULL;
    }
    snprintf(c->path, sizeof c->path, "%s", path);
    snprintf(c->spool_path, sizeof c->spool_path, "%s.part", path);
    /* Open the final file once now, so a bad path fails before the run rather than after it. */
    FILE *probe = fopen(path, "w");
    if (!probe || !(c->spool = fopen(c->spool_path, "w+"))) {
        gk_fail(e, GK_ERUNTIME, "--stats: cannot write '%s': %s", probe ? c->spool_path : path, strerror(errno));
        if (probe)
            fclose(probe);
        free(c);
        return NULL;
    }
    fclose(probe);
    return c;
}

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

/* Spool line: "frame,time_s,scene,method,frame_ms\tIDX=MS IDX=MS\tLEVEL LEVEL ...". frame_ms is
 * the report's total (the sum of its top-level passes); every pass of the report is a column named
 * by its dotted path ("gi.vct_trace"), so a nested pass is never mistaken for a top-level one. */
int gk_stats_csv_row(gk_stats_csv *c, long frame, double time_s, const char *scene, const char *method,
                     const gk_frame_report *report, const gk_budget *b, gk_err *e)
{
    fprintf(c->spool, "%ld,%.6f,%s,%s,%.3f\t", frame, time_s, scene, method, report->total_ms);
    for (int i = 0; i < report->n; i++) {
        char path[GK_PASS_PATH_LEN];
        gk_frame_report_path(report, i, path, sizeof path);
        int k = pass_index(c, path);
        if (k >= 0)
            fprintf(c->spool, "%d=%.3f ", k, report->pass[i].ms);
    }
    fputc('\t', c->spool);
    for (int i = 0; i < b->n; i++)
        fprintf(c->spool, "%d ", b->level[i]);
    if (fputc('\n', c->spool) == EOF)
        return gk_fail(e, GK_ERUNTIME, "--stats: cannot write '%s': %s", c->spool_path, strerror(errno));
    return 0;
}

int gk_stats_csv_close(gk_stats_csv *c, const gk_budget *b, gk_err *e)
{
    if (!c)
        return 0;
    int rc = 0;
    FILE *out = fopen(c->path, "w");
    if (!out) {
        rc = gk_fail(e, GK_ERUNTIME, "--stats: cannot write '%s': %s", c->path, strerror(errno));
        goto done;
    }
    fputs("frame,time_s,scene,method,frame_ms", out);
    for (int i = 0; i < c->n_pass; i++)
        fprintf(out, ",%s_ms", c->pass[i]);
    for (int i = 0; i < b->n; i++)
        fprintf(out, ",%s", b->def[i]->name);
    fputc('\n', out);
    rewind(c->spool);
    char line[4096];
    while (fgets(line, sizeof line, c->spool)) {
        char *t1 = strchr(line, '\t'), *t2 = t1 ? strchr(t1 + 1, '\t') : NULL;
        if (!t2)
            continue;
        *t1 = *t2 = '\0';
        double ms[MAX_PASS_NAMES];
        int have[MAX_PASS_NAMES] = {0};
        char *save = NULL;
        for (char *tok = strtok_r(t1 + 1, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
            int k;
            double v;
            if (sscanf(tok, "%d=%lf", &k, &v) == 2 && k >= 0 && k < MAX_PASS_NAMES) {
                ms[k] = v;
                have[k] = 1;
            }
        }
        fputs(line, out);
        for (int i = 0; i < c->n_pass; i++) {
            if (have[i])
                fprintf(out, ",%.3f", ms[i]);
            else
                fputs(",", out); /* the pass did not run this frame (another method) */
        }
        save = NULL;
        char *tok = strtok_r(t2 + 1, " \n", &save);
        for (int i = 0; i < b->n; i++) {
            int lv = tok ? atoi(tok) : b->level[i];
            if (lv < 0 || lv >= b->def[i]->n_values)
                lv = b->level[i];
            fprintf(out, ",%s", b->def[i]->values[lv]);
            tok = tok ? strtok_r(NULL, " \n", &save) : NULL;
        }
        fputc('\n', out);
    }
    if (fclose(out) != 0)
        rc = gk_fail(e, GK_ERUNTIME, "--stats: cannot write '%s': %s", c->path, strerror(errno));
done:
    fclose(c->spool);
    remove(c->spool_path);
    free(c);
    return rc;
}
