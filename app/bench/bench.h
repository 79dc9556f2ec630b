/* `gikiosk bench` (DESIGN §3-4): sweeps scenes x methods x knob values on the mock platform,
 * measures frame time and error against the path-traced references, writes DIR/bench.csv and one
 * speed-against-accuracy chart per scene (DIR/speed-accuracy-SCENE.png/.svg, Pareto front marked).
 * On a CPU-only machine the frame times are llvmpipe CPU times: compare them as ratios only. */
#ifndef GK_BENCH_H
#define GK_BENCH_H

#include <stdbool.h>

#include "base/err.h"
#include "../render/renderer.h"
#include "../sched/budget.h"
#include "gl/pass_work.h"

#define GK_BENCH_MAX_AXES 6
/* Configurations of one bench run. `make calibrate`'s sweep over every scene had outgrown 1024 (it
   stopped at the 1025th, after half an hour of measuring); the rows are heap-allocated (calloc'd
   gk_bench_result, about 6 KB a row, untouched pages free), so the cap is generous. */
#define GK_BENCH_MAX_ROWS 4096
/* Pass columns of one bench run: the union of every row's frame report (a frame has at most
   GK_MAX_PASSES; every method of a scene together has more: cornell's about 40) */
#define GK_BENCH_MAX_PASSES 96

/* One sweep: the cartesian product of each axis's values. */
typedef struct gk_bench_sweep {
    int n_axes;
    char knob[GK_BENCH_MAX_AXES][32];
    int n_values[GK_BENCH_MAX_AXES];
    char values[GK_BENCH_MAX_AXES][GK_MAX_KNOB_VALUES][24];
} gk_bench_sweep;

typedef struct gk_bench_opts {
    char scenes[512];          /* comma list; "" = cornell,shadow-planes */
    char methods[256];         /* comma list; "" = every method that applies */
    char sweep[1024];          /* "KNOB=V1,V2;KNOB=V1,V2" (cartesian); "" = the default per method */
    char budget[1024];         /* "KNOB=VALUE,..." pinned in every configuration (--budget), before the sweep's */
    int width, height;         /* 0 = the reference's size */
    int frames, warmup;        /* timed frames per configuration, untimed frames before them */
    bool rebuild_gi;           /* GI methods redo their static work (voxelize, inject...) every frame */
    bool one_ruler;            /* every method of a scene against ONE reference (SCENE-1bounce.exr
                                  where it exists, else SCENE.exr), so methods compare on one
                                  axis; default: each against what it computes (none: -direct) */
    char out_dir[512];
    char roofline_csv[512];    /* roofline.csv of `bench --roofline`: also write each pass's efficiency
                                  (efficiency.h); "" = not */
    char scenes_dir[512];
    char refs_dir[512];
    int gles_version;
    const char *shader_dir;
    double target_ms;          /* the kiosk's choice is marked for this target (default 400: the
                                  kiosk's default) ... */
    int target_width, target_height; /* ... at this display size (default 640x360: `make run`) */
} gk_bench_opts;

typedef struct gk_bench_row {
    char scene[64], method[32];
    char reference[80];        /* the reference the error is measured against ("cornell-direct"), "" = none */
    int level[GK_MAX_KNOBS];   /* knob levels, in the budget's knob order */
    double frame_ms_median, frame_ms_p95;
    double rel_rmse, ssim, psnr, mean_ratio;  /* NaN without a reference */
    double test_mean;                         /* mean linear radiance (light-leak: the leak itself, as
                                                 its reference is black) */
    double caustic_rel_rmse, caustic_mean_ratio; /* the same two inside the scene's caustic mask
                                                 (REFS/SCENE-caustics-mask.png: where the reference
                                                 caustic exceeds 1/4 of its peak), against the row's
                                                 ruler (none's, the direct one, has no caustic: none is
                                                 measured against SCENE-1bounce.exr, else SCENE.exr):
                                                 how right the caustic is, which a
                                                 small bright region barely moves in the whole-image
                                                 error. NaN where the scene has no mask */
    double pass_ms[GK_BENCH_MAX_PASSES];      /* medians, in the order of pass_names */
    int n_work;                               /* the useful fetches of the passes with a work model
                                                 (app/gl/pass_work.h), of the last timed frame */
    gk_pass_work work[GK_MAX_PASS_WORK];
    bool pareto;
    bool chosen;               /* the kiosk's automatic choice for this scene (method at its default
                                  budgets) from the calibration, at opts.target_ms */
} gk_bench_row;

