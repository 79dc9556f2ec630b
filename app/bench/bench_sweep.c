/* Sweep parsing and enumeration, and the Pareto front: the pure-logic half of the bench. */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int add_axis(gk_bench_sweep *s, const char *knob, gk_err *e)
{
    if (s->n_axes >= GK_BENCH_MAX_AXES)
        return gk_fail(e, GK_EINPUT, "--sweep: more than %d knobs", GK_BENCH_MAX_AXES);
    int a = s->n_axes++;
    snprintf(s->knob[a], sizeof s->knob[a], "%s", knob);
    s->n_values[a] = 0;
    return a;
}

int gk_bench_sweep_parse(const char *text, const gk_budget *b, gk_bench_sweep *s, gk_err *e)
{
    memset(s, 0, sizeof *s);
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", text);
    char *save_axis = NULL;
    for (char *axis = strtok_r(buf, ";", &save_axis); axis; axis = strtok_r(NULL, ";", &save_axis)) {
        char *eq = strchr(axis, '=');
        if (!eq || eq == axis || !eq[1])
            return gk_fail(e, GK_EINPUT, "--sweep: '%s' is not KNOB=V1,V2,...", axis);
        *eq = '\0';
        int k = gk_budget_find(b, axis);
        if (k < 0)
            return gk_fail(e, GK_EINPUT, "--sweep: unknown knob '%s'", axis);
        int a = add_axis(s, axis, e);
        if (a < 0)
            return -1;
        char *save_v = NULL;
        for (char *v = strtok_r(eq + 1, ",", &save_v); v; v = strtok_r(NULL, ",", &save_v)) {
            int found = 0;
            for (int i = 0; i < b->def[k]->n_values; i++)
                found |= strcmp(b->def[k]->values[i], v) == 0;
            if (!found)
                return gk_fail(e, GK_EINPUT, "--sweep: knob '%s' has no value '%s'", axis, v);
            if (s->n_values[a] >= GK_MAX_KNOB_VALUES)
                return gk_fail(e, GK_EINPUT, "--sweep: too many values for '%s'", axis);
            snprintf(s->values[a][s->n_values[a]++], sizeof s->values[a][0], "%s", v);
        }
    }
    if (s->n_axes == 0)
        return gk_fail(e, GK_EINPUT, "--sweep: empty");
    return 0;
}

static void axis_all_values(gk_bench_sweep *s, const gk_knob_def *d)
{
    int a = s->n_axes++;
    snprintf(s->knob[a], sizeof s->knob[a], "%s", d->name);
    s->n_values[a] = d->n_values;
    for (int i = 0; i < d->n_values; i++)
        snprintf(s->values[a][i], sizeof s->values[a][i], "%s", d->values[i]);
}

int gk_bench_default_sweeps(const gk_budget *b, const char *method, gk_bench_sweep *out, int max)
{
    int n = 0;
    if (strcmp(method, "none") == 0) {
        /* Direct light only: what there is to trade is the shadow method and the map size. */
        memset(&out[0], 0, sizeof out[0]);
        int k1 = gk_budget_find(b, "shadow"), k2 = gk_budget_find(b, "shadow_map");
        if (k1 >= 0)
            axis_all_values(&out[0], b->def[k1]);
        if (k2 >= 0)
            axis_all_values(&out[0], b->def[k2]);
        return out[0].n_axes > 0 ? 1 : 0;
    }
    for (int k = 0; k < b->n && n < max; k++) {
        if (!b->def[k]->owner || strcmp(b->def[k]->owner, method) != 0)
            continue;
        memset(&out[n], 0, sizeof out[n]);
        axis_all_values(&out[n], b->def[k]);
        n++;
    }
    return n;
}

int gk_bench_each_knob_sweeps(const gk_budget *b, const char *method, gk_bench_sweep *out, int max)
{
    int n = 0;
    for (int k = 0; k < b->n && n < max; k++) {
        const gk_knob_def *d = b->def[k];
        const char *owner = d->owner ? d->owner : "";
        if (d->fixed || d->n_values < 2 || (strcmp(owner, "render") != 0 && strcmp(owner, method) != 0))
            continue;
        int top = d->auto_max_level > 0 ? d->auto_max_level : d->n_values - 1;
        gk_bench_sweep *s = &out[n];
        memset(s, 0, sizeof *s);
        snprintf(s->knob[0], sizeof s->knob[0], "%s", d->name);
        for (int l = 0; l <= top; l++)
            if (l != d->default_level)
                snprintf(s->values[0][s->n_values[0]++], sizeof s->values[0][0], "%s", d->values[l]);
        if (s->n_values[0] > 0) {
            s->n_axes = 1;
            n++;
        }
    }
    return n;
}

int gk_bench_sweep_count(const gk_bench_sweep *s)
{
    int n = 1;
    for (int a = 0; a < s->n_axes; a++)
        n *= s->n_values[a];
    return s->n_axes ? n : 0;
}

void gk_bench_sweep_pins(const gk_bench_sweep *s, int index, char *out, int out_len)
{
    out[0] = '\0';
    /* The last axis varies fastest, like nested loops written in axis order. */
    int rest = index, digit[GK_BENCH_MAX_AXES];
    for (int a = s->n_axes - 1; a >= 0; a--) {
        digit[a] = rest % s->n_values[a];
        rest /= s->n_values[a];
    }
    for (int a = 0; a < s->n_axes; a++) {
        int used = (int)strlen(out);
        snprintf(out + used, (size_t)(out_len - used), "%s%s=%s", a ? "," : "", s->knob[a], s->values[a][digit[a]]);
    }
}

/* A reference whose mean is 0 makes the relative error infinite. */
static bool against_black(const gk_bench_row *row) { return isinf(row->rel_rmse) && row->reference[0]; }

double gk_bench_row_error(const gk_bench_row *row)
{
    return against_black(row) ? row->test_mean : row->rel_rmse;
}

double gk_bench_row_caustic_error(const gk_bench_row *row) { return row->caustic_rel_rmse; }

bool gk_bench_black_reference(const gk_bench_row *rows, int n, const char *scene)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(rows[i].scene, scene) && against_black(&rows[i]))
            return true;
    return false;
}

/* Is row i dominated by another row of its scene (at least as fast and as accurate, strictly one)? */
static bool on_front(const gk_bench_row *rows, int n, int i, double (*error)(const gk_bench_row *))
{
    double err_i = error(&rows[i]);
    if (isnan(err_i))
        return false;
    for (int j = 0; j < n; j++) {
        double err_j = error(&rows[j]);
        if (j == i || isnan(err_j) || strcmp(rows[i].scene, rows[j].scene) != 0)
            continue;
        bool faster_eq = rows[j].frame_ms_median <= rows[i].frame_ms_median;
        bool better_eq = err_j <= err_i;
        bool strictly = rows[j].frame_ms_median < rows[i].frame_ms_median || err_j < err_i;
        if (faster_eq && better_eq && strictly)
            return false;
    }
    return true;
}

void gk_bench_mark_pareto(gk_bench_row *rows, int n)
{
    for (int i = 0; i < n; i++)
        rows[i].pareto = on_front(rows, n, i, gk_bench_row_error);
}

void gk_bench_pareto_by(const gk_bench_row *rows, int n, const char *scene, double (*error)(const gk_bench_row *),
                        bool *front)
{
    for (int i = 0; i < n; i++)
        front[i] = !strcmp(rows[i].scene, scene) && on_front(rows, n, i, error);
}
