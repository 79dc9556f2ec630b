/* The bench's outputs: bench.csv and the speed-against-accuracy charts (gnuplot). */
#include "bench.h"
#include "bench_chart.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/csv.h"
#include "base/log.h"
#include "base/outfile.h"

void gk_bench_put_num(FILE *f, double v)
{
    if (isnan(v))
        fputs(",", f);
    else if (isinf(v))
        fputs(",inf", f);
    else
        fprintf(f, ",%.6g", v);
}

void gk_bench_csv_key_header(FILE *f, const gk_bench_result *r)
{
    fputs("scene,method", f);
    for (int k = 0; k < r->budget.n; k++)
        fprintf(f, ",%s", r->budget.def[k]->name);
}

void gk_bench_csv_key(FILE *f, const gk_bench_result *r, const gk_bench_row *row)
{
    gk_csv_field(f, row->scene); /* a scene name is a file name: quoted if it holds a comma */
    fputc(',', f);
    gk_csv_field(f, row->method);
    for (int k = 0; k < r->budget.n; k++)
        fprintf(f, ",%s", r->budget.def[k]->values[row->level[k]]);
}

int gk_bench_write_csv(const gk_bench_result *r, const char *path, gk_err *e)
{
    gk_outfile o; /* complete or not at all: a temporary file renamed into place */
    if (gk_outfile_open(&o, path, e))
        return -1;
    FILE *f = o.f;
    gk_bench_csv_key_header(f, r);
    fputs(",frame_ms_median,frame_ms_p95,reference,rel_rmse,ssim,psnr,mean_ratio,test_mean,caustic_rel_rmse,"
          "caustic_mean_ratio,pareto,chosen", f);
    for (int p = 0; p < r->n_passes; p++)
        fprintf(f, ",%s_ms", r->pass_names[p]);
    fputc('\n', f);
    for (int i = 0; i < r->n_rows; i++) {
        const gk_bench_row *row = &r->rows[i];
        gk_bench_csv_key(f, r, row);
        gk_bench_put_num(f, row->frame_ms_median);
        gk_bench_put_num(f, row->frame_ms_p95);
        fputc(',', f);
        gk_csv_field(f, row->reference);
        gk_bench_put_num(f, row->rel_rmse);
        gk_bench_put_num(f, row->ssim);
        gk_bench_put_num(f, row->psnr);
        gk_bench_put_num(f, row->mean_ratio);
        gk_bench_put_num(f, row->test_mean);
        gk_bench_put_num(f, row->caustic_rel_rmse);
        gk_bench_put_num(f, row->caustic_mean_ratio);
        fprintf(f, ",%d,%d", row->pareto ? 1 : 0, row->chosen ? 1 : 0);
        for (int p = 0; p < r->n_passes; p++)
            gk_bench_put_num(f, row->pass_ms[p]);
        fputc('\n', f);
    }
    return gk_outfile_commit(&o, e);
}

/* Does knob k take more than one value among the rows of this scene and method? */
static bool knob_varies(const gk_bench_result *r, const gk_bench_row *row, int k)
{
    for (int j = 0; j < r->n_rows; j++)
        if (!strcmp(r->rows[j].scene, row->scene) && !strcmp(r->rows[j].method, row->method) &&
            r->rows[j].level[k] != row->level[k])
            return true;
    return false;
}

/* The series a row is drawn in: its method when the scene has several, else the value of the
   first knob the sweep varies (the shadow method of a shadow sweep), so the chart separates what
   the engineer compares. *series_knob receives that knob (-1: the method). */
static void row_series(const gk_bench_result *r, int i, bool several_methods, char *out, int len, int *series_knob)
{
    const gk_bench_row *row = &r->rows[i];
    *series_knob = -1;
    if (!several_methods)
        for (int k = 0; k < r->budget.n && *series_knob < 0; k++)
            if (knob_varies(r, row, k))
                *series_knob = k;
    if (*series_knob < 0)
        snprintf(out, (size_t)len, "%s", row->method);
    else
        snprintf(out, (size_t)len, "%s=%s", r->budget.def[*series_knob]->name,
                 r->budget.def[*series_knob]->values[row->level[*series_knob]]);
}

