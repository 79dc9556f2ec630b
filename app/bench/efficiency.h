/* Each pass's efficiency (#21): its useful fetches (app/gl/pass_work.h, counted or modelled beside
 * the pass) per second of its measured time, as a fraction of this machine's limit for that kind of
 * fetch (`gikiosk bench --roofline`, roofline.csv). `gikiosk bench --roofline-csv FILE` writes
 * DIR/efficiency.csv and per scene DIR/efficiency-SCENE.png/.svg, a bar per measured pass. */
#ifndef GK_BENCH_EFFICIENCY_H
#define GK_BENCH_EFFICIENCY_H

#include "base/err.h"
#include "bench.h"
#include "roofline.h"

typedef struct gk_fetch_limit {
    char name[48];          /* roofline.csv's name: the kind of fetch */
    double fetches_per_s;
} gk_fetch_limit;

/* Reads roofline.csv (gk_roofline_write_csv's columns). Returns the number of limits, or -1 with
 * GK_EINPUT naming the file and line (a missing column, a rate that is not a positive number) or
 * GK_ERUNTIME (cannot read). */
int gk_fetch_limits_read(const char *path, gk_fetch_limit *out, int max, gk_err *e);
/* The limit of kind `name`, or 0 when roofline.csv has no such kind. */
double gk_fetch_limit_of(const gk_fetch_limit *lim, int n, const char *name);

/* (fetches / (pass_ms / 1000)) / limit: 1 = the pass fetches as fast as the micro-benchmark does.
 * NaN when the pass took no time or the limit is unknown. */
double gk_pass_efficiency(double fetches, double pass_ms, double limit_per_s);

/* DIR/efficiency.csv: scene,method,KNOBS...,pass,kind,fetches,pass_ms,fetches_per_s,
 * limit_fetches_per_s,efficiency -- one line per row and pass with a work model (rows without one
 * write nothing) -- and per scene DIR/efficiency-SCENE.{dat,gp,png,svg} (without gnuplot: no images). */
int gk_bench_write_efficiency(const gk_bench_result *r, const gk_fetch_limit *lim, int n_lim, const char *dir,
                              gk_err *e);

#endif
