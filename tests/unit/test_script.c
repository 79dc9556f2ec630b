/* Button script parsing: the timeline of raw edges, and every error naming FILE:LINE. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "platform/script.h"

static void parses_actions_into_sorted_edges(void **state)
{
    (void)state;
    gk_script s;
    gk_err e = {0};
    const char *text = "# demo\n"
                       "0.5 next click\n"
                       "   \n"
                       "0.52 prev press  # overlaps the click's release\n"
                       "1 prev release\n"
                       "2.25\tmode hold 800\r\n"
                       "3 info click";
    assert_int_equal(gk_script_parse(text, "demo.txt", &s, &e), 0);
    assert_int_equal(s.count, 8);
    const struct { double t; enum gk_button b; bool p; } want[] = {
        {0.5, GK_BTN_NEXT, true}, {0.52, GK_BTN_PREV, true}, {0.55, GK_BTN_NEXT, false},
        {1.0, GK_BTN_PREV, false}, {2.25, GK_BTN_MODE, true}, {3.0, GK_BTN_INFO, true},
        {3.05, GK_BTN_INFO, false}, {3.05, GK_BTN_MODE, false},
    };
    /* mode's release at 2.25 + 0.8 = 3.05 and info's at 3.0 + 0.05: equal times keep script order
     * only up to float rounding, so compare as a set at that instant */
    for (int i = 0; i < 6; i++) {
        assert_true(fabs(s.edges[i].time_s - want[i].t) < 1e-9);
        assert_int_equal(s.edges[i].button, want[i].b);
        assert_int_equal(s.edges[i].pressed, want[i].p);
    }
    assert_true(fabs(s.edges[6].time_s - 3.05) < 1e-9 && fabs(s.edges[7].time_s - 3.05) < 1e-9);
    assert_false(s.edges[6].pressed || s.edges[7].pressed);
    assert_true(s.edges[6].button != s.edges[7].button);
    for (int i = 1; i < s.count; i++)
        assert_true(s.edges[i].time_s >= s.edges[i - 1].time_s);
    gk_script_free(&s);
}

/* The worst case of the old insertion sort: every hold lasts an hour, so each release lands after
   every later press. 100k holds = 200k edges; the merge sort makes at most n ceil(log2 n)
   comparisons (3.6 M here; the insertion sort made n^2/4 = 10^10), sorted and stable. The bound
   is counted, not timed. */
static void overlapping_holds_sort_in_n_log_n(void **state)
{
    (void)state;
    enum { HOLDS = 100000 };
    size_t cap = (size_t)HOLDS * 32;
    char *text = malloc(cap), *p = text;
    for (int i = 0; i < HOLDS; i++)
        p += snprintf(p, cap - (size_t)(p - text), "%d.%03d %s hold 3600000\n", i / 1000, i % 1000,
                      i % 2 ? "next" : "prev");
    gk_script s;
    gk_err e = {0};
    assert_int_equal(gk_script_parse(text, "long.txt", &s, &e), 0);
    assert_int_equal(s.count, 2 * HOLDS);
    for (int i = 0; i < HOLDS; i++) /* the presses first, in order; then the releases */
        assert_true(s.edges[i].pressed && fabs(s.edges[i].time_s - i / 1000.0) < 1e-9);
    for (int i = HOLDS; i < 2 * HOLDS; i++)
        assert_true(!s.edges[i].pressed && s.edges[i].time_s >= s.edges[i - 1].time_s);
    /* count the comparisons on the parser's own unsorted order (presses and releases interleaved) */
    gk_raw_edge *edges = malloc(sizeof *edges * 2 * HOLDS);
    for (int i = 0; i < HOLDS; i++) {
        edges[2 * i] = (gk_raw_edge){.time_s = i / 1000.0, .button = GK_BTN_NEXT, .pressed = true};
        edges[2 * i + 1] = (gk_raw_edge){.time_s = i / 1000.0 + 3600, .button = GK_BTN_NEXT, .pressed = false};
    }
    long n = 2 * HOLDS, log2n = 0;
    while ((1L << log2n) < n)
        log2n++;
    long comparisons = gk_script_sort_edges(edges, (int)n);
    print_message("# %ld edges sorted with %ld comparisons (n log2 n = %ld)\n", n, comparisons, n * log2n);
    assert_true(comparisons <= n * log2n);
    for (int i = 1; i < n; i++)
        assert_true(edges[i].time_s >= edges[i - 1].time_s);
    /* stability: equal times keep their order */
    gk_raw_edge ties[5] = {{.time_s = 1, .button = GK_BTN_NEXT}, {.time_s = 0, .button = GK_BTN_PREV},
                           {.time_s = 1, .button = GK_BTN_MODE}, {.time_s = 0, .button = GK_BTN_INFO},
                           {.time_s = 1, .button = GK_BTN_PREV}};
    gk_script_sort_edges(ties, 5);
    enum gk_button want[5] = {GK_BTN_PREV, GK_BTN_INFO, GK_BTN_NEXT, GK_BTN_MODE, GK_BTN_PREV};
    for (int i = 0; i < 5; i++)
        assert_int_equal(ties[i].button, want[i]);
    free(edges);
    gk_script_free(&s);
    free(text);
}

