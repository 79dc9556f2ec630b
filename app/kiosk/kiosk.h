/* The kiosk loop: platform, renderer, playlist, scheduler, HUD, captures and stats. */
#ifndef GK_KIOSK_H
#define GK_KIOSK_H

#include <stdbool.h>

#include "config.h"

/* What one run of the loop is asked to do beyond the config (the command line fills it: `gikiosk
 * run`, app/cli/cmd_run.c). Sizes, platform, target and playlist are already in the config. */
typedef struct gk_kiosk_opts {
    bool size_set;                  /* the size was asked for: on KMS it picks a mode (else the panel's) */
    long frames;                    /* stop after N frames; 0 = unbounded */
    double seconds;                 /* stop after S seconds of the platform clock; 0 = unbounded */
    const char *method;             /* forced GI method (a catalogue name), NULL = the playlist's */
    const char *script;             /* mock platform: button script, NULL = none */
    const char *capture_dir;        /* NULL = no captures */
    long capture_every;             /* 0: the last frame of each scene visit */
    bool hdr;                       /* captures also as linear .exr */
    bool capture_hud;               /* captures also with the HUD drawn over them (-hud.png); the
                                       normal captures stay HUD-free */
    const char *stats_path;         /* per-frame CSV, NULL = none */
    int gles;                       /* 0 = best available, 31 or 32 */
    const char *budget_pins;        /* KNOB=VALUE,... or NULL */
    const char *shader_dir;         /* NULL: the shaders embedded in the binary */
    const char *scenes_dir;         /* where the playlist's scene files are */
} gk_kiosk_opts;

/* Runs until o->frames/o->seconds, SIGINT/SIGTERM/SIGHUP/SIGQUIT, or the mock script's end. c->scenes holds the
 * playlist (already resolved). Returns 0, or -1 with e (GK_EINPUT: bad budget pins/[budgets]/script,
 * GK_ERUNTIME: platform, GPU, no loadable scene). */
int gk_kiosk_run(const gk_kiosk_opts *o, const gk_kiosk_config *c, gk_err *e);

#endif
