/* Frame-time scheduler on a synthetic cost model: convergence under the target, no oscillation,
 * pins and ranges, recovery when the load drops. The synthetic "true" costs deliberately differ
 * from the knobs' priors (the shadow map's true cost grows linearly while its prior grows
 * quadratically), so the online fit has something to learn. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "sched/scheduler.h"

static const gk_knob_def scale = {
    .name = "render_scale", .owner = "render", .n_values = 3,
    .values = {"0.5", "0.75", "1"}, .cost = {1, 2.25f, 4}, .default_level = 2,
};
static const gk_knob_def shadow = {
    .name = "shadow_map", .owner = "render", .n_values = 4,
    .values = {"256", "512", "1024", "2048"}, .cost = {1, 4, 16, 64}, .default_level = 3,
};
static const gk_knob_def voxels = {
    .name = "vct_res", .owner = "vct", .n_values = 3,
    .values = {"32", "64", "128"}, .cost = {1, 8, 64}, .default_level = 2,
};

/* True cost in ms at the current levels, times load, with +-5 % uniform noise from a fixed LCG. */
typedef struct sim {
    unsigned rng;
    double load;
    double noise;
} sim;

static double frand(sim *m)
{
    m->rng = m->rng * 1664525u + 1013904223u;
    return (m->rng >> 8) / 16777216.0;
}

static double true_ms(sim *m, const gk_budget *b)
{
    static const double scale_ms[] = {3, 6.75, 12};       /* fill-rate bound: ~ pixel count */
    static const double shadow_ms[] = {0.5, 1, 2, 4};     /* linear, unlike the prior */
    static const double voxel_ms[] = {0.4, 1.5, 6.4};
    double t = 2 + scale_ms[b->level[0]] + shadow_ms[b->level[1]] + voxel_ms[b->level[2]];
    return t * m->load * (1 + m->noise * (2 * frand(m) - 1));
}

static void setup(gk_budget *b)
{
    gk_budget_init(b);
    gk_budget_add(b, &scale);
    gk_budget_add(b, &shadow);
    gk_budget_add(b, &voxels);
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double p95(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    return v[(int)(0.95 * (n - 1))];
}

/* Runs n frames, storing frame times; counts per-knob direction changes. */
static void run(gk_sched *s, gk_budget *b, sim *m, int n, double *times, int *dir_changes, int *last_dir)
{
    for (int f = 0; f < n; f++) {
        double ms = true_ms(m, b);
        if (times)
            times[f] = ms;
        gk_sched_change ch[GK_MAX_KNOBS * GK_MAX_KNOB_VALUES];
        int k = gk_sched_update(s, b, ms, ch, (int)(sizeof ch / sizeof ch[0]));
        for (int i = 0; i < k; i++) {
            int d = ch[i].to > ch[i].from ? 1 : -1;
            if (last_dir[ch[i].knob] && last_dir[ch[i].knob] != d)
                (*dir_changes)++;
            last_dir[ch[i].knob] = d;
        }
    }
}

static void converges_under_target_without_oscillation(void **state)
{
    (void)state;
    gk_budget b;
    setup(&b);
    gk_sched_params p;
    gk_sched_params_defaults(&p, 16.7);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, NULL);
    sim m = {.rng = 1, .load = 1, .noise = 0.05};
    assert_true(true_ms(&m, &b) > 16.7 * 1.2); /* the richest levels do not fit: work to do */
    double times[1000];
    int changes = 0, last_dir[GK_MAX_KNOBS] = {0};
    run(&s, &b, &m, 1000, times, &changes, last_dir);
    /* Judge the steady state: frames 100..999 (the first frames are the descent). */
    double q95 = p95(times + 100, 900);
    print_message("# sched steady state: p95 %.2f ms vs target 16.7 ms, %d direction changes, levels %d/%d/%d\n",
                  q95, changes, b.level[0], b.level[1], b.level[2]);
    assert_true(q95 <= 16.7);
    /* Measured: 0 direction changes (the step-response fit learns render_scale's true cost on its
       first move). Reversals are held for 120, 240, 480 frames, so hunting would show as 3+. */
    assert_true(changes <= 2);
    /* It must not have given up more than needed: some knob above its minimum. */
    assert_true(b.level[0] + b.level[1] + b.level[2] > 0);
}

