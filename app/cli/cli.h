/* `gikiosk run` command line (DESIGN §3). Parsing is separate from running so it is unit-tested;
 * values given on the command line override the config file. */
#ifndef GK_CLI_H
#define GK_CLI_H

#include <stdbool.h>
#include <stdio.h>

#include "kiosk/config.h"

typedef struct gk_run_opts {
    const char *config_path;        /* NULL: config/kiosk.ini if it exists, else built-in defaults */
    bool platform_set;  enum gk_platform_kind platform;
    bool size_set;      int width, height;
    const char *scene;              /* NAME[,NAME...]: replaces the playlist */
    const char *method;             /* forced GI method */
    long frames;                    /* 0 = unbounded */
    double seconds;                 /* 0 = unbounded (platform clock: virtual on mock) */
    bool target_set;    double target_ms;
    const char *script;
    const char *capture_dir;
    long capture_every;             /* 0: the last frame of each scene visit */
    bool hdr;
    bool capture_hud;   /* captures also with the HUD drawn (-hud.png) */
    const char *stats_path;
    int gles;                       /* 0 = best available, 31 or 32 */
    const char *budget_pins;        /* KNOB=VALUE,... */
    const char *shader_dir;
    const char *scenes_dir;         /* default config/scenes */
    bool help;
} gk_run_opts;

/* Parses argv (argv[0] = "run"). Accepts `--opt VALUE` and `--opt=VALUE`. Errors are GK_EINPUT and
 * name the option and the value ("--size: '12x' is not WxH"). */
int gk_run_parse_args(int argc, char **argv, gk_run_opts *o, gk_err *e);
/* Overrides config values with what the command line gave. */
void gk_run_opts_apply(const gk_run_opts *o, gk_kiosk_config *c);
void gk_run_usage(FILE *f);

#endif
