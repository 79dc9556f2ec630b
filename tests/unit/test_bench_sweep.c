/* The bench's pure logic: sweep parsing/enumeration and the Pareto front. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "bench/bench.h"

static const gk_knob_def shadow = {.name = "shadow", .owner = "render", .n_values = 2,
                                   .values = {"hard", "pcss"}, .cost = {1, 8}, .default_level = 1};
static const gk_knob_def map = {.name = "shadow_map", .owner = "render", .n_values = 3,
                                .values = {"256", "512", "1024"}, .cost = {1, 4, 16}, .default_level = 1};
static const gk_knob_def res = {.name = "vct_res", .owner = "vct", .n_values = 2,
                                .values = {"32", "64"}, .cost = {1, 8}, .default_level = 1};

static void setup_budget(gk_budget *b)
{
    gk_budget_init(b);
    gk_budget_add(b, &shadow);
    gk_budget_add(b, &map);
    gk_budget_add(b, &res);
}

static void sweep_is_a_cartesian_product(void **state)
{
    (void)state;
    gk_budget b;
    setup_budget(&b);
    gk_bench_sweep s;
    gk_err e = {0};
    assert_int_equal(gk_bench_sweep_parse("shadow=hard,pcss;shadow_map=256,1024", &b, &s, &e), 0);
    assert_int_equal(gk_bench_sweep_count(&s), 4);
    char pins[256];
    gk_bench_sweep_pins(&s, 0, pins, sizeof pins);
    assert_string_equal(pins, "shadow=hard,shadow_map=256");
    gk_bench_sweep_pins(&s, 1, pins, sizeof pins);
    assert_string_equal(pins, "shadow=hard,shadow_map=1024");
    gk_bench_sweep_pins(&s, 3, pins, sizeof pins);
    assert_string_equal(pins, "shadow=pcss,shadow_map=1024");
}

static void sweep_rejects_unknown_knobs_and_values(void **state)
{
    (void)state;
    gk_budget b;
    setup_budget(&b);
    gk_bench_sweep s;
    gk_err e = {0};
    assert_int_equal(gk_bench_sweep_parse("shadows=hard", &b, &s, &e), -1);
    assert_non_null(strstr(e.msg, "unknown knob 'shadows'"));
    assert_int_equal(gk_bench_sweep_parse("shadow=soft", &b, &s, &e), -1);
    assert_non_null(strstr(e.msg, "no value 'soft'"));
    assert_int_equal(gk_bench_sweep_parse("shadow", &b, &s, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
}

static void default_sweeps_follow_the_method(void **state)
{
    (void)state;
    gk_budget b;
    setup_budget(&b);
    gk_bench_sweep s[8];
    assert_int_equal(gk_bench_default_sweeps(&b, "none", s, 8), 1);
    assert_int_equal(gk_bench_sweep_count(&s[0]), 6);
    assert_int_equal(gk_bench_default_sweeps(&b, "vct", s, 8), 1);
    assert_string_equal(s[0].knob[0], "vct_res");
}

static void pareto_front_keeps_only_undominated_points(void **state)
{
    (void)state;
    gk_bench_row rows[5];
    memset(rows, 0, sizeof rows);
    double t[5] = {1, 2, 3, 4, 2};
    double err[5] = {0.5, 0.3, 0.35, 0.1, NAN};
    for (int i = 0; i < 5; i++) {
        strcpy(rows[i].scene, "cornell");
        rows[i].frame_ms_median = t[i];
        rows[i].rel_rmse = err[i];
    }
    gk_bench_mark_pareto(rows, 5);
    assert_true(rows[0].pareto);
    assert_true(rows[1].pareto);
    assert_false(rows[2].pareto); /* slower and worse than row 1 */
    assert_true(rows[3].pareto);
    assert_false(rows[4].pareto); /* no error measured */
}

/* light-leak: the reference is black, the relative error infinite; the leaked radiance ranks. */
static void black_reference_ranks_by_leaked_radiance(void **state)
{
    (void)state;
    gk_bench_row rows[3];
    memset(rows, 0, sizeof rows);
    double t[3] = {1, 2, 3}, leak[3] = {0.3, 0.1, 0.2};
    for (int i = 0; i < 3; i++) {
        strcpy(rows[i].scene, "light-leak");
        strcpy(rows[i].reference, "light-leak");
        rows[i].frame_ms_median = t[i];
        rows[i].rel_rmse = INFINITY;
        rows[i].test_mean = leak[i];
    }
    assert_true(gk_bench_black_reference(rows, 3, "light-leak"));
    assert_false(gk_bench_black_reference(rows, 3, "cornell"));
    assert_true(gk_bench_row_error(&rows[1]) == 0.1);
    gk_bench_mark_pareto(rows, 3);
    assert_true(rows[0].pareto);
    assert_true(rows[1].pareto);
    assert_false(rows[2].pareto); /* slower and leaks more than row 1 */
}

/* `--sweep each` (the calibration's): the renderer's and the method's movable knobs, one at a time,
 * their automatic levels without the default; switches (fixed) and other methods' knobs left out. */
static void each_knob_sweeps_cover_the_movable_knobs(void **state)
{
    (void)state;
    static const gk_knob_def richest_manual = {.name = "vct_step", .owner = "vct", .n_values = 4,
                                               .values = {"2", "1.5", "1", "0.5"}, .cost = {1, 2, 3, 4},
                                               .default_level = 2, .auto_max_level = 2};
    static const gk_knob_def variant = {.name = "vct_variant", .owner = "vct", .n_values = 2,
                                        .values = {"default", "thesis"}, .cost = {1, 1}, .fixed = true};
    static const gk_knob_def other = {.name = "vpl_n", .owner = "vpl", .n_values = 2, .values = {"256", "512"},
                                      .cost = {1, 2}};
    gk_budget b;
    setup_budget(&b);
    gk_budget_add(&b, &richest_manual);
    gk_budget_add(&b, &variant);
    gk_budget_add(&b, &other);
    gk_bench_sweep s[GK_MAX_KNOBS];
    int n = gk_bench_each_knob_sweeps(&b, "vct", s, GK_MAX_KNOBS);
    assert_int_equal(n, 4); /* shadow, shadow_map, vct_res, vct_step */
    char pins[256];
    const char *want[] = {"shadow=hard", "shadow_map=256", "shadow_map=1024", "vct_res=32", "vct_step=2", "vct_step=1.5"};
    int w = 0;
    for (int i = 0; i < n; i++) {
        assert_int_equal(s[i].n_axes, 1);
        for (int c = 0; c < gk_bench_sweep_count(&s[i]); c++) {
            gk_bench_sweep_pins(&s[i], c, pins, sizeof pins);
            assert_true(w < 6);
            assert_string_equal(pins, want[w++]);
        }
    }
    assert_int_equal(w, 6); /* vct_step=0.5 is past auto_max_level: a reference mode, not calibrated */
    assert_int_equal(gk_bench_each_knob_sweeps(&b, "none", s, GK_MAX_KNOBS), 2); /* the renderer's only */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sweep_is_a_cartesian_product),
        cmocka_unit_test(sweep_rejects_unknown_knobs_and_values),
        cmocka_unit_test(default_sweeps_follow_the_method),
        cmocka_unit_test(each_knob_sweeps_cover_the_movable_knobs),
        cmocka_unit_test(pareto_front_keeps_only_undominated_points),
        cmocka_unit_test(black_reference_ranks_by_leaked_radiance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
