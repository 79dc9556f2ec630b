#include "visit_memory.h"

#include <string.h>

static bool in_range(int scene, int method)
{
    return scene >= 0 && scene < GK_MAX_PLAYLIST && method >= 0 && method < GK_VISIT_METHODS;
}

void gk_visit_save(gk_visit_memory *m, int scene, int method, const gk_budget *b, const gk_sched *s)
{
    if (!in_range(scene, method))
        return;
    gk_visit_state *v = &m->slot[scene][method];
    v->valid = true;
    memcpy(v->level, b->level, sizeof v->level);
    v->sched = *s;
}

static int clamp_level(const gk_budget *b, int k, int level)
{
    if (level < b->min_level[k])
        level = b->min_level[k];
    if (level > b->max_level[k])
        level = b->max_level[k];
    return level;
}

bool gk_visit_restore(const gk_visit_memory *m, int scene, int method, gk_budget *b, gk_sched *s)
{
    if (!in_range(scene, method) || !m->slot[scene][method].valid)
        return false;
    const gk_visit_state *v = &m->slot[scene][method];
    for (int k = 0; k < b->n; k++)
        if (!b->pinned[k])
            b->level[k] = clamp_level(b, k, v->level[k]);
    *s = v->sched;
    s->warm = s->p.warmup;
    s->under_count = 0;
    s->under_worst_ms = 0;
    s->have_prev = false; /* a step response needs two frames of this visit */
    return true;
}

void gk_budget_reset_defaults(gk_budget *b)
{
    for (int k = 0; k < b->n; k++)
        if (!b->pinned[k])
            b->level[k] = clamp_level(b, k, b->def[k]->default_level);
}