static void empty_and_comment_only_scripts_are_fine(void **state)
{
    (void)state;
    gk_script s;
    gk_err e = {0};
    assert_int_equal(gk_script_parse("", "a", &s, &e), 0);
    assert_int_equal(s.count, 0);
    gk_script_free(&s);
    assert_int_equal(gk_script_parse("# nothing\n\n   # still nothing\n", "a", &s, &e), 0);
    assert_int_equal(s.count, 0);
    gk_script_free(&s);
}

static void expect_error(const char *text, const char *want)
{
    gk_script s;
    gk_err e = {0};
    assert_int_equal(gk_script_parse(text, "s.txt", &s, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    if (!strstr(e.msg, want))
        fail_msg("message '%s' lacks '%s'", e.msg, want);
    assert_null(s.edges);
}

static void errors_name_file_line_and_problem(void **state)
{
    (void)state;
    expect_error("1 next click\n2 jump click\n", "s.txt:2: unknown button 'jump'");
    expect_error("x next click\n", "s.txt:1: bad time 'x'");
    expect_error("-1 next click\n", "s.txt:1: bad time '-1'");
    expect_error("1.5s next click\n", "s.txt:1: bad time '1.5s'");
    expect_error("nan next click\n", "s.txt:1: bad time 'nan'");
    expect_error("2 next click\n# c\n1 next click\n", "s.txt:3: time 1 goes backwards");
    expect_error("1 mode hold\n", "s.txt:1: hold needs a duration in ms");
    expect_error("1 mode hold 0\n", "s.txt:1: bad hold duration '0'");
    expect_error("1 mode hold 80x\n", "s.txt:1: bad hold duration '80x'");
    expect_error("1 next click now\n", "s.txt:1: trailing garbage 'now'");
    expect_error("1 mode hold 800 800\n", "s.txt:1: trailing garbage '800'");
    expect_error("1 next tap\n", "s.txt:1: unknown action 'tap'");
    expect_error("1 next\n", "s.txt:1: missing action");
    expect_error("1\n", "s.txt:1: missing button");
    expect_error("1 NEXT click\n", "unknown button 'NEXT'");
}

static void missing_file_is_input_error_naming_it(void **state)
{
    (void)state;
    gk_script s;
    gk_err e = {0};
    assert_int_equal(gk_script_load("/nonexistent/buttons.txt", &s, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "/nonexistent/buttons.txt"));
}

static void button_names_round_trip(void **state)
{
    (void)state;
    for (int b = 0; b < GK_BTN_COUNT; b++)
        assert_int_equal(gk_button_from_name(gk_button_name((enum gk_button)b)), b);
    assert_int_equal(gk_button_from_name("power"), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(parses_actions_into_sorted_edges),
        cmocka_unit_test(overlapping_holds_sort_in_n_log_n),
        cmocka_unit_test(empty_and_comment_only_scripts_are_fine),
        cmocka_unit_test(errors_name_file_line_and_problem),
        cmocka_unit_test(missing_file_is_input_error_naming_it),
        cmocka_unit_test(button_names_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
