#include "budget.h"

#include <math.h>

#include "base/log.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void gk_budget_init(gk_budget *b) { memset(b, 0, sizeof *b); }

int gk_budget_find(const gk_budget *b, const char *name)
{
    for (int i = 0; i < b->n; i++)
        if (strcmp(b->def[i]->name, name) == 0)
            return i;
    return -1;
}

int gk_budget_add(gk_budget *b, const gk_knob_def *def)
{
    int i = gk_budget_find(b, def->name);
    if (i >= 0)
        return i;
    if (b->n >= GK_MAX_KNOBS) {
        /* Never silent: a refused knob is one the scheduler cannot move nor a user pin (the budget
           filled up unnoticed once three methods joined in one go). */
        gk_log("budget: knob '%s' refused: all %d places are taken (raise GK_MAX_KNOBS)", def->name, GK_MAX_KNOBS);
        return -1;
    }
    i = b->n++;
    b->def[i] = def;
    for (int k = 0; k < GK_MAX_KNOB_VALUES; k++) {
        char *end = NULL;
        float v = k < def->n_values ? strtof(def->values[k], &end) : NAN;
        b->number[i][k] = k < def->n_values && end != def->values[k] && *end == '\0' ? v : NAN;
    }
    b->level[i] = def->default_level;
    b->pinned[i] = false;
    b->min_level[i] = 0;
    b->max_level[i] = def->auto_max_level > 0 && def->auto_max_level < def->n_values ? def->auto_max_level
                                                                                   : def->n_values - 1;
    return i;
}

void gk_knob_handles(gk_knob *out, const gk_knob_def *defs, int n)
{
    for (int i = 0; i < n; i++)
        out[i] = (gk_knob){&defs[i], -1};
}

gk_knob gk_budget_knob(const gk_budget *b, const gk_knob_def *def)
{
    gk_knob k = {def, -1};
    gk_knob_resolve(b, &k);
    return k;
}

bool gk_knob_resolve(const gk_budget *b, gk_knob *k)
{
    if (!b)
        return false;
    if (k->index >= 0 && k->index < b->n && b->def[k->index] == k->def)
        return true;
    /* By address; then by name, for a budget whose knob of that name has another definition (a
       test's extended variant list): resolution runs only when the layout changes, never per frame
       once resolved. */
    k->index = -1;
    for (int i = 0; i < b->n; i++)
        if (b->def[i] == k->def) {
            k->index = i;
            return true;
        }
    k->index = gk_budget_find(b, k->def->name);
    return k->index >= 0;
}

const gk_knob_def *gk_knob_def_in(const gk_budget *b, gk_knob *k)
{
    return gk_knob_resolve(b, k) ? b->def[k->index] : NULL;
}

int gk_knob_level(const gk_budget *b, gk_knob *k, int fallback)
{
    return gk_knob_resolve(b, k) ? b->level[k->index] : fallback;
}

float gk_knob_number(const gk_budget *b, gk_knob *k, float fallback)
{
    if (!gk_knob_resolve(b, k))
        return fallback;
    float v = b->number[k->index][b->level[k->index]];
    return isnan(v) ? fallback : v;
}

void gk_knob_note_ran(gk_budget *ran, gk_knob *k, float value)
{
    if (!ran || !gk_knob_resolve(ran, k))
        return;
    int i = k->index, best = -1;
    for (int l = 0; l < ran->def[i]->n_values; l++)
        if (!isnan(ran->number[i][l]) && ran->number[i][l] <= value)
            best = l;
    if (best >= 0)
        ran->level[i] = best;
}

const char *gk_budget_value(const gk_budget *b, const char *name)
{
    int i = gk_budget_find(b, name);
    return i < 0 ? NULL : b->def[i]->values[b->level[i]];
}

float gk_budget_float(const gk_budget *b, const char *name, float fallback)
{
    const char *v = gk_budget_value(b, name);
    return v ? (float)atof(v) : fallback;
}

static int value_index(const gk_knob_def *d, const char *value)
{
    for (int k = 0; k < d->n_values; k++)
        if (strcmp(d->values[k], value) == 0)
            return k;
    return -1;
}

