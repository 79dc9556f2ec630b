/* The measured model the kiosk chooses a scene's method and budgets from (DESIGN §6), made by
 * `make calibrate` (tools/calibrate.sh, `gikiosk bench --sweep each`) into
 * config/calibration/CLASS.csv, CLASS named from the GL renderer string (llvmpipe on CI). Per scene
 * x method one row at the default budgets (knob and value empty) -- frame time, error against one
 * ruler per scene, and the time of each pass -- and one row per level of every knob the scheduler
 * may move, that knob alone changed from the defaults. The method choice reads the default rows;
 * the scheduler reads the knob rows (what a step costs, whether it lowers the error: knob orders
 * from measurement, scheduler.h). A missing file means no calibration: the kiosk then keeps the
 * playlist's order and the knobs' priors. Frame times are scaled to the run's pixel count (a
 * prior; the scheduler's online model corrects it per visit). Files of the first format (the
 * default rows only, 8 columns) still load. No GL: unit-tested. */
#ifndef GK_CALIBRATION_H
#define GK_CALIBRATION_H

#include <stdbool.h>

#include "base/err.h"

typedef struct gk_calib_row {
    char scene[64], method[32];
    char knob[32], value[24]; /* the one knob changed from the defaults; "" for the default row */
    int width, height;        /* the size it was measured at */
    double frame_ms;          /* median frame time */
    double error;             /* against the scene's ruler (rel_rmse, or rmse for a black ruler) */
    char passes[400];         /* "PATH=MS PATH=MS ...": median time of each pass that ran ("" in the
                                 first format) */
} gk_calib_row;

typedef struct gk_calibration {
    int n;
    gk_calib_row *rows;
    char path[512];
} gk_calibration;

/* Platform class of a GL renderer string: its first word, lower case ("llvmpipe (LLVM ...)" ->
 * "llvmpipe"). */
void gk_calibration_class(const char *renderer, char *out, int out_len);
/* Where the kiosk and the bench look for the calibration of a renderer: beside the scenes folder,
 * config/scenes -> config/calibration/CLASS.csv. */
void gk_calibration_path(const char *scenes_dir, const char *renderer, char *out, int out_len);
/* Reads path. Returns 0, or -1 with e: GK_EINPUT naming file:line for a malformed row,
 * GK_ERUNTIME when it cannot be read. A missing file is reported as GK_ERUNTIME too: the caller
 * decides (the kiosk logs it and runs uncalibrated). */
int gk_calibration_load(const char *path, gk_calibration *c, gk_err *e);
void gk_calibration_free(gk_calibration *c);
/* The default-budget row of scene x method, or NULL. */
const gk_calib_row *gk_calibration_find(const gk_calibration *c, const char *scene, const char *method);
/* The row with knob = value (others at their defaults); value the default's: the default row. */
const gk_calib_row *gk_calibration_find_level(const gk_calibration *c, const char *scene, const char *method,
                                              const char *knob, const char *value);
/* Median time of a pass (dotted path, "gi.vct_trace") in a row; NAN when the row has no such pass. */
double gk_calib_row_pass_ms(const gk_calib_row *r, const char *path);

/* The automatic choice among a scene's methods: the lowest calibrated error whose frame time,
 * scaled by run_pixels / measured pixels, is under target_ms; if none fits, the fastest. A method
 * whose error is larger than `none`'s on this scene is never chosen (`none` is chosen instead when
 * it is in the list). Methods without a calibration row are not candidates. Returns the index in
 * methods, or -1 when no method of the list is calibrated for this scene. why (optional) gets a
 * one-line account: "vpl: error 0.114 at ~70 ms (none 0.376, vct 0.467 worse than none)". */
int gk_calibration_choose(const gk_calibration *c, const char *scene, const char *const *methods, int n,
                          double target_ms, double run_pixels, char *why, int why_len);

#endif
