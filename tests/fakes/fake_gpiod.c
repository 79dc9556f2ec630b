/* Link-level libgpiod 1.x fake; see fake_gpiod.h. Built only against libgpiod 1.x headers. */
#if GK_GPIOD_MAJOR == 1
#include "fake_gpiod.h"

#include <dlfcn.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gpiod.h>

fake_gpiod_state fake_gpiod;

#define REAL(name) ((__typeof__(&name))dlsym(RTLD_NEXT, #name))

/* libgpiod's own structs are opaque to users, so the fake can give them its own layout. */
struct gpiod_chip {
    struct gpiod_line *lines[FAKE_GPIOD_LINES];
};
struct gpiod_line {
    unsigned offset;
};

void fake_gpiod_disable(void)
{
    if (fake_gpiod.enabled)
        for (int i = 0; i < FAKE_GPIOD_LINES; i++)
            if (fake_gpiod.requested[i]) {
                close(fake_gpiod.pipe[i][0]);
                close(fake_gpiod.pipe[i][1]);
            }
    memset(&fake_gpiod, 0, sizeof fake_gpiod);
}

void fake_gpiod_enable(const char *chip_name, int n_lines)
{
    fake_gpiod_disable();
    fake_gpiod.enabled = true;
    strncpy(fake_gpiod.chip_name, chip_name, sizeof fake_gpiod.chip_name - 1);
    fake_gpiod.chip_present = true;
    fake_gpiod.n_lines = n_lines;
}

void fake_gpiod_push(int line, double t, bool rising)
{
    int n = fake_gpiod.n_events[line];
    if (!fake_gpiod.requested[line] || n == FAKE_GPIOD_EVENTS)
        abort();
    fake_gpiod.ev_time[line][n] = t;
    fake_gpiod.ev_rising[line][n] = rising;
    fake_gpiod.n_events[line]++;
    if (write(fake_gpiod.pipe[line][1], "e", 1) != 1)
        abort();
}

void fake_gpiod_unplug(void)
{
    fake_gpiod.lost = true;
    fake_gpiod.chip_present = false;
    for (int i = 0; i < FAKE_GPIOD_LINES; i++)
        if (fake_gpiod.requested[i] && write(fake_gpiod.pipe[i][1], "x", 1) != 1)
            abort();
}

void fake_gpiod_replug(void)
{
    fake_gpiod.chip_present = true;
}

struct gpiod_chip *gpiod_chip_open_lookup(const char *descr)
{
    if (!fake_gpiod.enabled)
        return REAL(gpiod_chip_open_lookup)(descr);
    fake_gpiod.open_calls++;
    if (!fake_gpiod.chip_present || strcmp(descr, fake_gpiod.chip_name) != 0) {
        errno = ENOENT;
        return NULL;
    }
    fake_gpiod.lost = false;
    return calloc(1, sizeof(struct gpiod_chip));
}

void gpiod_chip_close(struct gpiod_chip *chip)
{
    if (!fake_gpiod.enabled) {
        REAL(gpiod_chip_close)(chip);
        return;
    }
    for (int i = 0; i < FAKE_GPIOD_LINES; i++)
        free(chip->lines[i]);
    free(chip);
}

struct gpiod_line *gpiod_chip_get_line(struct gpiod_chip *chip, unsigned int offset)
{
    if (!fake_gpiod.enabled)
        return REAL(gpiod_chip_get_line)(chip, offset);
    if ((int)offset >= fake_gpiod.n_lines || offset >= FAKE_GPIOD_LINES) {
        errno = EINVAL;
        return NULL;
    }
    if (!chip->lines[offset]) {
        chip->lines[offset] = calloc(1, sizeof(struct gpiod_line));
        chip->lines[offset]->offset = offset;
    }
    return chip->lines[offset];
}

int gpiod_line_request(struct gpiod_line *line, const struct gpiod_line_request_config *config, int default_val)
{
    if (!fake_gpiod.enabled)
        return REAL(gpiod_line_request)(line, config, default_val);
    unsigned o = line->offset;
    if (fake_gpiod.requested[o]) {
        errno = EBUSY;
        return -1;
    }
    if (config->request_type != GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES) {
        errno = EINVAL;
        return -1;
    }
    if (pipe(fake_gpiod.pipe[o]))
        return -1;
    fake_gpiod.requested[o] = true;
    fake_gpiod.request_flags[o] = config->flags;
    fake_gpiod.n_events[o] = 0;
    return 0;
}

void gpiod_line_release(struct gpiod_line *line)
{
    if (!fake_gpiod.enabled) {
        REAL(gpiod_line_release)(line);
        return;
    }
    unsigned o = line->offset;
    if (!fake_gpiod.requested[o])
        return;
    close(fake_gpiod.pipe[o][0]);
    close(fake_gpiod.pipe[o][1]);
    fake_gpiod.requested[o] = false;
}

int gpiod_line_event_get_fd(struct gpiod_line *line)
{
    if (!fake_gpiod.enabled)
        return REAL(gpiod_line_event_get_fd)(line);
    return fake_gpiod.requested[line->offset] ? fake_gpiod.pipe[line->offset][0] : -1;
}

int gpiod_line_event_read(struct gpiod_line *line, struct gpiod_line_event *event)
{
    if (!fake_gpiod.enabled)
        return REAL(gpiod_line_event_read)(line, event);
    unsigned o = line->offset;
    char byte;
    if (fake_gpiod.lost) {
        errno = ENODEV;
        return -1;
    }
    if (read(fake_gpiod.pipe[o][0], &byte, 1) != 1 || fake_gpiod.n_events[o] == 0) {
        errno = EIO;
        return -1;
    }
    double t = fake_gpiod.ev_time[o][0];
    event->ts.tv_sec = (time_t)t;
    event->ts.tv_nsec = (long)((t - (double)event->ts.tv_sec) * 1e9 + 0.5);
    event->event_type = fake_gpiod.ev_rising[o][0] ? GPIOD_LINE_EVENT_RISING_EDGE : GPIOD_LINE_EVENT_FALLING_EDGE;
    fake_gpiod.n_events[o]--;
    memmove(fake_gpiod.ev_time[o], fake_gpiod.ev_time[o] + 1, sizeof(double) * (size_t)fake_gpiod.n_events[o]);
    memmove(fake_gpiod.ev_rising[o], fake_gpiod.ev_rising[o] + 1, sizeof(bool) * (size_t)fake_gpiod.n_events[o]);
    return 0;
}
#else
/* libgpiod 2.x: the v1 fake does not apply (gpiod_v2.c is tested against its own v2 fake). */
typedef int gk_fake_gpiod_v1_not_built;
#endif