static void high_noise_bounded_direction_changes(void **state)
{
    (void)state;
    /* +-20 % noise keeps frames crossing the thresholds: the hold times must bound the hunting. */
    gk_budget b;
    setup(&b);
    gk_sched_params p;
    gk_sched_params_defaults(&p, 16.7);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, NULL);
    sim m = {.rng = 7, .load = 1, .noise = 0.2};
    double times[1000];
    int changes = 0, last_dir[GK_MAX_KNOBS] = {0};
    run(&s, &b, &m, 1000, times, &changes, last_dir);
    double q95 = p95(times + 100, 900);
    print_message("# sched noisy (+-20%%): p95 %.2f ms vs target 16.7 ms, %d direction changes\n", q95, changes);
    /* Measured: 8. 3 knobs x (1 + log2(1000/120)) reversals ~ 12 is the hard bound of the hold rule. */
    assert_true(changes <= 12);
    assert_true(q95 <= 16.7 * 1.1);
}

static void pins_and_ranges_hold_under_overload(void **state)
{
    (void)state;
    gk_budget b;
    setup(&b);
    gk_err e = {0};
    assert_int_equal(gk_budget_pin_list(&b, "render_scale=1", &e), 0);
    assert_int_equal(gk_budget_set_range(&b, "vct_res", "64", "128", &e), 0);
    gk_sched_params p;
    gk_sched_params_defaults(&p, 16.7);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, NULL);
    sim m = {.rng = 3, .load = 4, .noise = 0.05}; /* impossible target: everything movable drops */
    int changes = 0, last_dir[GK_MAX_KNOBS] = {0};
    for (int f = 0; f < 500; f++) {
        run(&s, &b, &m, 1, NULL, &changes, last_dir);
        assert_int_equal(b.level[0], 2);   /* pinned at "1" */
        assert_true(b.level[2] >= 1);      /* range floor "64" */
    }
    assert_int_equal(b.level[1], 0);      /* the free knob went to its minimum */
    assert_int_equal(b.level[2], 1);
    /* at the floor: pinned render_scale at "1" and vct_res at its range's "64" do not count */
    assert_true(gk_sched_at_floor(&s, &b));
    b.level[2] = 2;
    assert_false(gk_sched_at_floor(&s, &b)); /* vct_res could step down again */
    b.level[2] = 1;
    b.level[1] = 1;
    assert_false(gk_sched_at_floor(&s, &b));
}

static void inactive_knobs_never_move(void **state)
{
    (void)state;
    gk_budget b;
    setup(&b);
    bool active[GK_MAX_KNOBS] = {true, true, false}; /* method "none": vct_res does not matter */
    gk_sched_params p;
    gk_sched_params_defaults(&p, 16.7);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, active);
    sim m = {.rng = 5, .load = 3, .noise = 0.05};
    int changes = 0, last_dir[GK_MAX_KNOBS] = {0};
    run(&s, &b, &m, 300, NULL, &changes, last_dir);
    assert_int_equal(b.level[2], 2);
    assert_int_equal(b.level[0], 0);
}

/* A variant switch (the document's behaviour vs an improvement, e.g. vct_variant) is not a
   cost/quality trade: under an impossible target every other knob drops to its floor, and the
   scheduler would otherwise take even a "free" knob (its tiny prior score) before giving up. */
static void fixed_variant_knobs_never_move(void **state)
{
    (void)state;
    static const gk_knob_def variant = {
        .name = "vct_variant", .owner = "vct", .n_values = 2,
        .values = {"default", "thesis"}, .cost = {1, 1}, .default_level = 1, .fixed = true,
    };
    for (int fixed = 0; fixed < 2; fixed++) {
        gk_knob_def v = variant;
        v.fixed = fixed;
        gk_budget b;
        setup(&b);
        gk_budget_add(&b, &v);
        gk_sched_params p;
        gk_sched_params_defaults(&p, 16.7);
        gk_sched s;
        gk_sched_reset(&s, &p, &b, NULL);
        sim m = {.rng = 9, .load = 4, .noise = 0.05};
        int changes = 0, last_dir[GK_MAX_KNOBS] = {0};
        run(&s, &b, &m, 500, NULL, &changes, last_dir);
        assert_int_equal(b.level[0] + b.level[1] + b.level[2], 0);   /* everything else at its floor */
        /* the same knob without the flag is taken (so the test sees the difference) */
        assert_int_equal(b.level[3], fixed ? 1 : 0);
    }
}

