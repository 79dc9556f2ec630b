/* Frame-time scheduler (see scheduler.h for the model and the control rules). */
#include "scheduler.h"

#include <math.h>
#include <string.h>

void gk_sched_params_defaults(gk_sched_params *p, double target_ms)
{
    p->target_ms = target_ms;
    p->margin = 0.15;
    p->up_after = 30;
    p->hold_base = 120;
    p->warmup = 3;
    p->learn_rate = 0.3;
    p->max_down_steps = 2;
    p->max_up_steps = 3;
    p->up_after_far = 5;
}

void gk_sched_reset(gk_sched *s, const gk_sched_params *p, const gk_budget *b, const bool *active)
{
    memset(s, 0, sizeof *s);
    s->p = *p;
    for (int k = 0; k < b->n; k++) {
        s->active[k] = active ? active[k] : true;
        s->gain[k] = 1;
    }
    s->warm = p->warmup;
}

/* Cost prior of a knob at a level; knobs that declare none cost 1, 2, 3, ... */
static double prior(const gk_budget *b, int k, int level)
{
    const gk_knob_def *d = b->def[k];
    double c = d->cost[level];
    return c > 0 ? c : 1.0 + level;
}

static bool movable(const gk_sched *s, const gk_budget *b, int k)
{
    return s->active[k] && !b->pinned[k] && !b->def[k]->fixed && b->def[k]->n_values > 1;
}

bool gk_sched_at_floor(const gk_sched *s, const gk_budget *b)
{
    for (int k = 0; k < b->n; k++)
        if (s->active[k] && !b->pinned[k] && !b->def[k]->fixed && b->level[k] > b->min_level[k])
            return false;
    return true;
}

double gk_sched_predict(const gk_sched *s, const gk_budget *b)
{
    if (!s->seeded)
        return 0;
    double t = s->base_ms;
    for (int k = 0; k < b->n; k++)
        if (s->active[k])
            t += s->weight[k] * prior(b, k, b->level[k]);
    return t;
}

static void seed(gk_sched *s, const gk_budget *b, double ms)
{
    int n = 0;
    for (int k = 0; k < b->n; k++)
        n += s->active[k];
    double share = ms / (n + 1);
    s->base_ms = share;
    for (int k = 0; k < b->n; k++)
        s->weight[k] = s->active[k] ? share / prior(b, k, b->level[k]) : 0;
    s->seeded = true;
}

/* Normalised LMS on x = (1, prior_k(level_k)...): moves the parameters along x so that the
 * prediction closes learn_rate of its error. Weights stay non-negative (a knob never makes a frame
 * faster by being richer). */
static void fit(gk_sched *s, const gk_budget *b, double ms)
{
    double err = ms - gk_sched_predict(s, b);
    double xx = 1;
    for (int k = 0; k < b->n; k++)
        if (s->active[k]) {
            double x = prior(b, k, b->level[k]);
            xx += x * x;
        }
    double g = s->p.learn_rate * err / xx;
    s->base_ms = fmax(0, s->base_ms + g);
    for (int k = 0; k < b->n; k++)
        if (s->active[k])
            s->weight[k] = fmax(0, s->weight[k] + g * prior(b, k, b->level[k]));
}

void gk_sched_calibrate(gk_sched *s, double default_frame_ms, double default_error)
{
    s->cal_default_ms = default_frame_ms > 0 && isfinite(default_frame_ms) ? default_frame_ms : 0;
    s->cal_default_err = default_error > 0 && isfinite(default_error) ? default_error : 0;
}

void gk_sched_calibrate_knob(gk_sched *s, int k, const double *frame_ms, const double *error, const double *pass_ms,
                             int n_levels)
{
    if (k < 0 || k >= GK_MAX_KNOBS)
        return;
    s->calibrated[k] = false;
    for (int l = 0; l < GK_MAX_KNOB_VALUES; l++) {
        bool in = l < n_levels;
        s->cal_ms[k][l] = in && frame_ms[l] > 0 && isfinite(frame_ms[l]) ? (float)frame_ms[l] : NAN;
        s->cal_err[k][l] = in && error[l] >= 0 && isfinite(error[l]) ? (float)error[l] : NAN;
        s->cal_pass[k][l] = in && pass_ms && pass_ms[l] > 0 && isfinite(pass_ms[l]) ? (float)pass_ms[l] : NAN;
        s->calibrated[k] |= in && !isnan(s->cal_ms[k][l]) && !isnan(s->cal_err[k][l]);
    }
}

void gk_sched_observe_pass(gk_sched *s, int k, double pass_ms)
{
    if (k >= 0 && k < GK_MAX_KNOBS)
        s->pass_ms[k] = pass_ms > 0 && isfinite(pass_ms) ? pass_ms : 0;
}

/* Predicted change of the frame when pass-scaled knob k moves from level `from` to `to`, from the
 * pass time measured at `from`; NAN when the pass time is unknown. */
