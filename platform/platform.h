/* The platform layer: display, GPU context, input and clock behind one small interface.
 * Backends: kms (DRM/KMS + GBM + EGL, buttons from GPIO or evdev) and mock (EGL surfaceless, an
 * FBO of the requested size, a virtual clock, input from a button script). Nothing here knows
 * about scenes or GI; the app sees the platform only through this header (DESIGN §1). */
#ifndef GK_PLATFORM_H
#define GK_PLATFORM_H

#include <stdbool.h>

#include "base/err.h"

enum gk_platform_kind { GK_PLATFORM_AUTO, GK_PLATFORM_KMS, GK_PLATFORM_MOCK };

enum gk_button { GK_BTN_NEXT, GK_BTN_PREV, GK_BTN_MODE, GK_BTN_INFO, GK_BTN_COUNT };

enum gk_input_kind {
    GK_INPUT_PRESS,     /* raw edge, after debounce */
    GK_INPUT_RELEASE,
    GK_INPUT_CLICK,     /* press + release shorter than hold_ms */
    GK_INPUT_HOLD,      /* held for hold_ms (sent once, while still held) */
    GK_INPUT_QUIT,      /* SIGTERM/SIGINT/SIGHUP/SIGQUIT or end of the mock script's run */
};

typedef struct gk_input_event {
    enum gk_input_kind kind;
    enum gk_button button;
    double time_s;      /* platform clock */
} gk_input_event;

enum gk_button_backend { GK_BUTTONS_NONE, GK_BUTTONS_GPIOD, GK_BUTTONS_EVDEV };

typedef struct gk_button_config {
    enum gk_button_backend backend;
    char chip[128];                 /* gpiod: "gpiochip0" or "/dev/gpiochip0" */
    int line[GK_BTN_COUNT];         /* gpiod line offsets, -1 = not wired */
    bool active_low;
    char bias[16];                  /* "as-is", "pull-up", "pull-down", "disabled" */
    int debounce_ms;
    int hold_ms;                    /* long-press threshold */
    char evdev_device[128];         /* evdev: "/dev/input/event0" or "" = first gpio-keys device */
    int evdev_code[GK_BTN_COUNT];   /* evdev key codes (KEY_*) */
} gk_button_config;

typedef struct gk_platform_desc {
    enum gk_platform_kind kind;
    int width, height;              /* mock: FBO size; kms: 0 = preferred mode */
    char device[128];               /* kms: "/dev/dri/card0", "" = first card with a connected connector */
    char mode[32];                  /* kms: "1920x1080" or "1920x1080@60", "" = preferred */
    gk_button_config buttons;
    char script_path[512];          /* mock: button script, "" = none */
    double frame_period_s;          /* mock: virtual clock step per present (default 1/60) */
    bool debug;                     /* EGL/GL debug output */
    bool quit_at_script_end;        /* mock: poll reports GK_INPUT_QUIT once the script's last
                                     * event is delivered and every button is up (default false) */
} gk_platform_desc;

typedef struct gk_platform gk_platform;

/* Fills desc with defaults (auto, 1280x720, no buttons, 60 Hz virtual clock). */
void gk_platform_desc_defaults(gk_platform_desc *desc);

/* Opens the platform and makes a GLES 3.1+ context current. Errors: GK_EINPUT for a bad button
 * script (file:line), GK_ERUNTIME for no display/GPU/chip. With kind AUTO and no connected
 * display, falls back to mock and logs it. */
gk_platform *gk_platform_open(const gk_platform_desc *desc, gk_err *e);
void gk_platform_close(gk_platform *p);

const char *gk_platform_name(const gk_platform *p);          /* "kms" or "mock" */
void gk_platform_size(const gk_platform *p, int *w, int *h); /* display (or FBO) size */
int gk_platform_gles_version(const gk_platform *p);          /* 31 or 32 */
/* The framebuffer the app draws the final image into: an FBO on mock, 0 on KMS. */
unsigned gk_platform_framebuffer(const gk_platform *p);

/* Shows the frame: page flip on KMS (waits for the previous flip), on mock advances the virtual
 * clock by one frame period. */
int gk_platform_present(gk_platform *p, gk_err *e);

/* Waits up to timeout_ms for input (0 = poll) and returns up to max events (count, or -1 on a
 * runtime error). Also reports GK_INPUT_QUIT after SIGINT/SIGTERM/SIGHUP/SIGQUIT. Buttons that disappear are
 * logged and reconnected here; that is not an error. */
int gk_platform_poll(gk_platform *p, int timeout_ms, gk_input_event *ev, int max);

/* Seconds since open: virtual on mock (frames * period), CLOCK_MONOTONIC on KMS. */
double gk_platform_now(const gk_platform *p);

/* True once SIGINT/SIGTERM/SIGHUP/SIGQUIT has been received. */
bool gk_platform_quit_requested(const gk_platform *p);

#endif
