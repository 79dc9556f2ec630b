/* The renderer's one clock in GPU mode (app/gl/gl_timing.c) against a fake of
 * EXT_disjoint_timer_query: GL allows one TIME_ELAPSED query at a time, so nested passes are timed
 * as segments (a child closes its parent's query, the parent resumes in a new one). The fake
 * fails the test if two queries are ever open together, and gives each segment a known duration
 * (the n-th query begun lasts n ms), so every inclusive time and the frame total are checked
 * exactly, GK_TIMER_LAG frames late as the timer reads them. Also: the frame report's paths, a
 * pass begun twice accumulating, and a disjoint frame being dropped. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdbool.h>
#include <string.h>

#include "gl/gl_timing.h"

#define MAX_IDS 4096

static struct {
    GLuint next_id;
    GLuint open;            /* the query now open, 0 = none */
    int begun;              /* queries begun so far */
    GLuint64 ns[MAX_IDS];   /* duration given to each id when it was begun */
    bool disjoint_next;
} fake;

static void f_gen(GLsizei n, GLuint *ids)
{
    for (GLsizei i = 0; i < n; i++)
        ids[i] = ++fake.next_id;
}
static void f_del(GLsizei n, const GLuint *ids) { (void)n, (void)ids; }
static void f_begin(GLenum target, GLuint id)
{
    assert_int_equal(target, GL_TIME_ELAPSED_EXT);
    assert_int_equal(fake.open, 0); /* never two open queries: GL would raise INVALID_OPERATION */
    assert_true(id > 0 && id < MAX_IDS);
    fake.open = id;
    fake.ns[id] = (GLuint64)(++fake.begun) * 1000000u;
}
static void f_end(GLenum target)
{
    assert_int_equal(target, GL_TIME_ELAPSED_EXT);
    assert_int_not_equal(fake.open, 0);
    fake.open = 0;
}
static void f_get_u(GLuint id, GLenum pname, GLuint *v)
{
    (void)id;
    assert_int_equal(pname, GL_QUERY_RESULT_AVAILABLE_EXT);
    *v = 1;
}
static void f_get_u64(GLuint id, GLenum pname, GLuint64 *v)
{
    assert_int_equal(pname, GL_QUERY_RESULT_EXT);
    *v = fake.ns[id];
}
static bool f_disjoint(void)
{
    bool d = fake.disjoint_next;
    fake.disjoint_next = false;
    return d;
}

static const gk_timer_queries fake_queries = {f_gen, f_del, f_begin, f_end, f_get_u, f_get_u64, f_disjoint};

static int setup(void **state)
{
    (void)state;
    memset(&fake, 0, sizeof fake);
    return 0;
}

/* The renderer's frame shape: 7 query segments, durations 1..7 ms in the order begun:
 * shadow 1 | gi 2 [vct_voxelize 3] gi 4 [vct_trace 5] gi 6 | compose 7. */
static void frame_shape(gk_timer *t, gk_frame_report *out)
{
    gk_timer_frame_begin(t);
    gk_timer_pass_begin(t, "shadow");
    gk_timer_pass_end(t);
    gk_timer_pass_begin(t, "gi");
    gk_timer_pass_begin(t, "vct_voxelize");
    gk_timer_pass_end(t);
    gk_timer_pass_begin(t, "vct_trace");
    gk_timer_pass_end(t);
    gk_timer_pass_end(t);
    gk_timer_pass_begin(t, "compose");
    gk_timer_pass_end(t);
    gk_timer_frame_end(t, out);
}

