/* Debounce and gesture state machines, driven with synthetic timestamps. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "platform/gesture.h"

#define MS(x) ((x) / 1000.0)

/* Feeds a list of raw levels through a 20 ms debounce and collects the accepted edges, ticking at
 * each raw edge time and finally at `end` (as a backend's poll loop would). */
static int debounce_run(const double *t, const bool *level, int n, double end, double *out_t, bool *out_level)
{
    gk_debounce d;
    gk_debounce_init(&d, 20, false);
    int k = 0;
    double at;
    for (int i = 0; i < n; i++) {
        if (gk_debounce_tick(&d, t[i], &at)) {
            out_t[k] = at;
            out_level[k++] = d.state;
        }
        if (gk_debounce_edge(&d, level[i], t[i], &at)) {
            out_t[k] = at;
            out_level[k++] = d.state;
        }
    }
    if (gk_debounce_tick(&d, end, &at)) {
        out_t[k] = at;
        out_level[k++] = d.state;
    }
    return k;
}

static void debounce_bounce_burst_gives_one_edge(void **state)
{
    (void)state;
    /* press with contact bounce: 0, 1, 3, 4 ms ... settles pressed */
    const double t[] = {MS(0), MS(1), MS(3), MS(4), MS(6)};
    const bool lv[] = {true, false, true, false, true};
    double ot[8];
    bool ol[8];
    int n = debounce_run(t, lv, 5, MS(100), ot, ol);
    assert_int_equal(n, 1);
    assert_true(ol[0]);
    assert_true(ot[0] == 0);
}

static void debounce_release_bounce_then_settled(void **state)
{
    (void)state;
    /* clean press at 0, release at 200 with bounces at 201/202/205: press and one release */
    const double t[] = {MS(0), MS(200), MS(201), MS(202), MS(205)};
    const bool lv[] = {true, false, true, false, true == false};
    double ot[8];
    bool ol[8];
    int n = debounce_run(t, lv, 5, MS(400), ot, ol);
    assert_int_equal(n, 2);
    assert_true(ol[0] && !ol[1]);
    assert_true(fabs(ot[1] - 0.2) < 1e-12);
}

static void debounce_short_press_inside_window_is_not_lost(void **state)
{
    (void)state;
    /* press at 0, release at 10 ms (inside the 20 ms window): the release is accepted when the
     * window expires, at 20 ms */
    const double t[] = {MS(0), MS(10)};
    const bool lv[] = {true, false};
    double ot[8];
    bool ol[8];
    int n = debounce_run(t, lv, 2, MS(50), ot, ol);
    assert_int_equal(n, 2);
    assert_false(ol[1]);
    assert_true(fabs(ot[1] - MS(20)) < 1e-9);
}

static void debounce_edge_exactly_at_window_is_accepted(void **state)
{
    (void)state;
    gk_debounce d;
    gk_debounce_init(&d, 20, false);
    double at;
    assert_int_equal(gk_debounce_edge(&d, true, 1.0, &at), 1);
    assert_int_equal(gk_debounce_edge(&d, false, 1.0 + MS(19.9), &at), 0);
    assert_int_equal(gk_debounce_edge(&d, true, 1.0 + MS(19.95), &at), 0);
    assert_int_equal(gk_debounce_edge(&d, false, 1.0 + MS(20), &at), 1);
    assert_true(fabs(at - 1.020) < 1e-12);
    assert_true(gk_debounce_deadline(&d) < 0);
}

static void debounce_zero_window_passes_everything(void **state)
{
    (void)state;
    gk_debounce d;
    gk_debounce_init(&d, 0, false);
    double at;
    assert_int_equal(gk_debounce_edge(&d, true, 0, &at), 1);
    assert_int_equal(gk_debounce_edge(&d, false, 1e-6, &at), 1);
    assert_int_equal(gk_debounce_edge(&d, false, 2e-6, &at), 0); /* same level twice: no edge */
}

static void debounce_deadline_tells_when_to_wake(void **state)
{
    (void)state;
    gk_debounce d;
    gk_debounce_init(&d, 30, false);
    double at;
    gk_debounce_edge(&d, true, 5.0, &at);
    gk_debounce_edge(&d, false, 5.010, &at);
    assert_true(fabs(gk_debounce_deadline(&d) - 5.030) < 1e-12);
    assert_int_equal(gk_debounce_tick(&d, 5.029, &at), 0);
    assert_int_equal(gk_debounce_tick(&d, 5.031, &at), 1);
    assert_true(fabs(at - 5.030) < 1e-12);
    assert_false(d.state);
}

static int count_kind(const gk_input_event *ev, int n, enum gk_input_kind k)
{
    int c = 0;
    for (int i = 0; i < n; i++)
        c += ev[i].kind == k;
    return c;
}

static void gesture_short_press_is_click(void **state)
{
    (void)state;
    gk_gesture g;
    gk_gesture_init(&g, 800);
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    assert_int_equal(gk_gesture_edge(&g, GK_BTN_INFO, true, 1.0, ev), 1);
    assert_int_equal(ev[0].kind, GK_INPUT_PRESS);
    assert_int_equal(ev[0].button, GK_BTN_INFO);
    assert_int_equal(gk_gesture_tick(&g, GK_BTN_INFO, 1.5, ev), 0);
    assert_int_equal(gk_gesture_edge(&g, GK_BTN_INFO, false, 1.2, ev), 2);
    assert_int_equal(ev[0].kind, GK_INPUT_RELEASE);
    assert_int_equal(ev[1].kind, GK_INPUT_CLICK);
    assert_true(ev[1].time_s == 1.2);
}

