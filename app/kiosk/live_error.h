/* The kiosk's live error (issue 19): keeps the ground truth (truth.h) on the view now shown and
 * measures the shown method against it.
 *
 * The view: the truth restarts when the scene changes; an animated scene (gk_scene.anim_duration >
 * 0) moves every frame, so it gets a truth only while its animation is paused (prev held,
 * gk_live_error_pause: traced at the frozen time, stopped when it moves again). Scenes with mirrors
 * or glass get the reference's light pass too (truth.h). Committed reference: SCENES_DIR/../../
 * tests/references/SCENE.exr, used as the truth of a still scene when the truth size is the frame
 * size (sub = 1) and equals the reference's (the references are rendered through pixel centres at
 * time 0).
 *
 * The error: every GK_LIVE_ERROR_PERIOD_S of kiosk time, the frame's linear HDR image (before
 * exposure and tonemap, gk_renderer_read_linear) is box-downsampled by sub to the truth's size and
 * its rel RMSE against the truth's current estimate is taken (metrics.h's definition, the truth as
 * the reference). Raw, not corrected for the truth's noise: the HUD shows that noise beside it
 * (E[error^2] = true error^2 + noise^2, so the number means something once noise << error).
 *
 * The plot: per scene, one point per (method, knob levels) shown in this run: its mean frame time
 * and its latest error; at most GK_LIVE_MAX_POINTS, the one with the fewest frames giving way. */
#ifndef GK_KIOSK_LIVE_ERROR_H
#define GK_KIOSK_LIVE_ERROR_H

#include <stdbool.h>

#include "base/err.h"
#include "../render/renderer.h"
#include "../scene/scene.h"
#include "config.h"
#include "truth.h"

#define GK_LIVE_ERROR_PERIOD_S 0.5
/* After a method change the error is unknown until this much kiosk time has passed: the renderer
 * cross-fades GI over gi_blend frames (4 by default; 0.1 s is 6 frames at 60 Hz), and a blend of two
 * methods is neither's error. */
#define GK_LIVE_SETTLE_S 0.1
#define GK_LIVE_MAX_POINTS 24

typedef struct gk_live_point {
    char method[32];
    char levels[160];         /* the active knobs as "name=value ..." */
    double ms_sum;            /* judged frame times while it was shown (not the warm-up's one-off costs) */
    long frames;
    double error;             /* latest measured error (NAN: none yet) */
} gk_live_point;

typedef struct gk_live_error {
    gk_truth *truth;
    int frame_w, frame_h, w, h, sub;
    int workers;
    gk_scene *scene;          /* the view the truth follows (NULL: none) */
    char scene_name[GK_NAME_LEN];
    bool frozen;              /* an animated scene's truth runs at frozen_t (its animation paused) */
    double frozen_t;
    bool check_stop;          /* stopped on a resume: the next frame logs whether the workers are out */
    char note[160];           /* why there is no truth, or "" */
    gk_truth_view view;       /* the latest snapshot (the split view shows it) */
    double error;             /* the latest measurement, NAN before the first */
    long error_spp;           /* the truth's spp at that measurement */
    double error_noise;       /* and its noise */
    double next_measure_s;
    bool settle;              /* a method change: the next measurement waits GK_LIVE_SETTLE_S */
    float *down;              /* the downsampled frame, w * h * 3 */
    int scene_index;
    int n_points[GK_MAX_PLAYLIST];
    gk_live_point points[GK_MAX_PLAYLIST][GK_LIVE_MAX_POINTS];
    int current_point;        /* index into points[scene_index], -1: none */
} gk_live_error;

/* Starts the truth's workers for frames of fw x fh. */
int gk_live_error_open(gk_live_error *le, const gk_kiosk_config *c, int fw, int fh, gk_err *e);
void gk_live_error_close(gk_live_error *le);
/* A new scene is shown (s evaluated at t = 0 by the caller or not yet: done here). */
void gk_live_error_scene(gk_live_error *le, gk_scene *s, int scene_index, const char *scene_name,
                         const char *scenes_dir);
/* Once a frame, before it is drawn: the animation is paused (at anim_t) or moving. An animated
 * scene's truth starts when it is paused, restarts when the frozen time changes and stops when it
 * moves again (the workers leave the old view between two samples); a still scene's is untouched. */
void gk_live_error_pause(gk_live_error *le, bool paused, double anim_t);
/* The method shown changed: the error is unknown (NAN) until it is measured on the new method. */
void gk_live_error_method(gk_live_error *le);
/* After a frame drawn and shown: its (method, levels) point gets the frame time when judged (the
 * scheduler's judged frames: no warm-up); every
 * GK_LIVE_ERROR_PERIOD_S the error is measured. Returns true when a new measurement was taken. */
bool gk_live_error_frame(gk_live_error *le, gk_renderer *r, double now, const char *method, const char *levels,
                         double frame_ms, bool judged);

/* rel RMSE of a linear RGBA frame (fw x fh, top row first) box-downsampled by sub against truth
 * (w x h RGB, w * sub <= fw, h * sub <= fh); down receives the downsampled frame (w * h * 3). */
double gk_live_error_measure(const float *rgba, int fw, int fh, int sub, const float *truth, int w, int h,
                             float *down);

#endif
