/* The roofline micro-benchmark (app/bench/roofline.c) on llvmpipe: every kind of fetch runs, the
 * shader's own count of the fetches it did equals invocations x fetches x timed dispatches (so a
 * wrong dispatch size, loop bound or counter reset shows; the raster kind's counting run counts
 * each fragment it shaded: pixels x triangles, once), the rate is that count over the time,
 * and bad options are refused. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "bench/roofline.h"
#include "common/gl_fixture.h"

static gkt_gl G;
static gk_program_cache *P;

static int setup(void **state)
{
    (void)state;
    if (gkt_gl_open(&G) != 0)
        return -1;
    P = gkt_programs(G.egl.gles_version);
    return P ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    gk_program_cache_destroy(P);
    gkt_gl_close(&G);
    return 0;
}

static void every_kind_does_the_fetches_it_is_asked(void **state)
{
    (void)state;
    /* deliberately not the defaults (64³ x 64 x 5) so a count fixed to them would show */
    gk_roofline_opts o = {.invocations = 64 * 37, .fetches = 13, .reps = 3};
    gk_roofline_result r[GK_ROOFLINE_MAX_CASES];
    gk_err e = {0};
    int n = gk_roofline_measure(P, &o, r, GK_ROOFLINE_MAX_CASES, &e);
    if (n < 0)
        fail_msg("%s", e.msg);
    assert_int_equal(n, 14);
    int tex3d = 0, raster = 0;
    for (int i = 0; i < n; i++) {
        bool fill = strncmp(r[i].name, "raster_", 7) == 0;
        raster += fill;
        /* the fill: a 64 x 37 target, 13 triangles each covering it, counted in one run */
        assert_int_equal(r[i].counted, fill ? 64ull * 37 * 13 : 64ull * 37 * 13 * 3);
        assert_true(r[i].expected == (double)r[i].counted);
        assert_true(r[i].fetches == 64.0 * 37 * 13);
        assert_true(r[i].median_ms > 0.0);
        assert_float_equal(r[i].fetches_per_s, r[i].fetches / (r[i].median_ms * 1e-3), 1e-6 * r[i].fetches_per_s);
        tex3d += strncmp(r[i].name, "tex3d_", 6) == 0;
    }
    assert_int_equal(tex3d, 2);   /* rgba8 and rgba16f: the voxel volumes' formats */
    assert_int_equal(raster, 1);
}

static void a_partial_workgroup_is_refused(void **state)
{
    (void)state;
    gk_roofline_opts o = {.invocations = 100, .fetches = 4, .reps = 1};
    gk_roofline_result r[GK_ROOFLINE_MAX_CASES];
    gk_err e = {0};
    assert_int_equal(gk_roofline_measure(P, &o, r, GK_ROOFLINE_MAX_CASES, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "multiple of 64"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_kind_does_the_fetches_it_is_asked),
        cmocka_unit_test(a_partial_workgroup_is_refused),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
