/* Per-(scene, method) memory of the kiosk: a visit starts from its own remembered levels and cost
 * model, or from the defaults on a first visit -- not from whatever the previous scene left. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "kiosk/visit_memory.h"

static const gk_knob_def scale = {
    .name = "render_scale", .owner = "render", .n_values = 3, .values = {"0.5", "0.75", "1"},
    .cost = {1, 2.25f, 4}, .default_level = 2,
};
static const gk_knob_def res = {
    .name = "vct_res", .owner = "vct", .n_values = 3, .values = {"32", "64", "128"}, .cost = {1, 4, 24},
    .default_level = 1,
};

static void setup_budget(gk_budget *b)
{
    gk_budget_init(b);
    gk_budget_add(b, &scale);
    gk_budget_add(b, &res);
}

static void remembered_per_scene_and_method(void **state)
{
    (void)state;
    gk_visit_memory *m = calloc(1, sizeof *m);
    gk_budget b;
    setup_budget(&b);
    gk_sched_params p;
    gk_sched_params_defaults(&p, 100);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, NULL);
    assert_false(gk_visit_restore(m, 0, 1, &b, &s)); /* first visit: nothing remembered */

    /* Scene 0 (heavy) ends at the floor with a learned model ... */
    b.level[0] = 0, b.level[1] = 0;
    s.seeded = true, s.base_ms = 42, s.weight[1] = 3, s.warm = 0;
    gk_visit_save(m, 0, 1, &b, &s);
    /* ... scene 1 starts from the defaults, not from scene 0's floor. */
    assert_false(gk_visit_restore(m, 1, 1, &b, &s));
    gk_budget_reset_defaults(&b);
    assert_int_equal(b.level[0], 2);
    assert_int_equal(b.level[1], 1);
    /* Scene 0 with another method is another visit. */
    assert_false(gk_visit_restore(m, 0, 2, &b, &s));

    /* Back to scene 0: its levels and model return; its warm-up starts over. */
    gk_sched fresh;
    gk_sched_reset(&fresh, &p, &b, NULL);
    assert_true(gk_visit_restore(m, 0, 1, &b, &fresh));
    assert_int_equal(b.level[0], 0);
    assert_int_equal(b.level[1], 0);
    assert_true(fresh.seeded && fresh.base_ms == 42 && fresh.weight[1] == 3);
    assert_int_equal(fresh.warm, p.warmup);

    /* A pin wins over the memory; out-of-range slots are ignored. */
    b.level[0] = 1;
    b.pinned[0] = true;
    assert_true(gk_visit_restore(m, 0, 1, &b, &fresh));
    assert_int_equal(b.level[0], 1);
    gk_visit_save(m, GK_MAX_PLAYLIST, 0, &b, &s);
    assert_false(gk_visit_restore(m, GK_MAX_PLAYLIST, 0, &b, &s));
    free(m);
}

static void defaults_respect_ranges_and_pins(void **state)
{
    (void)state;
    gk_budget b;
    setup_budget(&b);
    b.max_level[0] = 1; /* [budgets] render_scale = 0.5..0.75 */
    b.level[1] = 2;
    b.pinned[1] = true;
    gk_budget_reset_defaults(&b);
    assert_int_equal(b.level[0], 1);
    assert_int_equal(b.level[1], 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(remembered_per_scene_and_method),
        cmocka_unit_test(defaults_respect_ranges_and_pins),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
