/* Button sources + debounce + gestures + reconnect; see buttons.h. */
#include "buttons.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"

#define RECONNECT_INTERVAL_S 1.0
#define MAX_CLOCK_SKEW_S 5.0 /* a kernel timestamp further than this from now is on another clock */

static const char *source_label(const gk_buttons *b)
{
    return b->cfg.backend == GK_BUTTONS_EVDEV ? (b->cfg.evdev_device[0] ? b->cfg.evdev_device : "gpio-keys")
                                              : b->cfg.chip;
}

static void reset_state(gk_buttons *b)
{
    for (int i = 0; i < GK_BTN_COUNT; i++) {
        gk_debounce_init(&b->debounce[i], b->ops->kernel_debounce ? 0 : b->cfg.debounce_ms, false);
        gk_gesture_init(&b->gesture[i], b->cfg.hold_ms);
    }
}

gk_buttons *gk_buttons_open_with(const struct gk_button_source_ops *ops, const gk_button_config *cfg,
                                 gk_clock_fn now, void *clock_ctx, double mono_origin, gk_err *e)
{
    gk_buttons *b = calloc(1, sizeof *b);
    if (!b) {
        gk_fail(e, GK_ERUNTIME, "out of memory");
        return NULL;
    }
    b->ops = ops;
    b->cfg = *cfg;
    b->now = now;
    b->clock_ctx = clock_ctx;
    b->mono_origin = mono_origin;
    reset_state(b);
    if (ops->open(&b->src, cfg, e)) {
        free(b);
        return NULL;
    }
    return b;
}

gk_buttons *gk_buttons_open(const gk_button_config *cfg, gk_clock_fn now, void *clock_ctx, double mono_origin,
                            gk_err *e)
{
    switch (cfg->backend) {
    case GK_BUTTONS_GPIOD: return gk_buttons_open_with(&gk_gpiod_source_ops, cfg, now, clock_ctx, mono_origin, e);
    case GK_BUTTONS_EVDEV: return gk_buttons_open_with(&gk_evdev_source_ops, cfg, now, clock_ctx, mono_origin, e);
    default: return NULL;
    }
}

int gk_buttons_fds(gk_buttons *b, struct pollfd *pfd, int max)
{
    if (!b || !b->src)
        return 0;
    return b->ops->fds(b->src, pfd, max);
}

static void push(gk_event_queue *q, const gk_input_event *ev, int n)
{
    for (int i = 0; i < n; i++)
        gk_evq_push(q, ev[i]);
}

static void tick_all(gk_buttons *b, double t, gk_event_queue *q)
{
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    for (int i = 0; i < GK_BTN_COUNT; i++) {
        double at;
        if (gk_debounce_tick(&b->debounce[i], t, &at))
            push(q, ev, gk_gesture_edge(&b->gesture[i], (enum gk_button)i, b->debounce[i].state, at, ev));
        push(q, ev, gk_gesture_tick(&b->gesture[i], (enum gk_button)i, t, ev));
    }
}

static void lose_device(gk_buttons *b, const char *why)
{
    gk_log("buttons: %s lost (%s); the kiosk keeps running and retries every second", source_label(b), why);
    b->ops->close(b->src);
    b->src = NULL;
    reset_state(b); /* the lines' state is unknown until they come back: all up, no gestures */
    b->next_reconnect_s = b->now(b->clock_ctx) + RECONNECT_INTERVAL_S;
}

void gk_buttons_dispatch(gk_buttons *b, const struct pollfd *pfd, int n, gk_event_queue *q)
{
    if (!b || !b->src)
        return;
    bool ready = false;
    for (int i = 0; i < n; i++)
        ready |= (pfd[i].revents & (POLLIN | POLLERR | POLLHUP)) != 0;
    if (!ready)
        return;
    gk_raw_edge edges[64];
    gk_err e = {0};
    int count = b->ops->read(b->src, edges, 64, &e);
    if (count < 0) {
        lose_device(b, e.msg);
        return;
    }
    double now = b->now(b->clock_ctx);
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    for (int k = 0; k < count; k++) {
        double t = edges[k].time_s > 0 ? edges[k].time_s - b->mono_origin : now;
        if (fabs(t - now) > MAX_CLOCK_SKEW_S)
            t = now;
        tick_all(b, t, q);
        int i = edges[k].button;
        double at;
        if (gk_debounce_edge(&b->debounce[i], edges[k].pressed, t, &at))
            push(q, ev, gk_gesture_edge(&b->gesture[i], (enum gk_button)i, edges[k].pressed, at, ev));
    }
}

void gk_buttons_tick(gk_buttons *b, gk_event_queue *q)
{
    if (!b)
        return;
    double now = b->now(b->clock_ctx);
    if (b->src) {
        tick_all(b, now, q);
        return;
    }
    if (now < b->next_reconnect_s)
        return;
    gk_err e = {0};
    if (b->ops->open(&b->src, &b->cfg, &e) == 0) {
        b->reconnects++;
        gk_log("buttons: %s is back", source_label(b));
    } else {
        b->src = NULL;
        b->next_reconnect_s = now + RECONNECT_INTERVAL_S;
    }
}

int gk_buttons_timeout_ms(const gk_buttons *b, int timeout_ms)
{
    if (!b)
        return timeout_ms;
    double now = b->now(b->clock_ctx);
    double due = -1;
    if (!b->src) {
        due = b->next_reconnect_s;
    } else {
        for (int i = 0; i < GK_BTN_COUNT; i++) {
            double d1 = gk_debounce_deadline(&b->debounce[i]);
            double d2 = gk_gesture_deadline(&b->gesture[i]);
            if (d1 >= 0 && (due < 0 || d1 < due))
                due = d1;
            if (d2 >= 0 && (due < 0 || d2 < due))
                due = d2;
        }
    }
    if (due < 0)
        return timeout_ms;
    int ms = (int)ceil((due - now) * 1000.0);
    if (ms < 0)
        ms = 0;
    return timeout_ms < 0 || ms < timeout_ms ? ms : timeout_ms;
}

void gk_buttons_close(gk_buttons *b)
{
    if (!b)
        return;
    if (b->src)
        b->ops->close(b->src);
    free(b);
}
