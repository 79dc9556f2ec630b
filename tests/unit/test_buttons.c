/* Button sources end to end above the fakes: libgpiod v1 (link-level fake) with software debounce,
 * gestures and chip loss/reconnect on a fake clock; evdev through a pipe carrying input_events. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <linux/input.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "base/log.h"
#include "fakes/fake_gpiod.h"
#include "platform/buttons.h"

#if GK_GPIOD_MAJOR == 1
#include <gpiod.h>
#endif

static double fake_now;
static double clock_fn(void *ctx) { (void)ctx; return fake_now; }

static gk_button_config gpio_config(void)
{
    gk_platform_desc d;
    gk_platform_desc_defaults(&d);
    gk_button_config c = d.buttons;
    c.backend = GK_BUTTONS_GPIOD;
    strcpy(c.chip, "gpiochip0");
    c.line[GK_BTN_NEXT] = 17;
    c.line[GK_BTN_PREV] = 27;
    c.line[GK_BTN_MODE] = 22;
    c.line[GK_BTN_INFO] = 23;
    c.active_low = true;
    strcpy(c.bias, "pull-up");
    c.debounce_ms = 20;
    c.hold_ms = 800;
    return c;
}

/* One poll round as the KMS backend does it: poll the fds (no waiting), dispatch, tick. */
static int pump(gk_buttons *b, gk_event_queue *q, gk_input_event *out, int max)
{
    struct pollfd pfd[GK_BUTTONS_MAX_FDS];
    int n = gk_buttons_fds(b, pfd, GK_BUTTONS_MAX_FDS);
    if (n)
        poll(pfd, (nfds_t)n, 0);
    gk_buttons_dispatch(b, pfd, n, q);
    gk_buttons_tick(b, q);
    return gk_evq_pop(q, out, max);
}

#if GK_GPIOD_MAJOR == 1
static int setup(void **state)
{
    (void)state;
    fake_gpiod_enable("gpiochip0", 28);
    fake_now = 100.0;
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    fake_gpiod_disable();
    return 0;
}

static void gpiod_requests_lines_with_bias_and_active_low(void **state)
{
    (void)state;
    gk_button_config c = gpio_config();
    gk_err e = {0};
    gk_buttons *b = gk_buttons_open(&c, clock_fn, NULL, 0, &e);
    assert_non_null(b);
    assert_true(fake_gpiod.requested[17] && fake_gpiod.requested[27] && fake_gpiod.requested[22] &&
                fake_gpiod.requested[23]);
    assert_int_equal(fake_gpiod.request_flags[17],
                     GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW | GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP);
    gk_buttons_close(b);
    assert_false(fake_gpiod.requested[17]);
}

static void gpiod_bouncy_click_gives_one_click(void **state)
{
    (void)state;
    gk_button_config c = gpio_config();
    gk_err e = {0};
    gk_buttons *b = gk_buttons_open(&c, clock_fn, NULL, 0, &e);
    assert_non_null(b);
    gk_event_queue q = {0};
    gk_input_event ev[16];
    /* press with 3 bounces within 5 ms, release 150 ms later with 2 bounces */
    fake_gpiod_push(17, 100.000, true);
    fake_gpiod_push(17, 100.001, false);
    fake_gpiod_push(17, 100.002, true);
    fake_gpiod_push(17, 100.004, false);
    fake_gpiod_push(17, 100.005, true);
    fake_now = 100.010;
    int n = pump(b, &q, ev, 16);
    assert_int_equal(n, 1);
    assert_int_equal(ev[0].kind, GK_INPUT_PRESS);
    assert_int_equal(ev[0].button, GK_BTN_NEXT);
    fake_gpiod_push(17, 100.150, false);
    fake_gpiod_push(17, 100.151, true);
    fake_gpiod_push(17, 100.153, false);
    fake_now = 100.200;
    n = pump(b, &q, ev, 16);
    assert_int_equal(n, 2);
    assert_int_equal(ev[0].kind, GK_INPUT_RELEASE);
    assert_int_equal(ev[1].kind, GK_INPUT_CLICK);
    assert_in_range((long)(ev[1].time_s * 1000 + 0.5), 100150, 100150);
    gk_buttons_close(b);
}

static void gpiod_hold_fires_while_held_and_timeout_is_bounded(void **state)
{
    (void)state;
    gk_button_config c = gpio_config();
    gk_err e = {0};
    gk_buttons *b = gk_buttons_open(&c, clock_fn, NULL, 0, &e);
    gk_event_queue q = {0};
    gk_input_event ev[16];
    fake_gpiod_push(22, 100.0, true);
    fake_now = 100.05;
    assert_int_equal(pump(b, &q, ev, 16), 1);
    /* the poll timeout is cut to the hold deadline, so HOLD is not late by a whole timeout */
    assert_int_equal(gk_buttons_timeout_ms(b, 5000), 750);
    fake_now = 100.79;
    assert_int_equal(pump(b, &q, ev, 16), 0);
    fake_now = 100.81;
    assert_int_equal(pump(b, &q, ev, 16), 1);
    assert_int_equal(ev[0].kind, GK_INPUT_HOLD);
    assert_int_equal(ev[0].button, GK_BTN_MODE);
    fake_gpiod_push(22, 101.5, false);
    fake_now = 101.6;
    assert_int_equal(pump(b, &q, ev, 16), 1);
    assert_int_equal(ev[0].kind, GK_INPUT_RELEASE);
    gk_buttons_close(b);
}