static double pass_delta(const gk_sched *s, const gk_budget *b, int k, double pass_ms, int from, int to)
{
    if (!b->def[k]->scales_pass || !(pass_ms > 0))
        return NAN;
    double ratio = prior(b, k, to) / prior(b, k, from);
    /* measured pass ratio where both levels' passes took long enough to time (a kept shadow map's
       pass is ~1 us: its ratio would be noise) */
    if (s->calibrated[k] && s->cal_pass[k][from] >= 0.05f && s->cal_pass[k][to] >= 0.05f)
        ratio = (double)s->cal_pass[k][to] / s->cal_pass[k][from];
    return s->gain[k] * pass_ms * (ratio - 1);
}

/* Predicted change from the calibrated frame times of the two levels, scaled to this run; NAN when
 * either level was not measured or the run's scale is not known yet. */
static double calibrated_delta(const gk_sched *s, int k, int from, int to)
{
    if (!s->calibrated[k] || !(s->cal_scale > 0) || isnan(s->cal_ms[k][from]) || isnan(s->cal_ms[k][to]))
        return NAN;
    return s->gain[k] * s->cal_scale * ((double)s->cal_ms[k][to] - s->cal_ms[k][from]);
}

/* Step response: exactly one active knob changed level since the previous measured frame, so the
 * difference in frame time is its doing. Returns 1 when it updated the model. The base absorbs the
 * rest so the prediction matches this frame. */
static int fit_step(gk_sched *s, const gk_budget *b, double ms)
{
    if (!s->have_prev)
        return 0;
    int changed = -1;
    for (int k = 0; k < b->n; k++)
        if (s->active[k] && b->level[k] != s->prev_level[k]) {
            if (changed >= 0)
                return 0;
            changed = k;
        }
    if (changed < 0)
        return 0;
    double dprior = prior(b, changed, b->level[changed]) - prior(b, changed, s->prev_level[changed]);
    if (dprior == 0)
        return 0;
    double predicted = pass_delta(s, b, changed, s->prev_pass_ms[changed], s->prev_level[changed], b->level[changed]);
    if (!isfinite(predicted))
        predicted = calibrated_delta(s, changed, s->prev_level[changed], b->level[changed]);
    if (isfinite(predicted) && fabs(predicted) > 1e-3) {
        /* the pass-scaled prediction, corrected by what the step really did (bounded: one noisy
           frame must not make the knob look free or ten times its cost) */
        double g = s->gain[changed] * (ms - s->prev_ms) / predicted;
        s->gain[changed] = fmin(fmax(0.5 * s->gain[changed] + 0.5 * g, 0.25), 4.0);
    }
    double w = (ms - s->prev_ms) / dprior;
    if (w < 0)
        w = 0; /* noise larger than the step: the knob is cheap */
    s->weight[changed] = 0.5 * s->weight[changed] + 0.5 * w;
    s->measured[changed] = true;
    double rest = ms;
    for (int k = 0; k < b->n; k++)
        if (s->active[k])
            rest -= s->weight[k] * prior(b, k, b->level[k]);
    s->base_ms = fmax(0, rest);
    return 1;
}

/* Predicted time saved by one step down of knob k (negative = added by a step up). */
static double step_delta(const gk_sched *s, const gk_budget *b, int k, int dir)
{
    int l = b->level[k];
    double d = pass_delta(s, b, k, s->pass_ms[k], l, l + dir);
    if (!isfinite(d))
        d = calibrated_delta(s, k, l, l + dir);
    if (isfinite(d))
        return d;
    return s->weight[k] * (prior(b, k, l + dir) - prior(b, k, l));
}

/* After a step of pass-scaled knob k, the predicted new time of its pass for every knob that scales
 * the same pass, so a second step in the same frame is predicted from the grown (or shrunk) pass. */
static void pass_moved(gk_sched *s, const gk_budget *b, int k, double delta)
{
    const char *pass = b->def[k]->scales_pass;
    if (!pass || !(s->pass_ms[k] > 0))
        return;
    for (int j = 0; j < b->n; j++)
        if (b->def[j]->scales_pass && strcmp(b->def[j]->scales_pass, pass) == 0 && s->pass_ms[j] > 0)
            s->pass_ms[j] = fmax(s->pass_ms[j] + delta, 1e-3);
}

/* What the step between level lo and lo + 1 of knob k is worth: the calibrated error it removes,
 * relative to the default configuration's error (0 or less: the richer level measured no better),
 * else 1/(levels - 1) of the knob's range. */
static double step_quality(const gk_sched *s, const gk_budget *b, int k, int lo)
{
    if (s->calibrated[k] && !isnan(s->cal_err[k][lo]) && !isnan(s->cal_err[k][lo + 1]))
        return ((double)s->cal_err[k][lo] - s->cal_err[k][lo + 1]) / (s->cal_default_err > 0 ? s->cal_default_err : 1);
    return 1.0 / (b->def[k]->n_values - 1);
}