static void recovers_when_load_drops(void **state)
{
    (void)state;
    gk_budget b;
    setup(&b);
    gk_sched_params p;
    gk_sched_params_defaults(&p, 16.7);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, NULL);
    sim m = {.rng = 11, .load = 2.5, .noise = 0.05};
    int changes = 0, last_dir[GK_MAX_KNOBS] = {0};
    run(&s, &b, &m, 300, NULL, &changes, last_dir);
    int heavy = b.level[0] + b.level[1] + b.level[2];
    m.load = 0.5; /* at half the load even the richest levels (24.4 ms * 0.5) fit */
    double times[1000];
    run(&s, &b, &m, 1000, times, &changes, last_dir);
    int light = b.level[0] + b.level[1] + b.level[2];
    double q95 = p95(times + 500, 500);
    print_message("# sched recovery: levels %d -> %d (max 7), p95 after %.2f ms\n", heavy, light, q95);
    assert_true(light > heavy);
    assert_int_equal(light, 2 + 3 + 2); /* everything back at its richest */
    assert_true(q95 <= 16.7);
}

/* Far under the target the climb uses the model: several measured knobs per step, after
 * up_after_far frames instead of up_after. From the floor at a tenth of the load (the richest levels
 * take 2.4 ms against 16.7) back to the richest levels: one step per 30 frames would take
 * 7 x 30 = 210 frames (asserted for the one-step configuration, so the comparison is real). Bound
 * for the default: no more than one up_after_far wait per level, 7 x 5 = 35 frames (measured 20:
 * measured knobs climb up to 3 levels per step). */
static int frames_to_richest(const gk_sched_params *p)
{
    gk_budget b;
    setup(&b);
    gk_sched s;
    gk_sched_reset(&s, p, &b, NULL);
    sim m = {.rng = 5, .load = 5, .noise = 0.02};
    int changes = 0, last_dir[GK_MAX_KNOBS] = {0};
    run(&s, &b, &m, 300, NULL, &changes, last_dir); /* to the floor, the knobs' costs measured */
    assert_int_equal(b.level[0] + b.level[1] + b.level[2], 0);
    m.load = 0.1;
    for (int f = 1; f <= 1000; f++) {
        run(&s, &b, &m, 1, NULL, &changes, last_dir);
        if (b.level[0] + b.level[1] + b.level[2] == 2 + 3 + 2)
            return f;
    }
    return 1000;
}

static void climbs_fast_far_under_target(void **state)
{
    (void)state;
    gk_sched_params p;
    gk_sched_params_defaults(&p, 16.7);
    int fast = frames_to_richest(&p), far_wait = p.up_after_far;
    p.max_up_steps = 1;
    p.up_after_far = p.up_after;
    int one_by_one = frames_to_richest(&p);
    print_message("# sched climb from the floor at 1/10 load: %d frames (one step per %d frames: %d)\n", fast,
                  p.up_after, one_by_one);
    assert_true(one_by_one >= 7 * p.up_after);
    assert_true(fast <= 7 * far_wait);
}

static void fit_learns_true_costs(void **state)
{
    (void)state;
    /* After convergence the model's prediction should track the measured mean closely. */
    gk_budget b;
    setup(&b);
    gk_sched_params p;
    gk_sched_params_defaults(&p, 16.7);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, NULL);
    sim m = {.rng = 13, .load = 1, .noise = 0.0};
    int changes = 0, last_dir[GK_MAX_KNOBS] = {0};
    run(&s, &b, &m, 400, NULL, &changes, last_dir);
    double truth = true_ms(&m, &b), pred = gk_sched_predict(&s, &b);
    print_message("# sched model: predicted %.2f ms, true %.2f ms\n", pred, truth);
    assert_true(pred > truth * 0.95 && pred < truth * 1.05);
}