static void gpiod_chip_loss_is_logged_and_reconnected_once_a_second(void **state)
{
    (void)state;
    gk_button_config c = gpio_config();
    gk_err e = {0};
    gk_buttons *b = gk_buttons_open(&c, clock_fn, NULL, 0, &e);
    gk_event_queue q = {0};
    gk_input_event ev[16];
    fake_gpiod_unplug();
    assert_int_equal(pump(b, &q, ev, 16), 0); /* the read fails: lost, not an error */
    assert_null(b->src);
    int opens = fake_gpiod.open_calls;
    for (int i = 0; i < 50; i++) { /* 50 polls within 0.5 s: no reconnect attempt yet */
        fake_now += 0.01;
        pump(b, &q, ev, 16);
    }
    assert_int_equal(fake_gpiod.open_calls, opens);
    fake_now += 0.6;
    pump(b, &q, ev, 16);
    assert_int_equal(fake_gpiod.open_calls, opens + 1); /* tried, chip still absent */
    fake_now += 0.5;
    pump(b, &q, ev, 16);
    assert_int_equal(fake_gpiod.open_calls, opens + 1); /* not again within the second */
    fake_gpiod_replug();
    fake_now += 0.6;
    pump(b, &q, ev, 16);
    assert_int_equal(b->reconnects, 1);
    assert_non_null(b->src);
    fake_gpiod_push(23, fake_now, true);
    fake_gpiod_push(23, fake_now + 0.1, false);
    fake_now += 0.2;
    int n = pump(b, &q, ev, 16);
    assert_int_equal(n, 3);
    assert_int_equal(ev[2].kind, GK_INPUT_CLICK);
    assert_int_equal(ev[2].button, GK_BTN_INFO);
    gk_buttons_close(b);
}

static void gpiod_missing_chip_or_line_names_it(void **state)
{
    (void)state;
    gk_button_config c = gpio_config();
    gk_err e = {0};
    strcpy(c.chip, "gpiochip4");
    assert_null(gk_buttons_open(&c, clock_fn, NULL, 0, &e));
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_non_null(strstr(e.msg, "'gpiochip4'"));
    c = gpio_config();
    c.line[GK_BTN_INFO] = 40;
    assert_null(gk_buttons_open(&c, clock_fn, NULL, 0, &e));
    assert_non_null(strstr(e.msg, "no line 40"));
    assert_false(fake_gpiod.requested[17]); /* the lines already requested were released */
    c = gpio_config();
    strcpy(c.bias, "pullup");
    assert_null(gk_buttons_open(&c, clock_fn, NULL, 0, &e));
    assert_int_equal(e.code, GK_EINPUT);
}
#endif

static void write_key(int fd, double t, int code, int value)
{
    struct input_event ev = {0};
    ev.input_event_sec = (long)t;
    ev.input_event_usec = (long)((t - (long)t) * 1e6 + 0.5);
    ev.type = EV_KEY;
    ev.code = (unsigned short)code;
    ev.value = value;
    assert_int_equal(write(fd, &ev, sizeof ev), (int)sizeof ev);
    struct input_event syn = ev;
    syn.type = EV_SYN;
    syn.code = SYN_REPORT;
    syn.value = 0;
    assert_int_equal(write(fd, &syn, sizeof syn), (int)sizeof syn);
}

static void evdev_keys_become_gestures_and_eof_is_loss(void **state)
{
    (void)state;
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    gk_platform_desc d;
    gk_platform_desc_defaults(&d);
    gk_button_config c = d.buttons;
    c.backend = GK_BUTTONS_EVDEV;
    snprintf(c.evdev_device, sizeof c.evdev_device, "/proc/self/fd/%d", fds[0]);
    fake_now = 50.0;
    gk_err e = {0};
    gk_buttons *b = gk_buttons_open(&c, clock_fn, NULL, 0, &e);
    assert_non_null(b);
    gk_event_queue q = {0};
    gk_input_event ev[16];
    write_key(fds[1], 50.0, KEY_LEFT, 1);
    write_key(fds[1], 50.0, KEY_LEFT, 2); /* autorepeat: ignored */
    write_key(fds[1], 50.1, KEY_LEFT, 0);
    write_key(fds[1], 50.1, KEY_A, 1);        /* not mapped: ignored */
    fake_now = 50.2;
    int n = pump(b, &q, ev, 16);
    assert_int_equal(n, 3);
    assert_int_equal(ev[0].kind, GK_INPUT_PRESS);
    assert_int_equal(ev[0].button, GK_BTN_PREV);
    assert_int_equal(ev[2].kind, GK_INPUT_CLICK);
    close(fds[1]); /* the device goes away */
    pump(b, &q, ev, 16);
    assert_null(b->src);
    gk_buttons_close(b);
    close(fds[0]);
    strcpy(c.evdev_device, "/nonexistent/event7");
    assert_null(gk_buttons_open(&c, clock_fn, NULL, 0, &e));
    assert_non_null(strstr(e.msg, "/nonexistent/event7"));
}

int main(void)
{
    gk_log_set_quiet(1);
    const struct CMUnitTest tests[] = {
#if GK_GPIOD_MAJOR == 1
        cmocka_unit_test_setup_teardown(gpiod_requests_lines_with_bias_and_active_low, setup, teardown),
        cmocka_unit_test_setup_teardown(gpiod_bouncy_click_gives_one_click, setup, teardown),
        cmocka_unit_test_setup_teardown(gpiod_hold_fires_while_held_and_timeout_is_bounded, setup, teardown),
        cmocka_unit_test_setup_teardown(gpiod_chip_loss_is_logged_and_reconnected_once_a_second, setup, teardown),
        cmocka_unit_test_setup_teardown(gpiod_missing_chip_or_line_names_it, setup, teardown),
#endif
        cmocka_unit_test(evdev_keys_become_gestures_and_eof_is_loss),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
