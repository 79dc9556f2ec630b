/* What the backends share behind platform.h: the gk_platform object (a small vtable + common
 * fields), the event queue the backends fill, and the backend entry points. Internal to platform/
 * and its tests; the app sees only platform.h. */
#ifndef GK_PLATFORM_IMPL_H
#define GK_PLATFORM_IMPL_H

#include "platform.h"

#define GK_EVQ_CAP 256

typedef struct gk_event_queue {
    gk_input_event ev[GK_EVQ_CAP];
    int head, count;
} gk_event_queue;

/* Appends; when full, the oldest event is dropped (a stuck app must not grow memory). */
void gk_evq_push(gk_event_queue *q, gk_input_event ev);
/* Moves up to max events to out, oldest first; returns the count. */
int gk_evq_pop(gk_event_queue *q, gk_input_event *out, int max);

struct gk_platform_ops {
    const char *name;
    int (*present)(gk_platform *p, gk_err *e);
    /* Waits up to timeout_ms (backends may return early on a signal) and pushes what happened
     * into p->queue. Returns 0, or -1 on a runtime error. */
    int (*poll)(gk_platform *p, int timeout_ms);
    double (*now)(const gk_platform *p);
    void (*close)(gk_platform *p);
};

struct gk_platform {
    const struct gk_platform_ops *ops;
    void *impl;
    int width, height;
    int gles_version;
    unsigned framebuffer;
    gk_event_queue queue;
};

/* Backends. gk_kms_open sets *no_display when the failure is "no DRM device / nothing connected"
 * (the case AUTO falls back from), as opposed to a display that exists but could not be driven. */
gk_platform *gk_mock_open(const gk_platform_desc *desc, gk_err *e);
gk_platform *gk_kms_open(const gk_platform_desc *desc, bool *no_display, gk_err *e);

/* The SIGINT/SIGTERM/SIGHUP/SIGQUIT flag (the one allowed singleton). */
bool gk_platform_signal_pending(void);

/* Seconds of CLOCK_MONOTONIC. */
double gk_monotonic_s(void);

#endif
