/* Debounce and gesture state machines; see gesture.h. */
#include "gesture.h"

/* Times are doubles of seconds; a half-microsecond slack keeps "exactly at the threshold" exact
 * when thresholds are built from milliseconds (0.8 s + 0.001 s is not 0.801 in binary). */
#define TIME_EPS 5e-7

void gk_debounce_init(gk_debounce *d, int debounce_ms, bool initial_pressed)
{
    d->window_s = debounce_ms > 0 ? debounce_ms / 1000.0 : 0.0;
    d->state = d->raw = initial_pressed;
    d->raw_t = 0;
    d->have_accepted = false;
    d->last_t = 0;
}

int gk_debounce_edge(gk_debounce *d, bool pressed, double t, double *edge_t)
{
    d->raw = pressed;
    d->raw_t = t;
    if (pressed == d->state)
        return 0; /* back to the accepted level: the bounce ended where it started */
    if (d->have_accepted && t - d->last_t < d->window_s - TIME_EPS)
        return 0; /* inside the window: pending until gk_debounce_tick sees it settled */
    d->state = pressed;
    d->have_accepted = true;
    d->last_t = t;
    *edge_t = t;
    return 1;
}

double gk_debounce_deadline(const gk_debounce *d)
{
    if (d->raw == d->state)
        return -1;
    double expiry = d->last_t + d->window_s;
    return d->raw_t > expiry ? d->raw_t : expiry;
}

int gk_debounce_tick(gk_debounce *d, double now, double *edge_t)
{
    double due = gk_debounce_deadline(d);
    if (due < 0 || now < due - TIME_EPS)
        return 0;
    d->state = d->raw;
    d->have_accepted = true;
    d->last_t = due;
    *edge_t = due;
    return 1;
}

void gk_gesture_init(gk_gesture *g, int hold_ms)
{
    g->hold_s = (hold_ms > 0 ? hold_ms : 800) / 1000.0;
    g->down = false;
    g->hold_sent = false;
    g->down_t = 0;
}

static gk_input_event make_event(enum gk_input_kind kind, enum gk_button b, double t)
{
    gk_input_event ev = {.kind = kind, .button = b, .time_s = t};
    return ev;
}

double gk_gesture_deadline(const gk_gesture *g)
{
    return g->down && !g->hold_sent ? g->down_t + g->hold_s : -1;
}

int gk_gesture_tick(gk_gesture *g, enum gk_button b, double now, gk_input_event *out)
{
    double due = gk_gesture_deadline(g);
    if (due < 0 || now < due - TIME_EPS)
        return 0;
    g->hold_sent = true;
    out[0] = make_event(GK_INPUT_HOLD, b, due);
    return 1;
}

int gk_gesture_edge(gk_gesture *g, enum gk_button b, bool pressed, double t, gk_input_event *out)
{
    int n = gk_gesture_tick(g, b, t, out); /* held exactly hold_ms counts as a hold */
    if (pressed == g->down)
        return n;
    if (pressed) {
        g->down = true;
        g->hold_sent = false;
        g->down_t = t;
        out[n++] = make_event(GK_INPUT_PRESS, b, t);
        return n;
    }
    g->down = false;
    out[n++] = make_event(GK_INPUT_RELEASE, b, t);
    if (!g->hold_sent)
        out[n++] = make_event(GK_INPUT_CLICK, b, t);
    return n;
}