static int step_down(gk_sched *s, gk_budget *b, double ms, gk_sched_change *ch, int max)
{
    double goal = s->p.target_ms * (1 - s->p.margin / 2);
    double predicted = ms;
    int n = 0;
    while (predicted > goal) {
        int best = -1;
        double best_score = -1, best_saved = 0;
        for (int k = 0; k < b->n; k++) {
            if (!movable(s, b, k) || b->level[k] <= b->min_level[k])
                continue;
            double saved = -step_delta(s, b, k, -1);
            /* A knob the model believes free still beats doing nothing: tiny score from its prior. */
            /* a step that loses no measured accuracy is the first to go */
            double score = fmax(saved, 1e-9 * (prior(b, k, b->level[k]) - prior(b, k, b->level[k] - 1)))
                           / fmax(step_quality(s, b, k, b->level[k] - 1), 1e-9);
            if (score > best_score) {
                best_score = score;
                best = k;
                best_saved = saved;
            }
        }
        if (best < 0)
            break; /* everything at its minimum: nothing left to trade */
        if (n >= max || n >= s->p.max_down_steps)
            break; /* measure before dropping further: the model may not know the savings yet */
        ch[n++] = (gk_sched_change){best, b->level[best], b->level[best] - 1};
        pass_moved(s, b, best, -best_saved);
        b->level[best]--;
        predicted -= fmax(best_saved, 0);
        if (s->last_dir[best] > 0) {
            s->reversals[best]++;
            s->direction_changes++;
            int shift = s->reversals[best] - 1 < 16 ? s->reversals[best] - 1 : 16;
            s->blocked_until[best] = s->frame + ((long)s->p.hold_base << shift);
        }
        s->last_dir[best] = -1;
        if (best_saved <= 0)
            break; /* the model cannot tell how much more to drop: measure again first */
    }
    return n;
}

/* Up: the knob that buys the most quality per predicted millisecond while the worst recent frame
 * plus what the steps add stays under target*(1 - margin/2). The first step may take any knob (its
 * cost may still be the prior's guess: the next frames measure it); further steps in the same
 * frame only knobs whose cost a step response has measured, so a far-under-target scene climbs
 * several levels at once on a model it can trust, and an unfitted model climbs one step at a time. */
static int step_up(gk_sched *s, gk_budget *b, gk_sched_change *ch, int max)
{
    double goal = s->p.target_ms * (1 - s->p.margin / 2);
    double predicted = s->under_worst_ms;
    int n = 0;
    while (n < max && n < s->p.max_up_steps) {
        int best = -1;
        double best_score = -1, best_added = 0;
        for (int k = 0; k < b->n; k++) {
            if (!movable(s, b, k) || b->level[k] >= b->max_level[k] || s->frame < s->blocked_until[k])
                continue;
            if (n > 0 && !s->measured[k] && !isfinite(pass_delta(s, b, k, s->pass_ms[k], b->level[k], b->level[k] + 1)) &&
                !isfinite(calibrated_delta(s, k, b->level[k], b->level[k] + 1)))
                continue; /* neither a step response, its pass's time nor a calibration: one unknown step at a time */
            double quality = step_quality(s, b, k, b->level[k]);
            if (quality <= 0)
                continue; /* measured no more accurate: not a richer level on this scene */
            double added = fmax(step_delta(s, b, k, +1), 0);
            if (predicted + added >= goal)
                continue;
            double score = quality / fmax(added, 1e-6);
            if (score > best_score) {
                best_score = score;
                best = k;
                best_added = added;
            }
        }
        if (best < 0)
            break;
        ch[n++] = (gk_sched_change){best, b->level[best], b->level[best] + 1};
        pass_moved(s, b, best, best_added);
        b->level[best]++;
        predicted += best_added;
        if (s->last_dir[best] < 0)
            s->direction_changes++;
        s->last_dir[best] = +1;
    }
    return n;
}

int gk_sched_update(gk_sched *s, gk_budget *b, double frame_ms, gk_sched_change *changes, int max)
{
    s->frame++;
    if (s->warm > 0) {
        s->warm--;
        return 0;
    }
    if (!(frame_ms >= 0) || !isfinite(frame_ms))
        return 0;
    if (!s->seeded) {
        seed(s, b, frame_ms);
        /* the calibration was measured at another size (and machine load): its times scale by this */
        s->cal_scale = s->cal_default_ms > 0 ? frame_ms / s->cal_default_ms : 0;
    }
    else if (!fit_step(s, b, frame_ms))
        fit(s, b, frame_ms);
    s->have_prev = true;
    s->prev_ms = frame_ms;
    for (int k = 0; k < b->n; k++) {
        s->prev_level[k] = b->level[k];
        s->prev_pass_ms[k] = s->pass_ms[k];
    }
    const gk_sched_params *p = &s->p;
    if (frame_ms > p->target_ms) {
        s->under_count = 0;
        return step_down(s, b, frame_ms, changes, max);
    }
    if (frame_ms >= p->target_ms * (1 - p->margin)) {
        s->under_count = 0;
        return 0;
    }
    if (s->under_count == 0 || frame_ms > s->under_worst_ms)
        s->under_worst_ms = frame_ms;
    /* Far under the target (the worst recent frame under half of it), a few frames are evidence
       enough; near it, wait longer so noise does not pull levels up and down. */
    int wait = s->under_worst_ms < p->target_ms * 0.5 ? p->up_after_far : p->up_after;
    if (++s->under_count < wait)
        return 0;
    s->under_count = 0;
    return step_up(s, b, changes, max);
}