/* A point's label: the values of the other knobs that vary. */
static void row_label(const gk_bench_result *r, int i, int series_knob, char *out, int len)
{
    out[0] = '\0';
    const gk_bench_row *row = &r->rows[i];
    for (int k = 0; k < r->budget.n; k++) {
        if (k == series_knob || !knob_varies(r, row, k))
            continue;
        int used = (int)strlen(out);
        snprintf(out + used, (size_t)(len - used), "%s%s", used ? "/" : "", r->budget.def[k]->values[row->level[k]]);
    }
}

void gk_bench_row_name(const gk_bench_result *r, int i, char *out, int len)
{
    char knobs[128];
    row_label(r, i, -1, knobs, sizeof knobs);
    snprintf(out, (size_t)len, "%s%s%s", r->rows[i].method, knobs[0] ? " " : "", knobs);
}

/* One kind of chart: its file prefix, the error on its y axis and what the axis calls it. */
typedef struct chart_kind {
    const char *prefix;                      /* "speed-accuracy" */
    double (*error)(const gk_bench_row *);   /* NaN: the row is not on this chart */
    const char *what;                        /* the title's words for the error */
    const char *axis;                        /* y label before the references' names */
} chart_kind;

static const chart_kind k_accuracy = {.prefix = "speed-accuracy", .error = gk_bench_row_error,
                                      .what = "error", .axis = "relative RMSE vs "};
static const chart_kind k_caustic = {.prefix = "speed-caustic", .error = gk_bench_row_caustic_error,
                                     .what = "caustic error (inside SCENE-caustics-mask.png)",
                                     .axis = "relative RMSE inside the caustic mask vs "};

/* The row marked as the kiosk's automatic choice for scene (with a measured error), or NULL. */
static const gk_bench_row *chosen_row(const gk_bench_result *r, const chart_kind *k, const char *scene)
{
    for (int i = 0; i < r->n_rows; i++)
        if (!strcmp(r->rows[i].scene, scene) && r->rows[i].chosen && !isnan(k->error(&r->rows[i])))
            return &r->rows[i];
    return NULL;
}

/* The gnuplot script of one scene's chart, writing png and svg. */
static void put_chart_script(FILE *f, const gk_bench_result *r, const chart_kind *k, const char *scene,
                             const char *dat, const char *gp, char series[][64], int n_series, const char *png,
                             const char *svg)
{
    fprintf(f, "# Speed against accuracy for %s: regenerate with `gnuplot %s`.\n", scene, gp);
    fprintf(f, "set title \"%s: %s against frame time (llvmpipe CPU times: compare as ratios)\"\n", scene, k->what);
    /* the references this scene's rows were measured against, named on the axis */
    char refs[256] = "";
    for (int i = 0; i < r->n_rows; i++) {
        const char *ref = r->rows[i].reference;
        if (strcmp(r->rows[i].scene, scene) || !ref[0] || strstr(refs, ref))
            continue;
        snprintf(refs + strlen(refs), sizeof refs - strlen(refs), "%s%s.exr", refs[0] ? ", " : "", ref);
    }
    fprintf(f, "set xlabel \"frame time (ms, log scale): median of %d frames, bar to their p95\"\nset ylabel \"%s%s\"\n",
            r->frames,
            k == &k_accuracy && gk_bench_black_reference(r->rows, r->n_rows, scene)
                ? "mean radiance, nits (the reference is black: all of it is leaked light) "
                : k->axis, refs);
    fputs("set logscale xy\nset grid\nset key outside right top\nset offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n",
          f);
    const gk_bench_row *chosen = chosen_row(r, k, scene);
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 0)
            fprintf(f, "set terminal pngcairo size 1000,640 font \"DejaVu Sans,10\" noenhanced\nset output \"%s\"\n", png);
        else
            fprintf(f, "set terminal svg size 1000,640 font \"DejaVu Sans,10\" noenhanced\nset output \"%s\"\n", svg);
        fputs("plot ", f);
        /* each point: the median frame time, a bar to the p95 of the same frames (the spread that
           tells timing noise from a real difference), the varying knobs as its label */
        for (int m = 0; m < n_series; m++)
            fprintf(f, "\"%s\" index %d using 1:2:1:3 with xerrorbars pt 7 ps 1.2 lc %d title \"%s\", \"%s\" index %d using 1:2:4 with labels offset 0,0.8 font \",7\" notitle, ",
                    dat, m, m + 1, series[m], dat, m);
        fprintf(f, "\"%s\" index %d using 1:2 with linespoints lw 2 dt 2 pt 6 ps 2 lc rgb \"black\" title \"Pareto front\"", dat, n_series);
        if (chosen)
            fprintf(f, ", \"%s\" index %d using 1:2 with points pt 3 ps 3.5 lw 2 lc rgb \"red\" title \"kiosk's choice at %.0f ms, %dx%d\"",
                    dat, n_series + 1, r->choice_target_ms, r->choice_width, r->choice_height);
        fputc('\n', f);
    }
}

