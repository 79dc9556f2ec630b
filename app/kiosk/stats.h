/* Frame statistics of the kiosk: the recent frame times the HUD shows (median, p95, graph), the
 * per-scene summary printed at the end of a run, and the --stats CSV (DESIGN §4):
 * `frame,time_s,scene,method,frame_ms,` then one PASS_ms column per render pass (the union of the
 * pass names seen during the run, in order of first appearance), then one column per budget knob
 * (its value). The pass union is only known at the end, so rows are spooled to FILE.part (a CSV
 * of its own, flushed at every row: it survives SIGKILL) and the CSV is written when the run ends,
 * through a temporary file renamed into place (base/outfile.h). No GL here: unit-tested. */
#ifndef GK_KIOSK_STATS_H
#define GK_KIOSK_STATS_H

#include <stdio.h>

#include "gl/frame_report.h"
#include "../sched/budget.h"
#include "config.h"

#define GK_RECENT_FRAMES 120

typedef struct gk_recent {
    float ms[GK_RECENT_FRAMES];   /* ring buffer */
    int count, head;              /* head: next write */
} gk_recent;

void gk_recent_clear(gk_recent *r);
void gk_recent_push(gk_recent *r, float ms);
/* Percentile q in [0, 1] (nearest rank) of the recent frames; 0 when empty. */
float gk_recent_percentile(const gk_recent *r, float q);
/* i-th oldest sample (0 = oldest). */
float gk_recent_at(const gk_recent *r, int i);

/* Percentile of an array (sorted in place), nearest rank. */
double gk_percentile(double *v, long n, double q);

typedef struct gk_scene_summary {
    char scene[GK_NAME_LEN];
    char method[32];              /* method of the scene's last frame */
    char budgets[512];            /* knob values at the scene's last frame */
    long frames;                  /* measured frames, judged and warm-up */
    long warmup;                  /* frames the scheduler did not judge (one-off costs) */
    double warmup_max_ms;
    double *ms;                   /* every judged frame time (capped, see stats.c) */
    long n_ms, cap_ms;
    long over_at_floor;           /* judged frames over the target with every knob at its floor */
    double floor_best_ms;         /* the fastest judged frame at the floor (0: none) */
    double target_ms;
} gk_scene_summary;

typedef struct gk_summary {
    int n;
    gk_scene_summary scenes[GK_MAX_PLAYLIST];
} gk_summary;

void gk_summary_init(gk_summary *s);
/* A judged frame of scene drawn with every knob at its floor: counted when over target_ms, so the
 * summary can say the scene cannot meet the target and the best it reached (call after
 * gk_summary_add for the same frame). */
void gk_summary_at_floor(gk_summary *s, const char *scene, double frame_ms, double target_ms);
/* judged: a frame the scheduler judged against the target; the others (warm-up after a scene,
 * method or level change) are counted apart, so one-off costs do not spoil the percentiles. */
void gk_summary_add(gk_summary *s, const char *scene, const char *method, double frame_ms, bool judged,
                    const gk_budget *b);
/* One line per scene: "scene NAME: N frames (W warm-up, max X ms), judged: median X ms, p95 Y ms,
 * p99 Z ms, method M, budgets K=V,...". */
void gk_summary_print(gk_summary *s, FILE *f);
void gk_summary_free(gk_summary *s);

typedef struct gk_stats_csv gk_stats_csv;

gk_stats_csv *gk_stats_csv_open(const char *path, gk_err *e);
/* truth: the kiosk's ground truth runs (truth.h): two more columns after the knobs, `error` (the
 * shown method's rel RMSE against the truth, as last measured) and `truth_spp` (the truth's samples
 * per pixel then), empty in rows before the first measurement. */
gk_stats_csv *gk_stats_csv_open_truth(const char *path, bool truth, gk_err *e);
/* The error and truth_spp of the rows that follow (error NAN, spp 0: empty). */
void gk_stats_csv_truth(gk_stats_csv *c, double error, long truth_spp);
int gk_stats_csv_row(gk_stats_csv *c, long frame, double time_s, const char *scene, const char *method,
                     const gk_frame_report *report, const gk_budget *b, gk_err *e);
/* The spool in use: FILE.part, or FILE.part-N when a previous run's spool is still there. */
const char *gk_stats_csv_spool_path(const gk_stats_csv *c);
/* Writes the CSV from the spool (the knob columns are b's knobs) and removes the spool. When the
 * CSV cannot be written the spool is kept and e says where it is. Frees c either way. */
int gk_stats_csv_close(gk_stats_csv *c, const gk_budget *b, gk_err *e);

#endif
