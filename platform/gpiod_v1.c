/* Buttons on GPIO lines through libgpiod 1.x (Debian 12): both-edge events per line, bias and
 * active-low as request flags. v1 has no kernel debounce, so gk_buttons debounces in software. */
#include <errno.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>

#include <gpiod.h>

#include "buttons.h"

typedef struct gpiod_src {
    struct gpiod_chip *chip;
    struct gpiod_line *line[GK_BTN_COUNT];
    int fd[GK_BTN_COUNT];
} gpiod_src;

static void src_close(void *p)
{
    gpiod_src *s = p;
    if (!s)
        return;
    for (int i = 0; i < GK_BTN_COUNT; i++)
        if (s->line[i])
            gpiod_line_release(s->line[i]);
    if (s->chip)
        gpiod_chip_close(s->chip);
    free(s);
}

static int bias_flags(const char *bias, int *flags, gk_err *e)
{
    if (!bias[0] || strcmp(bias, "as-is") == 0)
        *flags = 0;
    else if (strcmp(bias, "pull-up") == 0)
        *flags = GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
    else if (strcmp(bias, "pull-down") == 0)
        *flags = GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
    else if (strcmp(bias, "disabled") == 0)
        *flags = GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
    else
        return gk_fail(e, GK_EINPUT, "buttons: unknown bias '%s' (as-is, pull-up, pull-down, disabled)", bias);
    return 0;
}

static int src_open(void **out, const gk_button_config *cfg, gk_err *e)
{
    int flags = 0;
    if (bias_flags(cfg->bias, &flags, e))
        return -1;
    if (cfg->active_low)
        flags |= GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW; /* pressed reads as 1: rising edge = press */
    int wired = 0;
    for (int i = 0; i < GK_BTN_COUNT; i++)
        wired += cfg->line[i] >= 0;
    if (!wired)
        return gk_fail(e, GK_EINPUT, "buttons: backend gpiod but no line configured");
    gpiod_src *s = calloc(1, sizeof *s);
    if (!s)
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    for (int i = 0; i < GK_BTN_COUNT; i++)
        s->fd[i] = -1;
    /* lookup accepts "gpiochip0", "/dev/gpiochip0", a label or a number */
    s->chip = gpiod_chip_open_lookup(cfg->chip);
    if (!s->chip) {
        int err = errno;
        src_close(s);
        return gk_fail(e, GK_ERUNTIME, "buttons: cannot open GPIO chip '%s': %s", cfg->chip, strerror(err));
    }
    for (int i = 0; i < GK_BTN_COUNT; i++) {
        if (cfg->line[i] < 0)
            continue;
        s->line[i] = gpiod_chip_get_line(s->chip, (unsigned)cfg->line[i]);
        if (!s->line[i]) {
            int err = errno;
            src_close(s);
            return gk_fail(e, GK_ERUNTIME, "buttons: GPIO chip '%s' has no line %d: %s", cfg->chip, cfg->line[i],
                           strerror(err));
        }
        struct gpiod_line_request_config rc = {
            .consumer = "gikiosk", .request_type = GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES, .flags = flags};
        if (gpiod_line_request(s->line[i], &rc, 0)) {
            int err = errno;
            s->line[i] = NULL;
            src_close(s);
            return gk_fail(e, GK_ERUNTIME, "buttons: cannot request line %d of '%s': %s", cfg->line[i], cfg->chip,
                           strerror(err));
        }
        s->fd[i] = gpiod_line_event_get_fd(s->line[i]);
    }
    *out = s;
    return 0;
}

static int src_fds(void *p, struct pollfd *pfd, int max)
{
    gpiod_src *s = p;
    int n = 0;
    for (int i = 0; i < GK_BTN_COUNT && n < max; i++)
        if (s->fd[i] >= 0)
            pfd[n++] = (struct pollfd){.fd = s->fd[i], .events = POLLIN};
    return n;
}

static int src_read(void *p, gk_raw_edge *out, int max, gk_err *e)
{
    gpiod_src *s = p;
    int n = 0;
    for (int i = 0; i < GK_BTN_COUNT; i++) {
        if (s->fd[i] < 0)
            continue;
        for (int guard = 0; guard < 16 && n < max; guard++) {
            struct pollfd pfd = {.fd = s->fd[i], .events = POLLIN};
            if (poll(&pfd, 1, 0) <= 0)
                break;
            if (pfd.revents & (POLLERR | POLLHUP | POLLNVAL))
                return gk_fail(e, GK_ERUNTIME, "line %d: device error", i);
            struct gpiod_line_event ev;
            if (gpiod_line_event_read(s->line[i], &ev))
                return gk_fail(e, GK_ERUNTIME, "reading line events: %s", strerror(errno));
            out[n++] = (gk_raw_edge){.time_s = (double)ev.ts.tv_sec + ev.ts.tv_nsec * 1e-9,
                                     .button = (enum gk_button)i,
                                     .pressed = ev.event_type == GPIOD_LINE_EVENT_RISING_EDGE};
        }
    }
    return n;
}

const struct gk_button_source_ops gk_gpiod_source_ops = {
    .name = "gpiod", .kernel_debounce = false,
    .open = src_open, .fds = src_fds, .read = src_read, .close = src_close,
};
