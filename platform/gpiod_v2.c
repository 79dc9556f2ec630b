/* Buttons on GPIO lines through libgpiod 2.x (bookworm-backports, Debian 13): one request for all
 * lines with both-edge detection, bias, active-low and kernel debounce
 * (gpiod_line_settings_set_debounce_period_us), timestamps on CLOCK_MONOTONIC. */
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gpiod.h>

#include "buttons.h"

typedef struct gpiod2_src {
    struct gpiod_chip *chip;
    struct gpiod_line_request *req;
    struct gpiod_edge_event_buffer *buf;
    int offset[GK_BTN_COUNT];
} gpiod2_src;

static void src_close(void *p)
{
    gpiod2_src *s = p;
    if (!s)
        return;
    if (s->buf)
        gpiod_edge_event_buffer_free(s->buf);
    if (s->req)
        gpiod_line_request_release(s->req);
    if (s->chip)
        gpiod_chip_close(s->chip);
    free(s);
}

static int parse_bias(const char *bias, enum gpiod_line_bias *out, gk_err *e)
{
    if (!bias[0] || strcmp(bias, "as-is") == 0)
        *out = GPIOD_LINE_BIAS_AS_IS;
    else if (strcmp(bias, "pull-up") == 0)
        *out = GPIOD_LINE_BIAS_PULL_UP;
    else if (strcmp(bias, "pull-down") == 0)
        *out = GPIOD_LINE_BIAS_PULL_DOWN;
    else if (strcmp(bias, "disabled") == 0)
        *out = GPIOD_LINE_BIAS_DISABLED;
    else
        return gk_fail(e, GK_EINPUT, "buttons: unknown bias '%s' (as-is, pull-up, pull-down, disabled)", bias);
    return 0;
}

static int request_lines(gpiod2_src *s, const gk_button_config *cfg, enum gpiod_line_bias bias, gk_err *e)
{
    unsigned offsets[GK_BTN_COUNT];
    size_t n = 0;
    for (int i = 0; i < GK_BTN_COUNT; i++)
        if (cfg->line[i] >= 0)
            offsets[n++] = (unsigned)cfg->line[i];
    struct gpiod_line_settings *ls = gpiod_line_settings_new();
    struct gpiod_line_config *lc = gpiod_line_config_new();
    struct gpiod_request_config *rc = gpiod_request_config_new();
    int rcode = -1;
    if (!ls || !lc || !rc) {
        gk_fail(e, GK_ERUNTIME, "out of memory");
        goto out;
    }
    gpiod_line_settings_set_direction(ls, GPIOD_LINE_DIRECTION_INPUT);
    gpiod_line_settings_set_edge_detection(ls, GPIOD_LINE_EDGE_BOTH);
    gpiod_line_settings_set_bias(ls, bias);
    gpiod_line_settings_set_active_low(ls, cfg->active_low); /* pressed = active = rising edge */
    gpiod_line_settings_set_debounce_period_us(ls, (unsigned long)(cfg->debounce_ms > 0 ? cfg->debounce_ms : 0) * 1000);
    gpiod_line_settings_set_event_clock(ls, GPIOD_LINE_CLOCK_MONOTONIC);
    if (gpiod_line_config_add_line_settings(lc, offsets, n, ls)) {
        gk_fail(e, GK_ERUNTIME, "buttons: line settings refused: %s", strerror(errno));
        goto out;
    }
    gpiod_request_config_set_consumer(rc, "gikiosk");
    s->req = gpiod_chip_request_lines(s->chip, rc, lc);
    if (!s->req) {
        gk_fail(e, GK_ERUNTIME, "buttons: cannot request the button lines of '%s': %s", cfg->chip, strerror(errno));
        goto out;
    }
    rcode = 0;
out:
    if (rc)
        gpiod_request_config_free(rc);
    if (lc)
        gpiod_line_config_free(lc);
    if (ls)
        gpiod_line_settings_free(ls);
    return rcode;
}

