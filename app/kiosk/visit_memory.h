/* What the kiosk remembers of each (scene, method) for the run: the budget levels it last ran at
 * and the scheduler's learned cost model. A visit starts from its own remembered state -- or from
 * the knobs' defaults on a first visit -- never from the previous scene's levels (which used to
 * carry the cheapest levels of a heavy scene into every scene after it). No GL: unit-tested. */
#ifndef GK_KIOSK_VISIT_MEMORY_H
#define GK_KIOSK_VISIT_MEMORY_H

#include <stdbool.h>

#include "../sched/budget.h"
#include "../sched/scheduler.h"
#include "config.h"

#define GK_VISIT_METHODS 16   /* catalogue entries remembered per scene */

typedef struct gk_visit_state {
    bool valid;
    int level[GK_MAX_KNOBS];
    gk_sched sched;
} gk_visit_state;

typedef struct gk_visit_memory {
    gk_visit_state slot[GK_MAX_PLAYLIST][GK_VISIT_METHODS];
} gk_visit_memory;

/* Remembers b's levels and the scheduler's model for (scene, method); method is a catalogue index.
 * Out-of-range indexes are ignored. */
void gk_visit_save(gk_visit_memory *m, int scene, int method, const gk_budget *b, const gk_sched *s);
/* Restores what was remembered for (scene, method) into b (pinned knobs keep their pins) and s (its
 * warm-up restarts: the first frames of a visit pay one-off costs). Returns false when nothing was
 * remembered; b and s are then untouched. */
bool gk_visit_restore(const gk_visit_memory *m, int scene, int method, gk_budget *b, gk_sched *s);
/* Every knob that is not pinned back to its default level, within its [budgets] range. */
void gk_budget_reset_defaults(gk_budget *b);

#endif
