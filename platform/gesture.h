/* Button state machines over edge timestamps, shared by every input source (GPIO, evdev, the mock's
 * script), so scripted runs exercise the same code as real buttons. Pure C, no clock of its own:
 * callers pass times in seconds on the platform clock.
 *
 * gk_debounce: software debounce for sources without kernel debounce (libgpiod v1). An edge closer
 *   than the window to the last accepted edge is not accepted; if the line has settled on a new
 *   level when the window expires, that level is accepted then (gk_debounce_tick), so a bounce
 *   burst gives exactly one edge and a very short real press is not lost.
 * gk_gesture: turns debounced edges into PRESS/RELEASE, CLICK (released before hold_ms) and HOLD
 *   (sent once, time-driven through gk_gesture_tick, so it fires while the button is still held). */
#ifndef GK_PLATFORM_GESTURE_H
#define GK_PLATFORM_GESTURE_H

#include <stdbool.h>

#include "platform.h"

/* One raw edge of one button: the unit exchanged between input sources and the state machines. */
typedef struct gk_raw_edge {
    double time_s;
    enum gk_button button;
    bool pressed;
} gk_raw_edge;

typedef struct gk_debounce {
    double window_s;
    bool state;         /* accepted level (true = pressed) */
    bool raw;           /* last level seen */
    double raw_t;       /* time of the last raw edge */
    bool have_accepted; /* an edge has been accepted (last_t is valid) */
    double last_t;      /* time of the last accepted edge */
} gk_debounce;

void gk_debounce_init(gk_debounce *d, int debounce_ms, bool initial_pressed);
/* Feeds a raw level change at t. Returns 1 and sets *edge_t when it is accepted now, else 0. */
int gk_debounce_edge(gk_debounce *d, bool pressed, double t, double *edge_t);
/* Accepts a level that differs from the accepted one once the window has expired at now.
 * Returns 1 (and the accepted level is d->state, at *edge_t = max(raw_t, last_t + window)), else 0. */
int gk_debounce_tick(gk_debounce *d, double now, double *edge_t);
/* Time at which gk_debounce_tick would accept a pending level, or -1 when nothing is pending. */
double gk_debounce_deadline(const gk_debounce *d);

typedef struct gk_gesture {
    double hold_s;
    bool down;
    bool hold_sent;
    double down_t;
} gk_gesture;

#define GK_GESTURE_MAX_EVENTS 3 /* most events one call can append */

void gk_gesture_init(gk_gesture *g, int hold_ms);
/* Feeds one debounced edge at t; appends to out (room for GK_GESTURE_MAX_EVENTS) and returns the
 * count: a HOLD that was due before t first, then PRESS, or RELEASE (+ CLICK when released before
 * hold_ms). A repeated edge (press while down, release while up) gives nothing. */
int gk_gesture_edge(gk_gesture *g, enum gk_button b, bool pressed, double t, gk_input_event *out);
/* Appends the HOLD (time = press time + hold) when the button has been down hold_ms at now. */
int gk_gesture_tick(gk_gesture *g, enum gk_button b, double now, gk_input_event *out);
/* Time of the pending HOLD, or -1: lets backends bound their poll timeout. */
double gk_gesture_deadline(const gk_gesture *g);

#endif
