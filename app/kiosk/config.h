/* The kiosk configuration (DESIGN §4): an INI file (config/kiosk.ini, board profiles in board/)
 * read with libinih. Every problem names file:line: unknown sections and keys, bad values,
 * out-of-range values (GK_EINPUT). [budgets] ranges are kept as raw strings with their line numbers,
 * because the knobs exist only once the renderer has declared them; gk_kiosk_config_apply_budgets
 * checks them later and still reports file:line. */
#ifndef GK_KIOSK_CONFIG_H
#define GK_KIOSK_CONFIG_H

#include <stdbool.h>

#include "../../platform/platform.h"
#include "base/err.h"
#include "../sched/budget.h"

#define GK_MAX_PLAYLIST 32
#define GK_NAME_LEN 64

/* Checks a comma list of method names ("vct,none") against the catalogue (app/gi/gi_catalogue.h);
 * what = context for the message. */
int gk_method_list_check(const char *list, const char *what, gk_err *e);

typedef struct gk_method_entry {       /* [playlist] methods.SCENE = vct,none */
    char scene[GK_NAME_LEN];
    char methods[256];
    int line;
} gk_method_entry;

typedef struct gk_budget_range {       /* [budgets] KNOB = MIN..MAX */
    char knob[GK_NAME_LEN];
    char min[32], max[32];
    int line;
} gk_budget_range;

typedef struct gk_kiosk_config {
    char path[512];                    /* file read, "" when only defaults */
    /* [display] */
    enum gk_platform_kind platform;
    char device[128];
    char mode[32];
    int width, height;                 /* render size on mock */
    /* [frame] */
    double target_ms;
    /* [buttons] */
    gk_button_config buttons;
    /* [playlist] */
    int n_scenes;                      /* 0: every scene in the scenes directory, sorted by name */
    char scenes[GK_MAX_PLAYLIST][GK_NAME_LEN];
    int scenes_line;
    double dwell_s;
    double pause_after_input_s;
    int n_methods;
    gk_method_entry methods[GK_MAX_PLAYLIST];
    /* [cpu] */
    int cpu_workers;                   /* threads a GI method may run on the CPU (lightmap's photon
                                          tracing), 0 = cores - 1 */
    /* [truth] (app/kiosk/truth.h) */
    bool truth_enabled;                /* the live ground truth and error on the HUD; off by default */
    int truth_workers;                 /* its path-tracing threads, 0 = cores - 1 (at least 1) */
    int truth_max_w, truth_max_h;      /* the largest truth image (160x120) */
    /* [budgets] */
    int n_ranges;
    gk_budget_range ranges[GK_MAX_KNOBS];
} gk_kiosk_config;

void gk_kiosk_config_defaults(gk_kiosk_config *c);
/* Reads path over the values already in c. */
int gk_kiosk_config_load(gk_kiosk_config *c, const char *path, gk_err *e);
/* Same, from a string; name is the file name used in messages. */
int gk_kiosk_config_parse(gk_kiosk_config *c, const char *text, const char *name, gk_err *e);
/* Applies [budgets] to b once its knobs are declared; errors name file:line. */
int gk_kiosk_config_apply_budgets(const gk_kiosk_config *c, gk_budget *b, gk_err *e);
/* The configured method list for a scene, or NULL. */
const char *gk_kiosk_config_methods(const gk_kiosk_config *c, const char *scene);

/* Small parsers shared with the command line. */
int gk_parse_size(const char *s, int *w, int *h);          /* "640x360" -> 0, else -1 */
int gk_parse_double(const char *s, double *out);           /* whole string, finite */
int gk_parse_int(const char *s, long *out);                /* whole string, base 10 */
int gk_parse_platform(const char *s, enum gk_platform_kind *k);

#endif