static void nested_segments_sum_exactly(void **state)
{
    (void)state;
    gk_timer *t = gk_timer_create_with_queries(&fake_queries);
    assert_true(gk_timer_uses_gpu(t));
    gk_frame_report r;
    for (int f = 0; f < GK_TIMER_LAG; f++) {
        frame_shape(t, &r);
        assert_int_equal(r.n, 0); /* results arrive GK_TIMER_LAG frames late */
    }
    frame_shape(t, &r); /* now frame 0's results: segments 1..7 ms */
    assert_int_equal(r.n, 5);
    assert_string_equal(r.pass[0].name, "shadow");
    assert_int_equal(r.pass[0].parent, -1);
    assert_string_equal(r.pass[1].name, "gi");
    assert_string_equal(r.pass[2].name, "vct_voxelize");
    assert_int_equal(r.pass[2].parent, 1);
    assert_int_equal(r.pass[3].parent, 1);
    assert_true(r.pass[0].ms == 1.0);
    assert_true(r.pass[2].ms == 3.0);
    assert_true(r.pass[3].ms == 5.0);
    assert_true(r.pass[1].ms == 2.0 + 4.0 + 6.0 + 3.0 + 5.0); /* own segments + children */
    assert_true(r.pass[4].ms == 7.0);
    assert_true(r.total_ms == 1.0 + 20.0 + 7.0); /* top level only: children are not counted twice */
    assert_true(gk_frame_report_top_sum(&r) == r.total_ms);
    assert_true(gk_frame_report_ms(&r, "gi.vct_trace") == 5.0);
    assert_true(gk_frame_report_ms(&r, "vct_trace") == 0.0); /* not a top-level pass */
    char path[GK_PASS_PATH_LEN];
    gk_frame_report_path(&r, 2, path, sizeof path);
    assert_string_equal(path, "gi.vct_voxelize");
    assert_int_equal(fake.open, 0);
    gk_timer_destroy(t);
}

/* A pass begun twice under one parent (one per light) is one entry with both segments. */
static void repeated_pass_accumulates(void **state)
{
    (void)state;
    gk_timer *t = gk_timer_create_with_queries(&fake_queries);
    gk_frame_report r = {0};
    for (int f = 0; f <= GK_TIMER_LAG; f++) {
        gk_timer_frame_begin(t);
        gk_timer_pass_begin(t, "direct");
        gk_timer_pass_end(t);
        gk_timer_pass_begin(t, "direct");
        gk_timer_pass_end(t);
        gk_timer_frame_end(t, &r);
    }
    assert_int_equal(r.n, 1);
    assert_true(r.pass[0].ms == 1.0 + 2.0);
    assert_true(r.total_ms == 3.0);
    gk_timer_destroy(t);
}

/* A disjoint event (clock change) drops that frame's results: the previous report stays. */
static void disjoint_frame_dropped(void **state)
{
    (void)state;
    gk_timer *t = gk_timer_create_with_queries(&fake_queries);
    gk_frame_report r;
    for (int f = 0; f <= GK_TIMER_LAG; f++)
        frame_shape(t, &r);
    double first = r.total_ms;
    assert_true(first == 28.0);
    fake.disjoint_next = true;
    frame_shape(t, &r);
    assert_true(r.total_ms == first); /* frame 1's results were dropped */
    frame_shape(t, &r);
    /* frame 2's segments are queries 15..21: shadow 15 + gi (16 + 18 + 20 + 17 + 19) + compose 21 */
    assert_true(r.total_ms == 15.0 + 90.0 + 21.0);
    gk_timer_destroy(t);
}

/* Unbalanced passes (a pass left open by an error path) are closed at frame end, and the next
 * frame starts clean. */
static void unbalanced_passes_closed(void **state)
{
    (void)state;
    gk_timer *t = gk_timer_create_with_queries(&fake_queries);
    gk_frame_report r;
    for (int f = 0; f <= GK_TIMER_LAG; f++) {
        gk_timer_frame_begin(t);
        gk_timer_pass_begin(t, "gi");
        gk_timer_pass_begin(t, "vct_trace");
        gk_timer_frame_end(t, &r);
        assert_int_equal(fake.open, 0);
    }
    /* closing vct_trace resumes gi in a third segment before gi closes: gi 1 [vct_trace 2] gi 3 */
    assert_int_equal(r.n, 2);
    assert_true(r.pass[1].ms == 2.0);
    assert_true(r.pass[0].ms == 1.0 + 2.0 + 3.0);
    assert_true(r.total_ms == 6.0);
    gk_timer_destroy(t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(nested_segments_sum_exactly, setup),
        cmocka_unit_test_setup(repeated_pass_accumulates, setup),
        cmocka_unit_test_setup(disjoint_frame_dropped, setup),
        cmocka_unit_test_setup(unbalanced_passes_closed, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
