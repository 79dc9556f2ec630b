/* Budget knobs: pinning from the command line and ranges from the config, with clear errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sched/budget.h"

static const gk_knob_def shadow_map = {
    .name = "shadow_map", .owner = "render", .n_values = 4,
    .values = {"256", "512", "1024", "2048"}, .cost = {1, 4, 16, 64}, .default_level = 2,
};
static const gk_knob_def scale = {
    .name = "render_scale", .owner = "render", .n_values = 3,
    .values = {"0.5", "0.75", "1"}, .cost = {1, 2.25f, 4}, .default_level = 2,
};

static void pin_sets_level_and_pins(void **state)
{
    (void)state;
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &shadow_map);
    gk_budget_add(&b, &scale);
    gk_err e = {0};
    assert_int_equal(gk_budget_pin_list(&b, "shadow_map=512,render_scale=0.5", &e), 0);
    assert_string_equal(gk_budget_value(&b, "shadow_map"), "512");
    assert_true(b.pinned[gk_budget_find(&b, "render_scale")]);
    assert_true(gk_budget_float(&b, "render_scale", 9) == 0.5f);
    char out[128];
    gk_budget_format(&b, out, sizeof out);
    assert_string_equal(out, "shadow_map=512,render_scale=0.5");
}

static void pin_rejects_unknown_knob_and_value(void **state)
{
    (void)state;
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &shadow_map);
    gk_err e = {0};
    assert_int_equal(gk_budget_pin_list(&b, "shadowmap=512", &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "unknown knob 'shadowmap'"));
    assert_int_equal(gk_budget_pin_list(&b, "shadow_map=300", &e), -1);
    assert_non_null(strstr(e.msg, "allowed: 256, 512, 1024, 2048"));
    assert_int_equal(gk_budget_pin_list(&b, "shadow_map", &e), -1);
    assert_non_null(strstr(e.msg, "KNOB=VALUE"));
}

static void range_clamps_and_rejects_inverted(void **state)
{
    (void)state;
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &shadow_map);
    gk_err e = {0};
    assert_int_equal(gk_budget_set_range(&b, "shadow_map", "256", "512", &e), 0);
    assert_string_equal(gk_budget_value(&b, "shadow_map"), "512");
    assert_int_equal(gk_budget_set_range(&b, "shadow_map", "2048", "256", &e), -1);
    assert_non_null(strstr(e.msg, "richer"));
}

static const gk_knob_def vpl_m = {
    .name = "vpl_m", .owner = "vpl", .n_values = 3, .values = {"2", "8", "adaptive"}, .cost = {1, 1, 1}, .default_level = 1,
};

/* Knob handles: the frame loop's typed joint. Resolved by the def's address once; a budget with
 * another layout (the bench declares knobs per configuration) re-resolves; values are numbers
 * parsed at declaration; a knob the budget lacks, or no budget, gives the fallback. */
static void knob_handles_resolve_and_read(void **state)
{
    (void)state;
    gk_budget a, b;
    gk_budget_init(&a);
    gk_budget_init(&b);
    gk_budget_add(&a, &shadow_map);
    gk_budget_add(&a, &vpl_m);
    gk_budget_add(&b, &vpl_m); /* another layout: vpl_m is knob 0 here, knob 1 in a */
    gk_knob k = gk_budget_knob(&a, &vpl_m);
    assert_int_equal(k.index, 1);
    assert_int_equal(gk_knob_level(&a, &k, -1), 1);
    assert_true(gk_knob_number(&a, &k, -1) == 8.0f);
    a.level[1] = 2; /* "adaptive" is not a number */
    assert_true(gk_knob_number(&a, &k, -1) == -1.0f);
    assert_true(isnan(a.number[1][2]) && a.number[1][0] == 2.0f);
    b.level[0] = 0;
    assert_int_equal(gk_knob_level(&b, &k, -1), 0); /* re-resolved against b */
    assert_int_equal(k.index, 0);
    assert_true(gk_knob_number(&b, &k, -1) == 2.0f);
    gk_knob missing = {&scale, -1};
    assert_int_equal(gk_knob_level(&a, &missing, 7), 7);
    assert_true(gk_knob_number(NULL, &missing, 0.25f) == 0.25f);
    assert_false(gk_knob_resolve(&a, &missing));
}

/* A pass that cannot run a level notes what it ran: the richest value not above it. */
static void note_ran_records_the_value_that_ran(void **state)
{
    (void)state;
    gk_budget ran;
    gk_budget_init(&ran);
    gk_budget_add(&ran, &scale);
    gk_budget_add(&ran, &shadow_map);
    gk_knob k = {&shadow_map, -1};
    ran.level[1] = 3; /* asked 2048 */
    gk_knob_note_ran(&ran, &k, 1024.0f);
    assert_string_equal(gk_budget_value(&ran, "shadow_map"), "1024");
    gk_knob_note_ran(&ran, &k, 700.0f); /* between values: the one below */
    assert_string_equal(gk_budget_value(&ran, "shadow_map"), "512");
    gk_knob_note_ran(&ran, &k, 100.0f); /* below every value: left as it was */
    assert_string_equal(gk_budget_value(&ran, "shadow_map"), "512");
    gk_knob_note_ran(NULL, &k, 256.0f); /* nobody reads it: no-op, no crash */
    gk_knob missing = {&vpl_m, -1};
    gk_knob_note_ran(&ran, &missing, 4.0f);
    assert_int_equal(ran.n, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(pin_sets_level_and_pins),
        cmocka_unit_test(pin_rejects_unknown_knob_and_value),
        cmocka_unit_test(range_clamps_and_rejects_inverted),
        cmocka_unit_test(knob_handles_resolve_and_read),
        cmocka_unit_test(note_ran_records_the_value_that_ran),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
