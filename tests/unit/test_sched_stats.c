/* Frame statistics the scheduler and the HUD report: percentiles, the recent-frame ring, the
 * --stats CSV (union of pass names in first-seen order, one column per knob) and the summary. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "kiosk/stats.h"

static void percentiles_nearest_rank(void **state)
{
    (void)state;
    double v[20];
    for (int i = 0; i < 20; i++)
        v[i] = 20 - i; /* 20..1, unsorted */
    assert_true(gk_percentile(v, 20, 0.5) == 10);
    assert_true(gk_percentile(v, 20, 0.95) == 19);
    assert_true(gk_percentile(v, 20, 1.0) == 20);
    assert_true(gk_percentile(v, 0, 0.5) == 0);
    gk_recent r;
    gk_recent_clear(&r);
    for (int i = 0; i < GK_RECENT_FRAMES + 10; i++)
        gk_recent_push(&r, (float)i);
    assert_int_equal(r.count, GK_RECENT_FRAMES);
    assert_true(gk_recent_at(&r, 0) == 10.0f); /* the 10 oldest fell out */
    assert_true(gk_recent_at(&r, GK_RECENT_FRAMES - 1) == (float)(GK_RECENT_FRAMES + 9));
    assert_true(gk_recent_percentile(&r, 1.0f) == (float)(GK_RECENT_FRAMES + 9));
}

static const gk_knob_def scale = {
    .name = "render_scale", .owner = "render", .n_values = 3,
    .values = {"0.5", "0.75", "1"}, .cost = {1, 2.25f, 4}, .default_level = 2,
};

static void csv_has_pass_union_and_knob_columns(void **state)
{
    (void)state;
    char path[] = "/tmp/gk-stats-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &scale);
    gk_err e = {0};
    gk_stats_csv *c = gk_stats_csv_open(path, &e);
    assert_non_null(c);
    /* Frame 1 nests vct_trace under gi: its column is "gi.vct_trace_ms", and frame_ms is the total
       of the top-level passes (1 + 7.5), not a sum over every column (which would add 7 twice). */
    gk_frame_report t1 = {.total_ms = 3.75, .n = 2, .pass = {{"gbuffer", -1, 1.5}, {"direct", -1, 2.25}}};
    gk_frame_report t2 = {.total_ms = 8.5, .n = 3, .pass = {{"gbuffer", -1, 1.0}, {"gi", -1, 7.5}, {"vct_trace", 1, 7.0}}};
    assert_int_equal(gk_stats_csv_row(c, 0, 0.0, "cornell", "none", &t1, &b, &e), 0);
    b.level[0] = 0;
    assert_int_equal(gk_stats_csv_row(c, 1, 1 / 60.0, "cornell", "vct", &t2, &b, &e), 0);
    assert_int_equal(gk_stats_csv_close(c, &b, &e), 0);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[512];
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line,
                        "frame,time_s,scene,method,frame_ms,gbuffer_ms,direct_ms,gi_ms,gi.vct_trace_ms,render_scale\n");
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line, "0,0.000000,cornell,none,3.750,1.500,2.250,,,1\n");
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line, "1,0.016667,cornell,vct,8.500,1.000,,7.500,7.000,0.5\n");
    assert_null(fgets(line, sizeof line, f));
    fclose(f);
    char spool[600];
    snprintf(spool, sizeof spool, "%s.part", path);
    assert_int_not_equal(access(spool, F_OK), 0); /* the spool is gone */
    remove(path);
}

static void csv_open_fails_on_bad_path(void **state)
{
    (void)state;
    gk_err e = {0};
    assert_null(gk_stats_csv_open("/nonexistent-dir/s.csv", &e));
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_non_null(strstr(e.msg, "/nonexistent-dir/s.csv"));
}

static void summary_one_line_per_scene(void **state)
{
    (void)state;
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &scale);
    gk_summary s;
    gk_summary_init(&s);
    gk_summary_add(&s, "cornell", "vct", 5000, false, &b); /* a warm-up frame: not in the percentiles */
    for (int i = 1; i <= 100; i++)
        gk_summary_add(&s, "cornell", "vct", i, true, &b);
    gk_summary_add(&s, "box", "none", 3, true, &b);
    char buf[1024] = {0};
    FILE *f = fmemopen(buf, sizeof buf, "w");
    gk_summary_print(&s, f);
    fclose(f);
    assert_string_equal(buf,
                        "scene cornell: 101 frames (1 warm-up, max 5000.00 ms), judged: median 50.00 ms, p95 95.00 ms, "
                        "p99 99.00 ms, method vct, budgets render_scale=1\n"
                        "scene box: 1 frames (0 warm-up, max 0.00 ms), judged: median 3.00 ms, p95 3.00 ms, p99 3.00 ms, "
                        "method none, budgets render_scale=1\n");
    gk_summary_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(percentiles_nearest_rank),
        cmocka_unit_test(csv_has_pass_union_and_knob_columns),
        cmocka_unit_test(csv_open_fails_on_bad_path),
        cmocka_unit_test(summary_one_line_per_scene),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
