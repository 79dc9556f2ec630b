/* Each pass's efficiency (efficiency.h): roofline.csv read back, efficiency.csv and the bars. */
#include "efficiency.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/csv.h"
#include "base/outfile.h"
#include "bench_chart.h"

int gk_fetch_limits_read(const char *path, gk_fetch_limit *out, int max, gk_err *e)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return gk_fail(e, GK_ERUNTIME, "%s: cannot read (make it with `gikiosk bench --roofline`)", path);
    gk_csv_record rec = {0};
    int n = 0, line = 0, name_col = -1, rate_col = -1, got, rc = 0;
    while ((got = gk_csv_read(f, &rec)) == 1) {
        line++;
        if (line == 1) {
            for (int i = 0; i < rec.n; i++) {
                if (!strcmp(gk_csv_get(&rec, i), "name"))
                    name_col = i;
                if (!strcmp(gk_csv_get(&rec, i), "fetches_per_s"))
                    rate_col = i;
            }
            if (name_col < 0 || rate_col < 0) {
                rc = gk_fail(e, GK_EINPUT, "%s:1: no 'name' or 'fetches_per_s' column", path);
                break;
            }
            continue;
        }
        const char *rate = gk_csv_get(&rec, rate_col);
        char *end;
        double v = strtod(rate, &end);
        if (!rate[0] || *end || !(v > 0.0) || isinf(v)) {
            rc = gk_fail(e, GK_EINPUT, "%s:%d: fetches_per_s '%s' is not a positive number", path, line, rate);
            break;
        }
        if (n < max) {
            snprintf(out[n].name, sizeof out[n].name, "%s", gk_csv_get(&rec, name_col));
            out[n++].fetches_per_s = v;
        }
    }
    if (rc == 0 && got < 0)
        rc = gk_fail(e, GK_EINPUT, "%s:%d: a quoted field is not closed", path, line + 1);
    if (rc == 0 && line == 0)
        rc = gk_fail(e, GK_EINPUT, "%s: empty", path);
    gk_csv_record_free(&rec);
    fclose(f);
    return rc < 0 ? -1 : n;
}

double gk_fetch_limit_of(const gk_fetch_limit *lim, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(lim[i].name, name))
            return lim[i].fetches_per_s;
    return 0.0;
}

double gk_pass_efficiency(double fetches, double pass_ms, double limit_per_s)
{
    if (!(pass_ms > 0.0) || !(limit_per_s > 0.0))
        return NAN;
    return fetches / (pass_ms * 1e-3) / limit_per_s;
}

/* The column of a pass in the result, or -1 (a model for a pass that did not run). */
static int pass_col(const gk_bench_result *r, const char *pass)
{
    for (int p = 0; p < r->n_passes; p++)
        if (!strcmp(r->pass_names[p], pass))
            return p;
    return -1;
}

static double work_ms(const gk_bench_result *r, const gk_bench_row *row, const gk_pass_work *w)
{
    int col = pass_col(r, w->pass);
    return col < 0 ? NAN : row->pass_ms[col];
}

static int write_csv(const gk_bench_result *r, const gk_fetch_limit *lim, int n_lim, const char *path, gk_err *e)
{
    gk_outfile o;
    if (gk_outfile_open(&o, path, e))
        return -1;
    FILE *f = o.f;
    gk_bench_csv_key_header(f, r);
    fputs(",pass,kind,fetches,pass_ms,fetches_per_s,limit_fetches_per_s,efficiency\n", f);
    for (int i = 0; i < r->n_rows; i++) {
        const gk_bench_row *row = &r->rows[i];
        for (int w = 0; w < row->n_work; w++) {
            const gk_pass_work *pw = &row->work[w];
            double ms = work_ms(r, row, pw), limit = gk_fetch_limit_of(lim, n_lim, pw->kind);
            gk_bench_csv_key(f, r, row);
            fprintf(f, ",%s,%s,%.0f", pw->pass, pw->kind, pw->fetches);
            gk_bench_put_num(f, ms);
            gk_bench_put_num(f, ms > 0.0 ? pw->fetches / (ms * 1e-3) : NAN);
            gk_bench_put_num(f, limit > 0.0 ? limit : NAN);
            gk_bench_put_num(f, gk_pass_efficiency(pw->fetches, ms, limit));
            fputc('\n', f);
        }
    }
    return gk_outfile_commit(&o, e);
}