/* Knobs that scale one pass multiplicatively (vct's cones and trace resolution both scale
 * gi.vct_trace): the furnace case of the showcase tour. Trace 275 ms of a 300 ms frame at 6 cones
 * and half-resolution tracing, 400 ms target, with a few cheap knobs beside so equal-share seeding
 * puts each knob near 1/7 of the frame. Predicted from the pass, 6 -> 9 cones adds 137 ms and is
 * never tried; on the additive model alone the same run climbs into frames over the target (checked
 * below, so the test shows the difference the pass makes). */
static const gk_knob_def cones = {
    .name = "vct_cones", .owner = "vct", .n_values = 3, .values = {"4", "6", "9"},
    .cost = {1, 1.5f, 2.25f}, .default_level = 1, .scales_pass = "gi.vct_trace",
};
static const gk_knob_def trace_scale = {
    .name = "vct_trace_scale", .owner = "vct", .n_values = 3, .values = {"0.25", "0.5", "1"},
    .cost = {1, 4, 16}, .default_level = 1, .scales_pass = "gi.vct_trace",
};
static const gk_knob_def cheap[4] = {
    {.name = "a", .owner = "t", .n_values = 3, .values = {"1", "2", "3"}, .cost = {1, 1.1f, 1.2f}},
    {.name = "b", .owner = "t", .n_values = 3, .values = {"1", "2", "3"}, .cost = {1, 1.1f, 1.2f}},
    {.name = "c", .owner = "t", .n_values = 3, .values = {"1", "2", "3"}, .cost = {1, 1.1f, 1.2f}},
    {.name = "d", .owner = "t", .n_values = 3, .values = {"1", "2", "3"}, .cost = {1, 1.1f, 1.2f}},
};

static double trace_ms(const gk_budget *b)
{
    return 275.0 / (1.5 * 4) * cones.cost[b->level[0]] * trace_scale.cost[b->level[1]];
}

static int pass_run(bool observe, int *cones_level, double *worst)
{
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &cones);
    gk_budget_add(&b, &trace_scale);
    for (int i = 0; i < 4; i++)
        gk_budget_add(&b, &cheap[i]);
    gk_sched_params p;
    gk_sched_params_defaults(&p, 400);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, NULL);
    sim m = {.rng = 7, .load = 1, .noise = 0.02};
    *worst = 0;
    double sum = 0;
    for (int f = 0; f < 600; f++) {
        double trace = trace_ms(&b) * (1 + m.noise * (2 * frand(&m) - 1));
        double ms = 25 + trace;
        for (int i = 2; i < 6; i++)
            ms += 0.5 * b.level[i];
        if (f >= p.warmup && ms > *worst)
            *worst = ms;
        sum += ms;
        if (observe)
            for (int k = 0; k < b.n; k++)
                gk_sched_observe_pass(&s, k, b.def[k]->scales_pass ? trace : 0);
        gk_sched_change ch[GK_MAX_KNOBS * GK_MAX_KNOB_VALUES];
        gk_sched_update(&s, &b, ms, ch, (int)(sizeof ch / sizeof ch[0]));
    }
    *cones_level = b.level[0];
    int cheap_levels = 0;
    for (int i = 2; i < 6; i++)
        cheap_levels += b.level[i];
    return cheap_levels;
}

static void pass_scaled_knobs_are_predicted_from_their_pass(void **state)
{
    (void)state;
    int cones_level;
    double worst;
    int cheap_levels = pass_run(true, &cones_level, &worst);
    print_message("# pass-scaled: worst %.1f ms, cones level %d, cheap knobs climbed %d levels\n", worst,
                  cones_level, cheap_levels);
    assert_true(worst <= 400);
    assert_int_equal(cones_level, 1);
    assert_int_equal(cheap_levels, 8); /* the cheap knobs still climb to their richest */
    (void)pass_run(false, &cones_level, &worst);
    print_message("# additive only: worst %.1f ms\n", worst);
    assert_true(worst > 400); /* what the pass's time prevents */
}

/* Calibrated knobs: costs and errors per level as `make calibrate` measures them (one knob changed
 * from the defaults). Knob m's two richest levels measured no more accurate than level 1 (as
 * shadow_map 2048 against 1024 on cornell-spot at the references' size); q's every level is better.
 * True frame = 20 + m_ms + q_ms, true error m_err + q_err. */
static const gk_knob_def knob_m = {.name = "m", .owner = "t", .n_values = 4, .values = {"0", "1", "2", "3"},
                                   .cost = {1, 2, 3, 4}, .default_level = 0};