/* The error a row is charted and ranked by: rel_rmse; for a black reference (light-leak), where the
   relative error is infinite, the mean radiance of the image (all of it is error); NaN without a
   reference. */
double gk_bench_row_error(const gk_bench_row *row);
/* The caustic error a row is charted by (speed-caustic-SCENE.png): caustic_rel_rmse. */
double gk_bench_row_caustic_error(const gk_bench_row *row);
/* True when the rows of this scene are measured against a black reference. */
bool gk_bench_black_reference(const gk_bench_row *rows, int n, const char *scene);

typedef struct gk_bench_result {
    gk_budget budget;          /* the knob set (names, values) the levels refer to */
    int n_passes;
    char pass_names[GK_BENCH_MAX_PASSES][GK_PASS_PATH_LEN]; /* dotted report paths: "shadow", "gi.vct_trace" */
    int n_rows;
    gk_bench_row rows[GK_BENCH_MAX_ROWS];
    int frames;                /* timed frames per row (the spread bars' sample) */
    double choice_target_ms;   /* what rows[].chosen was chosen for (0: nothing marked) */
    int choice_width, choice_height;
} gk_bench_result;

/* Parses a sweep; knobs and values are checked against b (GK_EINPUT naming what is unknown). */
int gk_bench_sweep_parse(const char *text, const gk_budget *b, gk_bench_sweep *s, gk_err *e);
/* The default sweep of a method: for "none" shadow x shadow_map, else each knob the method owns,
 * one at a time (the others at their defaults) — returned as several sweeps. */
int gk_bench_default_sweeps(const gk_budget *b, const char *method, gk_bench_sweep *out, int max);
/* The calibration's sweep (`--sweep each`): every knob the scheduler may move for this method --
 * the renderer's own and the method's, not the fixed switches -- one at a time through the levels
 * it may choose by itself (up to auto_max_level), the default level left out (the run measures the
 * default configuration first). Returns the number of sweeps. */
int gk_bench_each_knob_sweeps(const gk_budget *b, const char *method, gk_bench_sweep *out, int max);
/* Number of combinations of a sweep, and the pin list ("K=V,K=V") of combination i. */
int gk_bench_sweep_count(const gk_bench_sweep *s);
void gk_bench_sweep_pins(const gk_bench_sweep *s, int index, char *out, int out_len);

/* Marks rows[i].pareto for the rows of one scene: on the front when no other row of that scene is
 * both at least as fast and strictly more accurate (rel_rmse), or strictly faster and as accurate. */
void gk_bench_mark_pareto(gk_bench_row *rows, int n);
/* The same front by another error (gk_bench_row_caustic_error), for the rows of `scene` only:
 * on_front[i] for each of the n rows (false for other scenes' rows and rows without that error). */
void gk_bench_pareto_by(const gk_bench_row *rows, int n, const char *scene, double (*error)(const gk_bench_row *),
                        bool *on_front);

/* Marks the row the kiosk would show in attract mode: the method gk_calibration_choose picks for
 * each scene (calibration c, target_ms at target_pixels), in its row at every knob's default level.
 * why[scene index] gets the account. Scenes without a calibrated method or such a row: none. */
struct gk_calibration;
void gk_bench_mark_choice(gk_bench_result *r, const struct gk_calibration *c, double target_ms, double target_pixels);

/* Runs everything and writes the outputs. Allocates the result (free()). */
int gk_bench_run(const gk_bench_opts *o, gk_bench_result **out, gk_err *e);
/* mkdir -p: 0, or -1 with GK_ERUNTIME naming the directory. */
int gk_bench_make_dir(const char *path, gk_err *e);
int gk_bench_write_csv(const gk_bench_result *r, const char *path, gk_err *e);
/* Writes DIR/speed-accuracy-SCENE.{dat,gp,png,svg}, and for a scene with a caustic mask also
 * DIR/speed-caustic-SCENE.{...} (the error inside the mask); without gnuplot logs and skips the images. */
int gk_bench_write_charts(const gk_bench_result *r, const char *dir, gk_err *e);

#endif
