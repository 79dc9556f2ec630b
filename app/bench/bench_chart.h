/* What the bench's charts share (bench_output.c): gnuplot run on a script into files renamed into
 * place, and the names rows go by. */
#ifndef GK_BENCH_CHART_H
#define GK_BENCH_CHART_H

#include <stdio.h>

#include "bench.h"

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