static void list_values(const gk_knob_def *d, char *out, int len)
{
    out[0] = '\0';
    for (int k = 0; k < d->n_values; k++) {
        int used = (int)strlen(out);
        snprintf(out + used, (size_t)(len - used), "%s%s", k ? ", " : "", d->values[k]);
    }
}

static void list_knobs(const gk_budget *b, char *out, int len)
{
    out[0] = '\0';
    for (int i = 0; i < b->n; i++) {
        int used = (int)strlen(out);
        snprintf(out + used, (size_t)(len - used), "%s%s", i ? ", " : "", b->def[i]->name);
    }
}

int gk_budget_pin_list(gk_budget *b, const char *list, gk_err *e)
{
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", list);
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        char *eq = strchr(tok, '=');
        if (!eq || eq == tok || !eq[1])
            return gk_fail(e, GK_EINPUT, "--budget: '%s' is not KNOB=VALUE", tok);
        *eq = '\0';
        int i = gk_budget_find(b, tok);
        if (i < 0) {
            char known[512];
            list_knobs(b, known, sizeof known);
            return gk_fail(e, GK_EINPUT, "--budget: unknown knob '%s' (known: %s)", tok, known);
        }
        int k = value_index(b->def[i], eq + 1);
        if (k < 0) {
            char vals[256];
            list_values(b->def[i], vals, sizeof vals);
            return gk_fail(e, GK_EINPUT, "--budget: knob '%s' has no value '%s' (allowed: %s)", tok, eq + 1, vals);
        }
        b->level[i] = k;
        b->pinned[i] = true;
    }
    return 0;
}

int gk_budget_set_range(gk_budget *b, const char *name, const char *min_value, const char *max_value, gk_err *e)
{
    int i = gk_budget_find(b, name);
    if (i < 0) {
        char known[512];
        list_knobs(b, known, sizeof known);
        return gk_fail(e, GK_EINPUT, "unknown budget knob '%s' (known: %s)", name, known);
    }
    int lo = value_index(b->def[i], min_value), hi = value_index(b->def[i], max_value);
    if (lo < 0 || hi < 0) {
        char vals[256];
        list_values(b->def[i], vals, sizeof vals);
        return gk_fail(e, GK_EINPUT, "budget '%s': '%s' is not an allowed value (allowed: %s)", name,
                       lo < 0 ? min_value : max_value, vals);
    }
    if (lo > hi)
        return gk_fail(e, GK_EINPUT, "budget '%s': minimum %s is richer than maximum %s", name, min_value, max_value);
    b->min_level[i] = lo;
    b->max_level[i] = hi;
    if (b->level[i] < lo)
        b->level[i] = lo;
    if (b->level[i] > hi)
        b->level[i] = hi;
    return 0;
}

bool gk_budget_knob_active(const gk_budget *b, int i, const char *method)
{
    const char *owner = b->def[i]->owner;
    return !owner || !strcmp(owner, "render") || (method && !strcmp(owner, method));
}

static void format_knobs(const gk_budget *b, const char *method, bool all, char *out, int out_len)
{
    out[0] = '\0';
    for (int i = 0; i < b->n; i++) {
        if (!all && !gk_budget_knob_active(b, i, method))
            continue;
        int used = (int)strlen(out);
        if (used >= out_len - 1)
            break;
        snprintf(out + used, (size_t)(out_len - used), "%s%s=%s", used ? "," : "", b->def[i]->name,
                 b->def[i]->values[b->level[i]]);
    }
}

void gk_budget_format(const gk_budget *b, char *out, int out_len) { format_knobs(b, NULL, true, out, out_len); }

void gk_budget_format_active(const gk_budget *b, const char *method, char *out, int out_len)
{
    format_knobs(b, method, false, out, out_len);
}

void gk_budget_add_all(gk_budget *b, const gk_knob_def *defs, int n)
{
    for (int i = 0; i < n; i++)
        gk_budget_add(b, &defs[i]);
}
