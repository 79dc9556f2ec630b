/* The kiosk loop: platform, renderer, playlist, scheduler, HUD, captures and stats. */
#ifndef GK_KIOSK_H
#define GK_KIOSK_H

#include "cli/cli.h"
#include "config.h"

/* Runs until --frames/--seconds, SIGINT/SIGTERM, or the mock script's end. c->scenes holds the
 * playlist (already resolved). Returns 0, or -1 with e (GK_EINPUT: bad --budget/[budgets]/script,
 * GK_ERUNTIME: platform, GPU, no loadable scene). */
int gk_kiosk_run(const gk_run_opts *o, const gk_kiosk_config *c, gk_err *e);

#endif