static int src_open(void **out, const gk_button_config *cfg, gk_err *e)
{
    enum gpiod_line_bias bias = GPIOD_LINE_BIAS_AS_IS;
    if (parse_bias(cfg->bias, &bias, e))
        return -1;
    int wired = 0;
    for (int i = 0; i < GK_BTN_COUNT; i++)
        wired += cfg->line[i] >= 0;
    if (!wired)
        return gk_fail(e, GK_EINPUT, "buttons: backend gpiod but no line configured");
    gpiod2_src *s = calloc(1, sizeof *s);
    if (!s)
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    char path[160];
    /* v2 opens by path only: accept "gpiochip0" as the config does */
    snprintf(path, sizeof path, "%s%s", cfg->chip[0] == '/' ? "" : "/dev/", cfg->chip);
    s->chip = gpiod_chip_open(path);
    if (!s->chip) {
        int err = errno;
        src_close(s);
        return gk_fail(e, GK_ERUNTIME, "buttons: cannot open GPIO chip '%s': %s", path, strerror(err));
    }
    struct gpiod_chip_info *info = gpiod_chip_get_info(s->chip);
    size_t n_lines = info ? gpiod_chip_info_get_num_lines(info) : 0;
    if (info)
        gpiod_chip_info_free(info);
    for (int i = 0; i < GK_BTN_COUNT; i++) {
        s->offset[i] = cfg->line[i];
        if (cfg->line[i] >= 0 && (size_t)cfg->line[i] >= n_lines) {
            src_close(s);
            return gk_fail(e, GK_ERUNTIME, "buttons: GPIO chip '%s' has no line %d (it has %zu)", path, cfg->line[i],
                           n_lines);
        }
    }
    if (request_lines(s, cfg, bias, e)) {
        src_close(s);
        return -1;
    }
    s->buf = gpiod_edge_event_buffer_new(64);
    if (!s->buf) {
        src_close(s);
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    }
    *out = s;
    return 0;
}

static int src_fds(void *p, struct pollfd *pfd, int max)
{
    gpiod2_src *s = p;
    if (max < 1)
        return 0;
    pfd[0] = (struct pollfd){.fd = gpiod_line_request_get_fd(s->req), .events = POLLIN};
    return 1;
}

static int src_read(void *p, gk_raw_edge *out, int max, gk_err *e)
{
    gpiod2_src *s = p;
    struct pollfd pfd = {.fd = gpiod_line_request_get_fd(s->req), .events = POLLIN};
    if (poll(&pfd, 1, 0) <= 0)
        return 0; /* the read below would block */
    if (pfd.revents & (POLLERR | POLLHUP | POLLNVAL))
        return gk_fail(e, GK_ERUNTIME, "device error");
    int got = gpiod_line_request_read_edge_events(s->req, s->buf, (size_t)(max < 64 ? max : 64));
    if (got < 0)
        return gk_fail(e, GK_ERUNTIME, "reading edge events: %s", strerror(errno));
    int n = 0;
    for (int k = 0; k < got; k++) {
        struct gpiod_edge_event *ev = gpiod_edge_event_buffer_get_event(s->buf, (unsigned long)k);
        unsigned offset = gpiod_edge_event_get_line_offset(ev);
        for (int b = 0; b < GK_BTN_COUNT; b++)
            if (s->offset[b] >= 0 && (unsigned)s->offset[b] == offset)
                out[n++] = (gk_raw_edge){
                    .time_s = (double)gpiod_edge_event_get_timestamp_ns(ev) * 1e-9,
                    .button = (enum gk_button)b,
                    .pressed = gpiod_edge_event_get_event_type(ev) == GPIOD_EDGE_EVENT_RISING_EDGE};
    }
    return n;
}

const struct gk_button_source_ops gk_gpiod_source_ops = {
    .name = "gpiod", .kernel_debounce = true,
    .open = src_open, .fds = src_fds, .read = src_read, .close = src_close,
};
