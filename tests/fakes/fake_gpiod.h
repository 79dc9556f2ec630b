/* Link-level fake of the libgpiod 1.x calls the gpiod_v1 button source uses. Inert until a test
 * calls fake_gpiod_enable(): until then every call forwards to the real libgpiod. Each requested
 * line gets a pipe as its event fd, so the backend's poll() works for real. */
#ifndef GK_FAKE_GPIOD_H
#define GK_FAKE_GPIOD_H

#include <stdbool.h>

#define FAKE_GPIOD_LINES 32
#define FAKE_GPIOD_EVENTS 32

typedef struct fake_gpiod_state {
    bool enabled;
    char chip_name[32];             /* what gpiod_chip_open_lookup accepts */
    bool chip_present;
    int n_lines;
    bool requested[FAKE_GPIOD_LINES];
    int request_flags[FAKE_GPIOD_LINES];
    int pipe[FAKE_GPIOD_LINES][2];
    int n_events[FAKE_GPIOD_LINES];
    double ev_time[FAKE_GPIOD_LINES][FAKE_GPIOD_EVENTS];
    bool ev_rising[FAKE_GPIOD_LINES][FAKE_GPIOD_EVENTS];
    bool lost;                      /* reads fail with ENODEV */
    int open_calls;
} fake_gpiod_state;

extern fake_gpiod_state fake_gpiod;

void fake_gpiod_enable(const char *chip_name, int n_lines);
void fake_gpiod_disable(void);
/* Queues an edge (time in CLOCK_MONOTONIC seconds) on a requested line and wakes its fd. */
void fake_gpiod_push(int line, double time_s, bool rising);
/* The chip is unplugged: pending reads fail with ENODEV and opening fails until restored. */
void fake_gpiod_unplug(void);
void fake_gpiod_replug(void);

#endif
