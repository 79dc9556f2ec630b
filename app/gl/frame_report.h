/* The one frame report: what a frame cost, pass by pass, as the renderer's timer measured it
 * (app/gl/gl_timing.h). Passes nest: a GI method's passes are children of the renderer's `gi`
 * pass, never its siblings, so a parent's time already contains its children's and the frame's
 * total is the sum of the top-level passes only. The scheduler, the HUD, the stats CSV and the
 * bench all read this report; nobody re-sums columns. */
#ifndef GK_FRAME_REPORT_H
#define GK_FRAME_REPORT_H

#include <stddef.h>

#define GK_MAX_PASSES 32
#define GK_PASS_PATH_LEN 64

typedef struct gk_pass_time {
    const char *name;   /* stable string literal ("shadow", "vct_trace"): it becomes a CSV column */
    int parent;         /* index of the enclosing pass in the report, -1 at the top level */
    double ms;          /* inclusive: the pass and everything nested in it */
} gk_pass_time;

typedef struct gk_frame_report {
    double total_ms;    /* sum of the top-level passes */
    int n;
    gk_pass_time pass[GK_MAX_PASSES];   /* a parent always precedes its children */
} gk_frame_report;

/* Sum of the top-level passes (what total_ms holds once the timer filled the report). */
double gk_frame_report_top_sum(const gk_frame_report *r);
/* Dotted path of pass i: "shadow", "gi.vct_trace" (parents first). Returns its length. */
int gk_frame_report_path(const gk_frame_report *r, int i, char *out, size_t out_len);
/* Index of the pass with this dotted path, or -1. */
int gk_frame_report_find(const gk_frame_report *r, const char *path);
/* Time of a pass by dotted path; 0 when it did not run. */
double gk_frame_report_ms(const gk_frame_report *r, const char *path);

#endif