/* Draws a chart by gnuplot (bench_chart.h). The script kept beside the chart names the final files
   (`gnuplot FILE.gp` regenerates them); the run itself draws into temporary files renamed into place
   when gnuplot succeeds. */
int gk_bench_draw(const char *gp, gk_bench_script_fn script, const void *ctx, const char *png, const char *svg,
                  gk_err *e)
{
    gk_outfile gp_out, run_gp, png_out, svg_out;
    if (gk_outfile_open(&gp_out, gp, e))
        return -1;
    script(gp_out.f, ctx, png, svg);
    if (gk_outfile_commit(&gp_out, e))
        return -1;
    if (gk_outfile_reserve(&png_out, png, e))
        return -1;
    if (gk_outfile_reserve(&svg_out, svg, e)) {
        gk_outfile_discard(&png_out);
        return -1;
    }
    if (gk_outfile_open(&run_gp, gp, e)) {
        gk_outfile_discard(&png_out);
        gk_outfile_discard(&svg_out);
        return -1;
    }
    script(run_gp.f, ctx, png_out.tmp, svg_out.tmp);
    fflush(run_gp.f);
    char cmd[2200];
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>&1", run_gp.tmp);
    FILE *p = ferror(run_gp.f) ? NULL : popen(cmd, "r");
    if (!p) {
        gk_outfile_discard(&run_gp);
        gk_outfile_discard(&png_out);
        gk_outfile_discard(&svg_out);
        return gk_fail(e, GK_ERUNTIME, "bench: cannot run gnuplot: %s", strerror(errno));
    }
    char line[512];
    while (fgets(line, sizeof line, p))
        gk_log("gnuplot: %s", strtok(line, "\n"));
    int status = pclose(p);
    gk_outfile_discard(&run_gp);
    if (status != 0) {
        gk_outfile_discard(&png_out);
        gk_outfile_discard(&svg_out);
        gk_log("bench: gnuplot failed on %s (charts skipped; the CSV is complete)", gp);
        return 0;
    }
    if (gk_outfile_commit(&png_out, e)) {
        gk_outfile_discard(&svg_out);
        return -1;
    }
    return gk_outfile_commit(&svg_out, e);
}

struct chart_script_args {
    const gk_bench_result *r;
    const chart_kind *k;
    const char *scene, *dat, *gp;
    char (*series)[64];
    int n_series;
};

static void put_chart_script_of(FILE *f, const void *ctx, const char *png, const char *svg)
{
    const struct chart_script_args *a = ctx;
    put_chart_script(f, a->r, a->k, a->scene, a->dat, a->gp, a->series, a->n_series, png, svg);
}

