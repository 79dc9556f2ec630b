/* What the bench's outputs share (bench_output.c): a row's key columns and numbers in a CSV, gnuplot
 * run on a script into files renamed into place, and the names rows go by. */
#ifndef GK_BENCH_CHART_H
#define GK_BENCH_CHART_H

#include <stdio.h>

#include "bench.h"

/* "scene,method,KNOB..." (no newline), and a row's values of those columns. */
void gk_bench_csv_key_header(FILE *f, const gk_bench_result *r);
void gk_bench_csv_key(FILE *f, const gk_bench_result *r, const gk_bench_row *row);
/* ",V" (%.6g), "," for NaN, ",inf" for infinity. */
void gk_bench_put_num(FILE *f, double v);

/* Writes a gnuplot script to f drawing into png and svg. */
typedef void (*gk_bench_script_fn)(FILE *f, const void *ctx, const char *png, const char *svg);

/* Keeps the script at gp (`gnuplot GP` redraws), runs it and renames png and svg into place.
 * Without gnuplot, or when it fails, logs and returns 0 with no images; -1 on an I/O error. */
int gk_bench_draw(const char *gp, gk_bench_script_fn script, const void *ctx, const char *png, const char *svg,
                  gk_err *e);

/* Row i's name on a chart: its method and the values of the knobs that vary among its scene's and
 * method's rows ("vct 64/9/1"). */
void gk_bench_row_name(const gk_bench_result *r, int i, char *out, int len);

#endif
