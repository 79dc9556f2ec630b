/* Frame statistics the scheduler and the HUD report: percentiles, the recent-frame ring, the
 * --stats CSV (union of pass names in first-seen order, one column per knob) and the summary. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <signal.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/csv.h"

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

/* With the ground truth: `error` and `truth_spp` after the knob columns, empty before the first
 * measurement, then the values given for the rows that follow. */
static void csv_truth_columns(void **state)
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
    gk_stats_csv *c = gk_stats_csv_open_truth(path, true, &e);
    assert_non_null(c);
    gk_frame_report t1 = {.total_ms = 3.75, .n = 1, .pass = {{"gbuffer", -1, 3.75}}};
    assert_int_equal(gk_stats_csv_row(c, 0, 0.0, "cornell", "vct", &t1, &b, &e), 0);
    gk_stats_csv_truth(c, 0.125, 64);
    assert_int_equal(gk_stats_csv_row(c, 1, 0.5, "cornell", "vct", &t1, &b, &e), 0);
    assert_int_equal(gk_stats_csv_close(c, &b, &e), 0);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[512];
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line, "frame,time_s,scene,method,frame_ms,gbuffer_ms,render_scale,error,truth_spp\n");
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line, "0,0.000000,cornell,vct,3.750,3.750,1,,\n");
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line, "1,0.500000,cornell,vct,3.750,3.750,1,0.125,64\n");
    assert_null(fgets(line, sizeof line, f));
    fclose(f);
    remove(path);
}

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

/* A scratch directory per test: the CSV, its spool and any temporary file live side by side. */
static void scratch_dir(char *dir, size_t len)
{
    snprintf(dir, len, "/tmp/gk-stats-dir-XXXXXX");
    assert_non_null(mkdtemp(dir));
}

static int count_entries(const char *dir)
{
    char cmd[700];
    snprintf(cmd, sizeof cmd, "ls -A '%s' | wc -l", dir);
    FILE *p = popen(cmd, "r");
    int n = -1;
    assert_int_equal(fscanf(p, "%d", &n), 1);
    pclose(p);
    return n;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static char *slurp(const char *path)
{
    static char buf[8192];
    FILE *f = fopen(path, "r");
    if (!f)
        return NULL;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static gk_frame_report two_passes = {.total_ms = 3.75, .n = 2, .pass = {{"gbuffer", -1, 1.5}, {"direct", -1, 2.25}}};

/* Scene names are file names: a comma or a quote in one stays inside its field (RFC 4180). */
static void csv_quotes_fields(void **state)
{
    (void)state;
    char dir[64], path[128];
    scratch_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/s.csv", dir);
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &scale);
    gk_err e = {0};
    gk_stats_csv *c = gk_stats_csv_open(path, &e);
    assert_non_null(c);
    assert_int_equal(gk_stats_csv_row(c, 0, 0.0, "a,b", "none", &two_passes, &b, &e), 0);
    assert_int_equal(gk_stats_csv_row(c, 1, 0.5, "say \"hi\"", "none", &two_passes, &b, &e), 0);
    assert_int_equal(gk_stats_csv_close(c, &b, &e), 0);
    assert_string_equal(slurp(path), "frame,time_s,scene,method,frame_ms,gbuffer_ms,direct_ms,render_scale\n"
                                     "0,0.000000,\"a,b\",none,3.750,1.500,2.250,1\n"
                                     "1,0.500000,\"say \"\"hi\"\"\",none,3.750,1.500,2.250,1\n");
    /* and it reads back as 8 fields a row */
    FILE *f = fopen(path, "r");
    gk_csv_record r = {0};
    for (int row = 0; row < 3; row++) {
        assert_int_equal(gk_csv_read(f, &r), 1);
        assert_int_equal(r.n, 8);
    }
    assert_string_equal(gk_csv_get(&r, 2), "say \"hi\"");
    assert_int_equal(gk_csv_read(f, &r), 0);
    gk_csv_record_free(&r);
    fclose(f);
    remove(path);
    rmdir(dir);
}

/* What SIGKILL leaves: the spool, a CSV of its own with every row written so far (flushed at
   each row, read here while the writer still holds it open), and the old CSV untouched. */
static void spool_is_a_valid_csv_while_running(void **state)
{
    (void)state;
    char dir[64], path[128], spool[160];
    scratch_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/s.csv", dir);
    snprintf(spool, sizeof spool, "%s.part", path);
    write_file(path, "the previous run's CSV\n");
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &scale);
    gk_err e = {0};
    gk_stats_csv *c = gk_stats_csv_open(path, &e);
    assert_non_null(c);
    assert_string_equal(gk_stats_csv_spool_path(c), spool);
    for (int i = 0; i < 5; i++)
        assert_int_equal(gk_stats_csv_row(c, i, i / 60.0, "x,y", "none", &two_passes, &b, &e), 0);
    assert_string_equal(slurp(path), "the previous run's CSV\n"); /* not truncated at start */
    FILE *f = fopen(spool, "r");
    assert_non_null(f);
    gk_csv_record r = {0};
    assert_int_equal(gk_csv_read(f, &r), 1);
    assert_int_equal(r.n, 7);
    assert_string_equal(gk_csv_get(&r, 5), "passes_ms");
    int rows = 0;
    while (gk_csv_read(f, &r) == 1) {
        assert_int_equal(r.n, 7);
        assert_string_equal(gk_csv_get(&r, 2), "x,y");
        assert_string_equal(gk_csv_get(&r, 5), "gbuffer=1.500 direct=2.250");
        assert_string_equal(gk_csv_get(&r, 6), "render_scale=1");
        rows++;
    }
    assert_int_equal(rows, 5);
    gk_csv_record_free(&r);
    fclose(f);
    assert_int_equal(gk_stats_csv_close(c, &b, &e), 0);
    assert_int_equal(count_entries(dir), 1); /* the CSV only: spool and temporary file gone */
    remove(path);
    rmdir(dir);
}