static void gesture_hold_fires_while_held_once(void **state)
{
    (void)state;
    gk_gesture g;
    gk_gesture_init(&g, 800);
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    gk_gesture_edge(&g, GK_BTN_MODE, true, 2.0, ev);
    assert_true(fabs(gk_gesture_deadline(&g) - 2.8) < 1e-12);
    assert_int_equal(gk_gesture_tick(&g, GK_BTN_MODE, 2.79, ev), 0);
    assert_int_equal(gk_gesture_tick(&g, GK_BTN_MODE, 3.0, ev), 1);
    assert_int_equal(ev[0].kind, GK_INPUT_HOLD);
    assert_true(fabs(ev[0].time_s - 2.8) < 1e-12); /* the threshold time, not the late tick */
    assert_int_equal(gk_gesture_tick(&g, GK_BTN_MODE, 5.0, ev), 0); /* once */
    assert_true(gk_gesture_deadline(&g) < 0);
    int n = gk_gesture_edge(&g, GK_BTN_MODE, false, 6.0, ev);
    assert_int_equal(n, 1);
    assert_int_equal(ev[0].kind, GK_INPUT_RELEASE); /* no click after a hold */
}

static void gesture_release_exactly_at_threshold_is_hold(void **state)
{
    (void)state;
    gk_gesture g;
    gk_gesture_init(&g, 800);
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    gk_gesture_edge(&g, GK_BTN_NEXT, true, 0.1, ev);
    /* no tick in between: the release itself must discover the due hold */
    int n = gk_gesture_edge(&g, GK_BTN_NEXT, false, 0.1 + 0.8, ev);
    assert_int_equal(n, 2);
    assert_int_equal(ev[0].kind, GK_INPUT_HOLD);
    assert_int_equal(ev[1].kind, GK_INPUT_RELEASE);
    /* one tick before the threshold is still a click */
    gk_gesture_edge(&g, GK_BTN_NEXT, true, 10.0, ev);
    n = gk_gesture_edge(&g, GK_BTN_NEXT, false, 10.799, ev);
    assert_int_equal(count_kind(ev, n, GK_INPUT_CLICK), 1);
    assert_int_equal(count_kind(ev, n, GK_INPUT_HOLD), 0);
}

static void gesture_repeated_edges_are_ignored(void **state)
{
    (void)state;
    gk_gesture g;
    gk_gesture_init(&g, 500);
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    assert_int_equal(gk_gesture_edge(&g, GK_BTN_PREV, false, 0.0, ev), 0); /* release while up */
    assert_int_equal(gk_gesture_edge(&g, GK_BTN_PREV, true, 0.1, ev), 1);
    assert_int_equal(gk_gesture_edge(&g, GK_BTN_PREV, true, 0.2, ev), 0); /* press while down */
    /* the second press did not restart the hold timer */
    assert_true(fabs(gk_gesture_deadline(&g) - 0.6) < 1e-12);
}

static void gesture_new_press_rearms_hold(void **state)
{
    (void)state;
    gk_gesture g;
    gk_gesture_init(&g, 500);
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    gk_gesture_edge(&g, GK_BTN_PREV, true, 0.0, ev);
    assert_int_equal(gk_gesture_tick(&g, GK_BTN_PREV, 0.6, ev), 1);
    gk_gesture_edge(&g, GK_BTN_PREV, false, 0.7, ev);
    gk_gesture_edge(&g, GK_BTN_PREV, true, 1.0, ev);
    assert_int_equal(gk_gesture_tick(&g, GK_BTN_PREV, 1.5, ev), 1);
    assert_true(fabs(ev[0].time_s - 1.5) < 1e-12);
}

static void gesture_default_hold_when_unset(void **state)
{
    (void)state;
    gk_gesture g;
    gk_gesture_init(&g, 0); /* 0 = unset: 800 ms, never "everything is a hold" */
    assert_true(fabs(g.hold_s - 0.8) < 1e-12);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(debounce_bounce_burst_gives_one_edge),
        cmocka_unit_test(debounce_release_bounce_then_settled),
        cmocka_unit_test(debounce_short_press_inside_window_is_not_lost),
        cmocka_unit_test(debounce_edge_exactly_at_window_is_accepted),
        cmocka_unit_test(debounce_zero_window_passes_everything),
        cmocka_unit_test(debounce_deadline_tells_when_to_wake),
        cmocka_unit_test(gesture_short_press_is_click),
        cmocka_unit_test(gesture_hold_fires_while_held_once),
        cmocka_unit_test(gesture_release_exactly_at_threshold_is_hold),
        cmocka_unit_test(gesture_repeated_edges_are_ignored),
        cmocka_unit_test(gesture_new_press_rearms_hold),
        cmocka_unit_test(gesture_default_hold_when_unset),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
