/* Buttons on the KMS platform: one source (libgpiod v1 or v2, or evdev) behind a small ops struct,
 * plus what every source shares: software debounce where the kernel does none, the gesture
 * detector, and surviving a chip that goes away (logged once, reconnect tried at most once a
 * second from poll). Times: sources report CLOCK_MONOTONIC seconds; the platform clock is
 * monotonic - mono_origin. */
#ifndef GK_PLATFORM_BUTTONS_H
#define GK_PLATFORM_BUTTONS_H

#include <poll.h>

#include "gesture.h"
#include "platform_impl.h"

#define GK_BUTTONS_MAX_FDS 4

struct gk_button_source_ops {
    const char *name;       /* "gpiod" or "evdev" */
    bool kernel_debounce;   /* true: no software debounce needed */
    /* Opens the source; a missing chip/line/device is GK_ERUNTIME naming it. */
    int (*open)(void **src, const gk_button_config *cfg, gk_err *e);
    int (*fds)(void *src, struct pollfd *pfd, int max);
    /* Reads what is pending: returns the number of edges (time in CLOCK_MONOTONIC seconds, 0 =
     * unknown), or -1 when the device is gone (the message in e). Never blocks. */
    int (*read)(void *src, gk_raw_edge *out, int max, gk_err *e);
    void (*close)(void *src);
};

extern const struct gk_button_source_ops gk_gpiod_source_ops; /* gpiod_v1.c or gpiod_v2.c */
extern const struct gk_button_source_ops gk_evdev_source_ops; /* evdev.c */

typedef double (*gk_clock_fn)(void *ctx);

typedef struct gk_buttons {
    const struct gk_button_source_ops *ops;
    void *src;                      /* NULL while the device is lost */
    gk_button_config cfg;
    gk_clock_fn now;
    void *clock_ctx;
    double mono_origin;
    gk_debounce debounce[GK_BTN_COUNT];
    gk_gesture gesture[GK_BTN_COUNT];
    double next_reconnect_s;
    int reconnects;                 /* successful reconnections, for tests and logs */
} gk_buttons;

/* Opens the configured backend (GK_BUTTONS_NONE gives NULL and no error). */
gk_buttons *gk_buttons_open(const gk_button_config *cfg, gk_clock_fn now, void *clock_ctx, double mono_origin,
                            gk_err *e);
gk_buttons *gk_buttons_open_with(const struct gk_button_source_ops *ops, const gk_button_config *cfg,
                                 gk_clock_fn now, void *clock_ctx, double mono_origin, gk_err *e);
/* The fds to poll (0 while lost). */
int gk_buttons_fds(gk_buttons *b, struct pollfd *pfd, int max);
/* After poll(): reads ready fds, debounces, runs gestures, pushes events; handles device loss. */
void gk_buttons_dispatch(gk_buttons *b, const struct pollfd *pfd, int n, gk_event_queue *q);
/* Time-driven work: settled debounce levels, HOLDs, reconnect attempts. */
void gk_buttons_tick(gk_buttons *b, gk_event_queue *q);
/* timeout_ms shortened to the next debounce/hold deadline or reconnect attempt (-1 = forever). */
int gk_buttons_timeout_ms(const gk_buttons *b, int timeout_ms);
void gk_buttons_close(gk_buttons *b);

#endif
