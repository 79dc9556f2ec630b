/* Backend dispatch, defaults, the event queue and the SIGINT/SIGTERM/SIGHUP/SIGQUIT flag; see platform.h. */
#include "platform_impl.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/log.h"

/* Signals are process-wide, so this flag is the one singleton the platform keeps: the handler
 * only sets it; gk_platform_poll turns it into GK_INPUT_QUIT and the app closes the platform,
 * which restores the display (CRTC) the normal way. */
static volatile sig_atomic_t quit_signal;
static int handler_users;
/* SIGHUP (a closed terminal or session) and SIGQUIT end the run like SIGINT/SIGTERM: cleanly, the
   display restored, the stats and captures written. */
static const int quit_signals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
#define N_QUIT_SIGNALS ((int)(sizeof quit_signals / sizeof quit_signals[0]))
static struct sigaction saved[N_QUIT_SIGNALS];

static void on_quit_signal(int sig)
{
    (void)sig;
    quit_signal = 1;
}

static void install_signal_handlers(void)
{
    if (handler_users++ > 0)
        return;
    quit_signal = 0; /* before the first open the default action would have ended the process */
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_quit_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0; /* no SA_RESTART: a blocking poll() returns EINTR at once */
    for (int i = 0; i < N_QUIT_SIGNALS; i++)
        sigaction(quit_signals[i], &sa, &saved[i]);
}

static void restore_signal_handlers(void)
{
    if (handler_users == 0 || --handler_users > 0)
        return;
    for (int i = 0; i < N_QUIT_SIGNALS; i++)
        sigaction(quit_signals[i], &saved[i], NULL);
}

bool gk_platform_signal_pending(void) { return quit_signal != 0; }

double gk_monotonic_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

void gk_evq_push(gk_event_queue *q, gk_input_event ev)
{
    if (q->count == GK_EVQ_CAP) {
        q->head = (q->head + 1) % GK_EVQ_CAP;
        q->count--;
    }
    q->ev[(q->head + q->count) % GK_EVQ_CAP] = ev;
    q->count++;
}

int gk_evq_pop(gk_event_queue *q, gk_input_event *out, int max)
{
    int n = 0;
    while (n < max && q->count > 0) {
        out[n++] = q->ev[q->head];
        q->head = (q->head + 1) % GK_EVQ_CAP;
        q->count--;
    }
    return n;
}

void gk_platform_desc_defaults(gk_platform_desc *desc)
{
    memset(desc, 0, sizeof *desc);
    desc->kind = GK_PLATFORM_AUTO;
    desc->width = 1280;
    desc->height = 720;
    desc->buttons.backend = GK_BUTTONS_NONE;
    for (int i = 0; i < GK_BTN_COUNT; i++) {
        desc->buttons.line[i] = -1;
        desc->buttons.evdev_code[i] = 0;
    }
    /* evdev key codes, as config/kiosk.ini's defaults (linux/input-event-codes.h: KEY_RIGHT,
     * KEY_LEFT, KEY_M, KEY_I), so a USB keyboard works out of the box */
    desc->buttons.evdev_code[GK_BTN_NEXT] = 106;
    desc->buttons.evdev_code[GK_BTN_PREV] = 105;
    desc->buttons.evdev_code[GK_BTN_MODE] = 50;
    desc->buttons.evdev_code[GK_BTN_INFO] = 23;
    strcpy(desc->buttons.chip, "gpiochip0");
    strcpy(desc->buttons.bias, "as-is");
    desc->buttons.active_low = false;
    desc->buttons.debounce_ms = 20;
    desc->buttons.hold_ms = 800;
    desc->frame_period_s = 1.0 / 60.0;
    desc->debug = false;
}

gk_platform *gk_platform_open(const gk_platform_desc *desc, gk_err *e)
{
    gk_platform *p = NULL;
    if (desc->kind == GK_PLATFORM_MOCK) {
        p = gk_mock_open(desc, e);
    } else {
        bool no_display = false;
        gk_err kms_err = {0};
        p = gk_kms_open(desc, &no_display, &kms_err);
        if (!p && desc->kind == GK_PLATFORM_AUTO && no_display) {
            gk_log("no display: using the mock platform (%s)", kms_err.msg);
            p = gk_mock_open(desc, e);
        } else if (!p && e) {
            *e = kms_err;
        }
    }
    if (p)
        install_signal_handlers();
    return p;
}

void gk_platform_close(gk_platform *p)
{
    if (!p)
        return;
    p->ops->close(p);
    restore_signal_handlers();
}

const char *gk_platform_name(const gk_platform *p) { return p->ops->name; }

void gk_platform_size(const gk_platform *p, int *w, int *h)
{
    if (w)
        *w = p->width;
    if (h)
        *h = p->height;
}

int gk_platform_gles_version(const gk_platform *p) { return p->gles_version; }

unsigned gk_platform_framebuffer(const gk_platform *p) { return p->framebuffer; }

int gk_platform_present(gk_platform *p, gk_err *e) { return p->ops->present(p, e); }

int gk_platform_poll(gk_platform *p, int timeout_ms, gk_input_event *ev, int max)
{
    if (max <= 0)
        return 0;
    if (quit_signal) {
        ev[0] = (gk_input_event){.kind = GK_INPUT_QUIT, .button = GK_BTN_NEXT, .time_s = p->ops->now(p)};
        return 1;
    }
    /* Events already queued (e.g. buttons read while present() waited for a flip): no waiting. */
    if (p->ops->poll(p, p->queue.count > 0 ? 0 : timeout_ms) < 0)
        return -1;
    if (quit_signal) {
        ev[0] = (gk_input_event){.kind = GK_INPUT_QUIT, .button = GK_BTN_NEXT, .time_s = p->ops->now(p)};
        return 1;
    }
    return gk_evq_pop(&p->queue, ev, max);
}

double gk_platform_now(const gk_platform *p) { return p->ops->now(p); }

bool gk_platform_quit_requested(const gk_platform *p)
{
    (void)p;
    return quit_signal != 0;
}