struct bars_args {
    const char *scene, *dat, *gp;
};

/* One bar per row and pass, in percent of its kind's limit. */
static void put_bars_script(FILE *f, const void *ctx, const char *png, const char *svg)
{
    const struct bars_args *a = ctx;
    fprintf(f, "# Each pass's efficiency on %s: regenerate with `gnuplot %s`.\n", a->scene, a->gp);
    fprintf(f, "set title \"%s: useful fetches per second of each pass, %% of this machine's limit for its "
               "kind of fetch (roofline.csv)\"\n", a->scene);
    fputs("set ylabel \"efficiency (% of the roofline limit)\"\nset yrange [0:*]\nset grid ytics\n"
          "set style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.8 border -1\n"
          "set boxwidth 0.8\nset xtics rotate by -35 left font \",8\"\nset key off\nset bmargin 10\n",
          f);
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 0)
            fprintf(f, "set terminal pngcairo size 1000,640 font \"DejaVu Sans,10\" noenhanced\nset output \"%s\"\n", png);
        else
            fprintf(f, "set terminal svg size 1000,640 font \"DejaVu Sans,10\" noenhanced\nset output \"%s\"\n", svg);
        fprintf(f, "plot \"%s\" using 2:xtic(1) lc rgb \"#4477aa\", \"\" using 0:2:(sprintf(\"%%.1f\", $2)) "
                   "with labels offset 0,0.7 font \",8\"\n", a->dat);
    }
}

static int write_scene_bars(const gk_bench_result *r, const gk_fetch_limit *lim, int n_lim, const char *dir,
                            const char *scene, gk_err *e)
{
    char dat[1024], gp[1024], png[1024], svg[1024];
    snprintf(dat, sizeof dat, "%s/efficiency-%s.dat", dir, scene);
    snprintf(gp, sizeof gp, "%s/efficiency-%s.gp", dir, scene);
    snprintf(png, sizeof png, "%s/efficiency-%s.png", dir, scene);
    if (snprintf(svg, sizeof svg, "%s/efficiency-%s.svg", dir, scene) >= (int)sizeof svg)
        return gk_fail(e, GK_EINPUT, "bench: the path '%s/efficiency-%s...' is too long", dir, scene);
    gk_outfile o;
    if (gk_outfile_open(&o, dat, e))
        return -1;
    int bars = 0;
    for (int i = 0; i < r->n_rows; i++) {
        const gk_bench_row *row = &r->rows[i];
        if (strcmp(row->scene, scene))
            continue;
        char name[160];
        gk_bench_row_name(r, i, name, sizeof name);
        for (int w = 0; w < row->n_work; w++) {
            const gk_pass_work *pw = &row->work[w];
            double eff = gk_pass_efficiency(pw->fetches, work_ms(r, row, pw), gk_fetch_limit_of(lim, n_lim, pw->kind));
            if (isnan(eff))
                continue;
            bool two_kinds = false; /* CSSM's direct pass: a bar per kind, named by it */
            for (int v = 0; v < row->n_work; v++)
                two_kinds |= v != w && !strcmp(row->work[v].pass, pw->pass);
            fprintf(o.f, "\"%s: %s%s%s\" %.6g\n", name, pw->pass, two_kinds ? " " : "", two_kinds ? pw->kind : "",
                    100.0 * eff);
            bars++;
        }
    }
    if (gk_outfile_commit(&o, e))
        return -1;
    if (bars == 0) {
        remove(dat); /* no pass of this scene has a work model */
        return 0;
    }
    struct bars_args a = {scene, dat, gp};
    return gk_bench_draw(gp, put_bars_script, &a, png, svg, e);
}

int gk_bench_write_efficiency(const gk_bench_result *r, const gk_fetch_limit *lim, int n_lim, const char *dir,
                              gk_err *e)
{
    char csv[1100];
    snprintf(csv, sizeof csv, "%s/efficiency.csv", dir);
    if (write_csv(r, lim, n_lim, csv, e))
        return -1;
    for (int i = 0; i < r->n_rows; i++) {
        bool first = true;
        for (int j = 0; j < i && first; j++)
            first = strcmp(r->rows[j].scene, r->rows[i].scene) != 0;
        if (first && write_scene_bars(r, lim, n_lim, dir, r->rows[i].scene, e) < 0)
            return -1;
    }
    return 0;
}
