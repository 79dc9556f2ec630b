/* Buttons through the input layer (gpio-keys boards: the kernel debounces and reports EV_KEY).
 * The device is the configured one, or the first /dev/input/event* named "gpio-keys". */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <linux/input.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "buttons.h"

typedef struct evdev_src {
    int fd;
    int code[GK_BTN_COUNT];
} evdev_src;

static int open_device(const char *path)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd >= 0) {
        int clk = CLOCK_MONOTONIC; /* event times on the platform's clock (not wall time) */
        ioctl(fd, EVIOCSCLOCKID, &clk);
    }
    return fd;
}

static int find_gpio_keys(void)
{
    DIR *dir = opendir("/dev/input");
    if (!dir)
        return -1;
    int found = -1;
    for (struct dirent *de; found < 0 && (de = readdir(dir)) != NULL;) {
        if (strncmp(de->d_name, "event", 5) != 0)
            continue;
        char path[300], name[128] = "";
        snprintf(path, sizeof path, "/dev/input/%s", de->d_name);
        int fd = open_device(path);
        if (fd < 0)
            continue;
        if (ioctl(fd, EVIOCGNAME(sizeof name - 1), name) >= 0 && (strstr(name, "gpio-keys") || strstr(name, "gpio_keys")))
            found = fd;
        else
            close(fd);
    }
    closedir(dir);
    return found;
}

static int src_open(void **out, const gk_button_config *cfg, gk_err *e)
{
    int fd = cfg->evdev_device[0] ? open_device(cfg->evdev_device) : find_gpio_keys();
    if (fd < 0) {
        if (cfg->evdev_device[0])
            return gk_fail(e, GK_ERUNTIME, "buttons: cannot open input device '%s': %s", cfg->evdev_device,
                           strerror(errno));
        return gk_fail(e, GK_ERUNTIME, "buttons: no input device named gpio-keys in /dev/input");
    }
    evdev_src *s = calloc(1, sizeof *s);
    if (!s) {
        close(fd);
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    }
    s->fd = fd;
    memcpy(s->code, cfg->evdev_code, sizeof s->code);
    *out = s;
    return 0;
}

static int src_fds(void *p, struct pollfd *pfd, int max)
{
    evdev_src *s = p;
    if (max < 1)
        return 0;
    pfd[0] = (struct pollfd){.fd = s->fd, .events = POLLIN};
    return 1;
}

static int src_read(void *p, gk_raw_edge *out, int max, gk_err *e)
{
    evdev_src *s = p;
    int n = 0;
    struct input_event ev[32];
    while (n < max) {
        ssize_t got = read(s->fd, ev, sizeof ev);
        if (got < 0) {
            if (errno == EAGAIN || errno == EINTR)
                break;
            return gk_fail(e, GK_ERUNTIME, "reading input events: %s", strerror(errno));
        }
        if (got == 0)
            return gk_fail(e, GK_ERUNTIME, "input device closed");
        for (size_t i = 0; i < (size_t)got / sizeof ev[0] && n < max; i++) {
            if (ev[i].type != EV_KEY || ev[i].value == 2) /* 2 = autorepeat */
                continue;
            for (int b = 0; b < GK_BTN_COUNT; b++)
                if (s->code[b] && s->code[b] == ev[i].code)
                    out[n++] = (gk_raw_edge){.time_s = (double)ev[i].input_event_sec + ev[i].input_event_usec * 1e-6,
                                             .button = (enum gk_button)b, .pressed = ev[i].value == 1};
        }
        if ((size_t)got < sizeof ev)
            break;
    }
    return n;
}

static void src_close(void *p)
{
    evdev_src *s = p;
    if (!s)
        return;
    close(s->fd);
    free(s);
}

const struct gk_button_source_ops gk_evdev_source_ops = {
    .name = "evdev", .kernel_debounce = true,
    .open = src_open, .fds = src_fds, .read = src_read, .close = src_close,
};
