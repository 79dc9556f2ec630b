/* Frame-time scheduler (DESIGN §6): keeps frames under the target by moving budget knob levels.
 *
 * Cost model: frame_ms ~= base + sum_k w_k * cost_k(level_k), linear in the knobs' cost priors
 * (gk_knob_def.cost). It is seeded from the first measured frame (equal shares for the base and each
 * active knob) and fitted online: when exactly one knob changed since the previous measured frame,
 * the change in frame time over the change in its prior is a direct measurement of that knob's
 * weight (averaged into it); on other frames normalised least mean squares on the measured time
 * keeps the whole prediction calibrated (base and weights move along the feature vector).
 *
 * A knob whose cost lives in one timed pass (gk_knob_def.scales_pass: the VCT cones, step and trace
 * resolution all scale gi.vct_trace) is predicted from that pass instead: a step from level l to l'
 * changes the frame by gain_k * pass_ms * (cost(l')/cost(l) - 1), with pass_ms measured on the
 * frame just drawn (gk_sched_observe_pass) and gain_k (1 at first) fitted by its step responses.
 * Such knobs interact multiplicatively (cones x trace pixels), which the additive model cannot
 * express: seeded with equal shares it put the furnace's 6 -> 9 cones at +12 ms where the trace
 * pass of 275 ms grew to 424 ms, two frames 11% over a 400 ms target (showcase tour).
 *
 * Calibrated knobs (gk_sched_calibrate_knob, from `make calibrate`'s knob rows for this scene and
 * method): a step's cost comes from the measured frame times of its levels (scaled by this run's
 * first frame over the calibrated default frame, and corrected by the knob's step responses), a
 * pass-scaled knob's ratio from the measured pass times; its quality from the measured error: a
 * step's value is the error it removes, relative to the default's. A level the calibration shows
 * no more accurate than the one below it is never climbed to, and dropping to it costs no quality
 * (so it goes first when over target): knob orders from measurement. Uncalibrated knobs keep the
 * priors and count each step as 1/(levels - 1) of the knob's range.
 *
 * Control (up: see gk_sched_params.max_up_steps, up_after_far): over target -> step down at once, as many steps as the model predicts are needed to get
 * under target*(1 - margin/2) but at most max_down_steps per measured frame, each time the knob whose step saves the most predicted time per
 * quality lost (quality of a step = 1/(number of values - 1)). Under target*(1 - margin) for
 * up_after consecutive frames -> one step up, the knob that buys the most quality per predicted
 * time, and only if the worst of those frames plus the predicted cost stays under
 * target*(1 - margin/2). A knob stepped down after a step up (a reversal) may not step up again for
 * hold_base * 2^(reversals-1) frames, so the controller cannot oscillate for long.
 * Pinned knobs and knobs outside the active set never move; [budgets] ranges are respected. */
#ifndef GK_SCHEDULER_H
#define GK_SCHEDULER_H

#include <stdbool.h>

#include "budget.h"

typedef struct gk_sched_params {
    double target_ms;
    double margin;        /* fraction of the target kept free before stepping up (0.15) */
    int up_after;         /* consecutive frames under target*(1-margin) before a step up (30) */
    int hold_base;        /* frames a reversed knob is blocked from stepping up, doubled per reversal (120) */
    int warmup;           /* frames not measured after a reset (scene upload, shader compiles) (3) */
    double learn_rate;    /* NLMS step size, 0..1 (0.3) */
    int max_down_steps;   /* steps down per judged frame (2): measured on llvmpipe, a model seeded
                             with equal shares dropped 15 knobs in one frame (934 ms -> 46 ms at a
                             400 ms target); a couple of steps, then a new measurement, lands near
                             the target instead of on the floor */
    int max_up_steps;     /* steps up per judged frame (3); beyond the first only knobs whose cost a
                             step response has measured (see step_up) */
    int up_after_far;     /* frames under target/2 before a step up (5): far under the target the
                             kiosk should not take 30 frames a level to show what it can */
} gk_sched_params;

typedef struct gk_sched_change {
    int knob;             /* index in the budget */
    int from, to;         /* levels */
} gk_sched_change;

typedef struct gk_sched {
    gk_sched_params p;
    bool active[GK_MAX_KNOBS];
    double weight[GK_MAX_KNOBS]; /* ms per unit of cost prior */
    double base_ms;
    bool seeded;
    int warm;                    /* frames still to ignore */
    int under_count;
    double under_worst_ms;
    long frame;
    int last_dir[GK_MAX_KNOBS];  /* +1 last moved up, -1 down, 0 never */
    int reversals[GK_MAX_KNOBS];
    long blocked_until[GK_MAX_KNOBS];
    bool measured[GK_MAX_KNOBS]; /* the knob's weight came from a step response, not only the prior */
    long direction_changes;      /* total over the run, for tests and logs */
    bool have_prev;              /* the previous measured frame, for step responses */
    double prev_ms;
    int prev_level[GK_MAX_KNOBS];
    double pass_ms[GK_MAX_KNOBS];      /* time of the knob's scales_pass on the newest frame (0: unknown) */
    double prev_pass_ms[GK_MAX_KNOBS]; /* ... on the previous measured frame, for its step response */
    double gain[GK_MAX_KNOBS];         /* measured / predicted change of a pass-scaled or calibrated
                                          knob's step */
    bool calibrated[GK_MAX_KNOBS];
    float cal_ms[GK_MAX_KNOBS][GK_MAX_KNOB_VALUES];   /* calibrated frame time per level (NAN: not measured) */
    float cal_err[GK_MAX_KNOBS][GK_MAX_KNOB_VALUES];  /* calibrated error per level */
    float cal_pass[GK_MAX_KNOBS][GK_MAX_KNOB_VALUES]; /* calibrated time of the knob's scales_pass */
    double cal_default_ms, cal_default_err;           /* the calibration's default row */
    double cal_scale;                  /* this run's frame time / the calibrated one (set at seeding) */
} gk_sched;

void gk_sched_params_defaults(gk_sched_params *p, double target_ms);
/* Starts over (new scene or method): active[k] says which knobs affect the frame now (NULL = all). */
void gk_sched_reset(gk_sched *s, const gk_sched_params *p, const gk_budget *b, const bool *active);
/* Feeds the time of the frame just drawn at b's current levels; may change levels in b for the next
 * frame. Fills changes (up to max) and returns their count. */
int gk_sched_update(gk_sched *s, gk_budget *b, double frame_ms, gk_sched_change *changes, int max);
/* The time of knob k's scales_pass on the frame about to be fed to gk_sched_update (call before
 * it, for each knob that has one; a pass that did not run is 0 and leaves the knob on the
 * additive model). */
void gk_sched_observe_pass(gk_sched *s, int k, double pass_ms);
/* The calibration of this visit (call after gk_sched_reset): the default configuration's frame time
 * and error, then per knob the frame time, error and scales_pass time of each level (NAN where not
 * measured; the default level's are the default row's). */
void gk_sched_calibrate(gk_sched *s, double default_frame_ms, double default_error);
void gk_sched_calibrate_knob(gk_sched *s, int k, const double *frame_ms, const double *error, const double *pass_ms,
                             int n_levels);
/* True when no knob the scheduler may move can step down: every active, unpinned knob is at the
 * lowest level its range allows. A frame over the target then cannot be helped by budgets. */
bool gk_sched_at_floor(const gk_sched *s, const gk_budget *b);
/* The model's prediction for b's current levels (ms); 0 before the first measured frame. */
double gk_sched_predict(const gk_sched *s, const gk_budget *b);

#endif
