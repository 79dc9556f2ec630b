/* Budget knobs (DESIGN §5–6). Every module that has something to trade declares its knobs: a name,
 * ordered values from cheap to rich, and a cost prior (how cost grows with the value). The
 * scheduler moves knob levels; `--budget KNOB=VALUE` pins one so the scheduler leaves it alone. */
#ifndef GK_BUDGET_H
#define GK_BUDGET_H

#include <stdbool.h>

#include "base/err.h"

#define GK_MAX_KNOBS 96   /* every method's knobs together: 48 filled up once radiosity, lgv and volcaustics joined, 64 once vpl_umbra and vct_level0 did; a full budget refuses more (tests/unit/test_calibration.c checks the room) */
#define GK_MAX_KNOB_VALUES 8

typedef struct gk_knob_def {
    const char *name;                         /* "shadow_map", "render_scale", "vct_res" */
    const char *owner;                        /* "render", "vct", ... */
    int n_values;
    const char *values[GK_MAX_KNOB_VALUES];   /* cheap -> rich, as written on the command line */
    float cost[GK_MAX_KNOB_VALUES];           /* cost prior: relative cost of each value (cheapest = 1) */
    int default_level;
    int auto_max_level;                       /* richest level the scheduler may pick by itself (0 = the
                                                 last); richer ones are reference modes, reached only
                                                 through --budget or a [budgets] range */
    bool fixed;                               /* a variant switch (the document's behaviour or an
                                                 improvement), not a cost/quality trade: the
                                                 scheduler never moves it; set with --budget */
    const char *scales_pass;                  /* the timed pass (dotted path, "gi.vct_trace") whose time
                                                 grows with this knob as cost[level] does, the other
                                                 knobs held: the scheduler predicts a step from that
                                                 pass's measured time (scheduler.h). NULL: the cost
                                                 is a share of the frame, learnt from step responses */
} gk_knob_def;

typedef struct gk_budget {
    int n;
    const gk_knob_def *def[GK_MAX_KNOBS];
    int level[GK_MAX_KNOBS];                  /* index into def->values */
    float number[GK_MAX_KNOBS][GK_MAX_KNOB_VALUES]; /* each value parsed once when declared (NaN: not a number) */
    bool pinned[GK_MAX_KNOBS];
    int min_level[GK_MAX_KNOBS], max_level[GK_MAX_KNOBS]; /* from [budgets] in the config */
} gk_budget;

/* A knob handle: the frame loop reads knob levels through it -- an index checked by one pointer
 * comparison -- never by name. A module keeps one per knob it reads, {&its_def, -1} until
 * resolved; gk_knob_resolve finds the index once (by the def's address, else by its name) and
 * again only if it is handed a budget whose layout differs. The level indexes b->def[index]'s
 * values, which may be another definition of the same name: see gk_knob_def_in. */
typedef struct gk_knob {
    const gk_knob_def *def;
    int index;
} gk_knob;

void gk_budget_init(gk_budget *b);
/* Adds a knob at its default level (no-op if already there). Returns its index or -1 if full. */
int gk_budget_add(gk_budget *b, const gk_knob_def *def);
/* Adds each of defs[0..n) (a method's knob table); a full budget logs each knob it refuses. */
void gk_budget_add_all(gk_budget *b, const gk_knob_def *defs, int n);
int gk_budget_find(const gk_budget *b, const char *name);
/* Current value string of a knob ("1024"), or NULL if the knob is unknown. */
const char *gk_budget_value(const gk_budget *b, const char *name);
/* Numeric convenience: atof of the value, or fallback when the knob is unknown. */
float gk_budget_float(const gk_budget *b, const char *name, float fallback);
/* Parses "KNOB=VALUE[,KNOB=VALUE...]" and pins each; unknown knobs or values are GK_EINPUT errors
 * that list what is allowed. */
int gk_budget_pin_list(gk_budget *b, const char *list, gk_err *e);
/* Sets a knob's allowed range by value strings (config [budgets] NAME = MIN..MAX). */
int gk_budget_set_range(gk_budget *b, const char *name, const char *min_value, const char *max_value, gk_err *e);
/* "shadow_map=1024,render_scale=1" into out. */
void gk_budget_format(const gk_budget *b, char *out, int out_len);
/* Only the knobs in play for a GI method: the renderer's own ("render") and the method's. */
void gk_budget_format_active(const gk_budget *b, const char *method, char *out, int out_len);
/* Handle of def in b (index -1 when b lacks it). */
gk_knob gk_budget_knob(const gk_budget *b, const gk_knob_def *def);
/* Re-points k at b when b's layout differs from what k was resolved against. False when b lacks it. */
bool gk_knob_resolve(const gk_budget *b, gk_knob *k);
/* n unresolved handles, one per definition: what a module keeps for the knobs it declares. */
void gk_knob_handles(gk_knob *out, const gk_knob_def *defs, int n);
/* The definition the resolved handle reads in b (k->def, or a same-named one), NULL if absent. */
const gk_knob_def *gk_knob_def_in(const gk_budget *b, gk_knob *k);
/* Level of the knob in b, or fallback when b is NULL or lacks it. */
int gk_knob_level(const gk_budget *b, gk_knob *k, int fallback);
/* The knob's current value as a number (parsed at declaration), or fallback when b is NULL, lacks
 * the knob, or the value is not a number ("adaptive"). */
float gk_knob_number(const gk_budget *b, gk_knob *k, float fallback);

/* A pass could not run the knob's level and ran `value` instead (vct_res=256 past the GPU's
 * storage-buffer limit runs at 128): notes in `ran` -- the renderer's copy of the frame's levels,
 * what the HUD, the stats and the bench report -- the richest level whose value is <= value.
 * ran NULL (nobody reads it) or lacking the knob: no-op. */
void gk_knob_note_ran(struct gk_budget *ran, gk_knob *k, float value);

/* True when knob i matters for method (owner "render" or the method itself). */
bool gk_budget_knob_active(const gk_budget *b, int i, const char *method);

#endif