/* A previous run's spool (killed) is never overwritten: the next run spools beside it. */
static void spool_of_a_killed_run_is_kept(void **state)
{
    (void)state;
    char dir[64], path[128], spool[160], spool2[160];
    scratch_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/s.csv", dir);
    snprintf(spool, sizeof spool, "%s.part", path);
    snprintf(spool2, sizeof spool2, "%s.part-2", path);
    write_file(spool, "frame,time_s\n0,0\n");
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &scale);
    gk_err e = {0};
    gk_stats_csv *c = gk_stats_csv_open(path, &e);
    assert_non_null(c);
    assert_string_equal(gk_stats_csv_spool_path(c), spool2);
    assert_int_equal(gk_stats_csv_close(c, &b, &e), 0);
    assert_string_equal(slurp(spool), "frame,time_s\n0,0\n");
    remove(spool);
    remove(path);
    rmdir(dir);
}

/* The final write fails (a file-size limit: what a full disk does to write(2), EFBIG instead of
   ENOSPC): the old CSV stays as it was, the spool stays with every row, the message names it,
   and no temporary file is left behind. */
static void failed_final_write_keeps_the_spool(void **state)
{
    (void)state;
    char dir[64], path[128], spool[160];
    scratch_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/s.csv", dir);
    snprintf(spool, sizeof spool, "%s.part", path);
    write_file(path, "old\n");
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &scale);
    gk_err e = {0};
    gk_stats_csv *c = gk_stats_csv_open(path, &e);
    assert_non_null(c);
    for (int i = 0; i < 200; i++) /* about 12 kB of CSV, more than a stdio buffer */
        assert_int_equal(gk_stats_csv_row(c, i, i / 60.0, "cornell", "none", &two_passes, &b, &e), 0);
    struct rlimit saved, tiny;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &saved), 0);
    tiny = saved;
    tiny.rlim_cur = 1000;
    void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &tiny), 0);
    int rc = gk_stats_csv_close(c, &b, &e);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &saved), 0);
    signal(SIGXFSZ, old_handler);
    assert_int_equal(rc, -1);
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_non_null(strstr(e.msg, spool));
    assert_non_null(strstr(e.msg, "File too large"));
    assert_string_equal(slurp(path), "old\n");
    assert_int_equal(count_entries(dir), 2); /* the old CSV and the spool */
    FILE *f = fopen(spool, "r");
    gk_csv_record r = {0};
    int records = 0;
    while (gk_csv_read(f, &r) == 1)
        records++;
    assert_int_equal(records, 201);
    gk_csv_record_free(&r);
    fclose(f);
    remove(spool);
    remove(path);
    rmdir(dir);
}

/* A --stats path longer than any fixed buffer lands exactly where it was asked to (it used to be
   cut at 511 bytes and written elsewhere). */
static void long_stats_path_is_not_cut(void **state)
{
    (void)state;
    char dir[64];
    scratch_dir(dir, sizeof dir);
    char path[1200], sub[1000];
    char seg[201];
    memset(seg, 'd', 200);
    seg[200] = '\0';
    snprintf(sub, sizeof sub, "%s/%s", dir, seg);
    assert_int_equal(mkdir(sub, 0777), 0);
    snprintf(sub + strlen(sub), sizeof sub - strlen(sub), "/%s", seg);
    assert_int_equal(mkdir(sub, 0777), 0);
    snprintf(path, sizeof path, "%s/%s.csv", sub, seg);
    assert_true(strlen(path) > 600);
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &scale);
    gk_err e = {0};
    gk_stats_csv *c = gk_stats_csv_open(path, &e);
    assert_non_null(c);
    assert_int_equal(gk_stats_csv_row(c, 0, 0.0, "cornell", "none", &two_passes, &b, &e), 0);
    assert_int_equal(gk_stats_csv_close(c, &b, &e), 0);
    assert_int_equal(access(path, F_OK), 0);
    char cmd[1300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
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
        cmocka_unit_test(csv_truth_columns),
        cmocka_unit_test(csv_open_fails_on_bad_path),
        cmocka_unit_test(csv_quotes_fields),
        cmocka_unit_test(spool_is_a_valid_csv_while_running),
        cmocka_unit_test(spool_of_a_killed_run_is_kept),
        cmocka_unit_test(failed_final_write_keeps_the_spool),
        cmocka_unit_test(long_stats_path_is_not_cut),
        cmocka_unit_test(summary_one_line_per_scene),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