static const gk_knob_def knob_q = {.name = "q", .owner = "t", .n_values = 3, .values = {"0", "1", "2"},
                                   .cost = {1, 2, 3}, .default_level = 0};
static const double m_ms[] = {10, 12, 20, 60}, m_err[] = {0.30, 0.28, 0.28, 0.281};
static const double q_ms[] = {10, 30, 60}, q_err[] = {0.5, 0.3, 0.2};

static void calibrated_run(bool calibrated, double target, int m0, int q0, int *max_m, int *first_knob,
                           double *worst)
{
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &knob_m);
    gk_budget_add(&b, &knob_q);
    b.level[0] = m0;
    b.level[1] = q0;
    gk_sched_params p;
    gk_sched_params_defaults(&p, target);
    gk_sched s;
    gk_sched_reset(&s, &p, &b, NULL);
    if (calibrated) {
        /* the calibration's frames: the knob's level with the other at the start levels */
        double fm[4], fq[3], em[4], eq[3];
        for (int l = 0; l < 4; l++)
            fm[l] = 20 + m_ms[l] + q_ms[q0], em[l] = m_err[l] + q_err[q0];
        for (int l = 0; l < 3; l++)
            fq[l] = 20 + m_ms[m0] + q_ms[l], eq[l] = q_err[l] + m_err[m0];
        gk_sched_calibrate(&s, 20 + m_ms[m0] + q_ms[q0], m_err[m0] + q_err[q0]);
        gk_sched_calibrate_knob(&s, 0, fm, em, NULL, 4);
        gk_sched_calibrate_knob(&s, 1, fq, eq, NULL, 3);
    }
    sim m = {.rng = 3, .load = 1, .noise = 0.02};
    *max_m = b.level[0];
    *first_knob = -1;
    *worst = 0;
    for (int f = 0; f < 400; f++) {
        double ms = (20 + m_ms[b.level[0]] + q_ms[b.level[1]]) * (1 + m.noise * (2 * frand(&m) - 1));
        if (f > 60 && ms > *worst)
            *worst = ms;
        gk_sched_change ch[GK_MAX_KNOBS * GK_MAX_KNOB_VALUES];
        int n = gk_sched_update(&s, &b, ms, ch, (int)(sizeof ch / sizeof ch[0]));
        if (n > 0 && *first_knob < 0)
            *first_knob = ch[0].knob;
        if (b.level[0] > *max_m)
            *max_m = b.level[0];
    }
}

static void calibrated_levels_no_more_accurate_are_not_climbed(void **state)
{
    (void)state;
    int max_m, first;
    double worst;
    /* Room for everything (1000 ms target): q climbs to its richest, m stops at level 1. */
    calibrated_run(true, 1000, 0, 0, &max_m, &first, &worst);
    print_message("# calibrated, room: m reached level %d\n", max_m);
    assert_int_equal(max_m, 1);
    calibrated_run(false, 1000, 0, 0, &max_m, &first, &worst);
    print_message("# uncalibrated, room: m reached level %d\n", max_m);
    assert_int_equal(max_m, 3); /* the priors alone climb to levels that buy nothing */
    /* Over the target at the start (m 3, q 2: 140 ms for 100 ms): the step that loses no measured
       accuracy goes first (m 3 -> 2), and the judged frames settle under the target. */
    calibrated_run(true, 100, 3, 2, &max_m, &first, &worst);
    print_message("# calibrated, over: first knob moved %d, worst judged frame %.1f ms\n", first, worst);
    assert_int_equal(first, 0);
    assert_true(worst <= 100);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(converges_under_target_without_oscillation),
        cmocka_unit_test(high_noise_bounded_direction_changes),
        cmocka_unit_test(pins_and_ranges_hold_under_overload),
        cmocka_unit_test(inactive_knobs_never_move),
        cmocka_unit_test(fixed_variant_knobs_never_move),
        cmocka_unit_test(recovers_when_load_drops),
        cmocka_unit_test(climbs_fast_far_under_target),
        cmocka_unit_test(fit_learns_true_costs),
        cmocka_unit_test(pass_scaled_knobs_are_predicted_from_their_pass),
        cmocka_unit_test(calibrated_levels_no_more_accurate_are_not_climbed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