static int write_scene_chart(const gk_bench_result *r, const chart_kind *k, const char *dir, const char *scene,
                             gk_err *e)
{
    char dat[1024], gp[1024], png[1024], svg[1024];
    snprintf(dat, sizeof dat, "%s/%s-%s.dat", dir, k->prefix, scene);
    snprintf(gp, sizeof gp, "%s/%s-%s.gp", dir, k->prefix, scene);
    snprintf(png, sizeof png, "%s/%s-%s.png", dir, k->prefix, scene);
    if (snprintf(svg, sizeof svg, "%s/%s-%s.svg", dir, k->prefix, scene) >= (int)sizeof svg)
        return gk_fail(e, GK_EINPUT, "bench: the path '%s/%s-%s...' is too long", dir, k->prefix, scene);
    gk_outfile dat_out;
    if (gk_outfile_open(&dat_out, dat, e))
        return -1;
    FILE *f = dat_out.f;
    /* One gnuplot data block per method (separated by two blank lines), then the Pareto front
       sorted by time. */
    bool several_methods = false;
    for (int i = 0; i < r->n_rows; i++)
        for (int j = 0; j < r->n_rows; j++)
            several_methods |= !strcmp(r->rows[i].scene, scene) && !strcmp(r->rows[j].scene, scene) &&
                               strcmp(r->rows[i].method, r->rows[j].method) != 0;
    char series[32][64];
    int n_series = 0;
    for (int i = 0; i < r->n_rows; i++) {
        if (strcmp(r->rows[i].scene, scene) || isnan(k->error(&r->rows[i])))
            continue;
        char key[64];
        int sk;
        row_series(r, i, several_methods, key, sizeof key, &sk);
        bool seen = false;
        for (int m = 0; m < n_series; m++)
            seen |= !strcmp(series[m], key);
        if (!seen && n_series < 32)
            snprintf(series[n_series++], sizeof series[0], "%s", key);
    }
    for (int m = 0; m < n_series; m++) {
        fprintf(f, "# series %s\n", series[m]);
        for (int i = 0; i < r->n_rows; i++) {
            const gk_bench_row *row = &r->rows[i];
            char key[64], label[128];
            int sk;
            if (strcmp(row->scene, scene) || isnan(k->error(row)))
                continue;
            row_series(r, i, several_methods, key, sizeof key, &sk);
            if (strcmp(key, series[m]))
                continue;
            row_label(r, i, sk, label, sizeof label);
            fprintf(f, "%.6g %.6g %.6g \"%s\"\n", row->frame_ms_median, k->error(row), row->frame_ms_p95, label);
        }
        fputs("\n\n", f);
    }
    fputs("# pareto front\n", f);
    static bool front[GK_BENCH_MAX_ROWS]; /* the bench runs on one thread */
    gk_bench_pareto_by(r->rows, r->n_rows, scene, k->error, front);
    int idx[GK_BENCH_MAX_ROWS], n = 0;
    for (int i = 0; i < r->n_rows; i++)
        if (front[i])
            idx[n++] = i;
    for (int a = 1; a < n; a++) /* insertion sort by time: a handful of points */
        for (int b = a; b > 0 && r->rows[idx[b]].frame_ms_median < r->rows[idx[b - 1]].frame_ms_median; b--) {
            int t = idx[b];
            idx[b] = idx[b - 1];
            idx[b - 1] = t;
        }
    for (int a = 0; a < n; a++)
        fprintf(f, "%.6g %.6g\n", r->rows[idx[a]].frame_ms_median, k->error(&r->rows[idx[a]]));
    /* the kiosk's automatic choice (one point, or an empty block) */
    fputs("\n\n# kiosk's choice\n", f);
    const gk_bench_row *chosen = chosen_row(r, k, scene);
    if (chosen)
        fprintf(f, "%.6g %.6g\n", chosen->frame_ms_median, k->error(chosen));
    if (gk_outfile_commit(&dat_out, e))
        return -1;
    if (n_series == 0) {
        if (k == &k_accuracy)
            gk_log("bench: %s has no measured error (no reference): no chart", scene);
        else
            remove(dat); /* a scene without a caustic mask has no caustic chart, nor its data */
        return 0;
    }

    struct chart_script_args a = {r, k, scene, dat, gp, series, n_series};
    return gk_bench_draw(gp, put_chart_script_of, &a, png, svg, e);
}

int gk_bench_write_charts(const gk_bench_result *r, const char *dir, gk_err *e)
{
    for (int i = 0; i < r->n_rows; i++) {
        bool first = true;
        for (int j = 0; j < i && first; j++)
            first = strcmp(r->rows[j].scene, r->rows[i].scene) != 0;
        if (first && (write_scene_chart(r, &k_accuracy, dir, r->rows[i].scene, e) < 0 ||
                      write_scene_chart(r, &k_caustic, dir, r->rows[i].scene, e) < 0))
            return -1;
    }
    return 0;
}
