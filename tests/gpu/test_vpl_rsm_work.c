/* The RSM pass's work model (app/gi/vpl/vpl_work.c, #21: `gi.vpl_rsm`) against hand counts, on the
 * harness's Cornell corner without its cuboids (tests/gpu/test_vpl_harness.h): the spot stands
 * inside the box aiming at its back corner, so every texel of its one RSM face sees exactly one wall
 * (the walls share their corners exactly: no texel is covered twice or not at all) and rsm.frag,
 * counting before its depth test, shades VPL_RSM_RES² fragments; the generation then reads 3 RSM
 * texels (position, normal, flux) for each of the vpl_n VPLs. Neither depends on the other knobs,
 * and nothing is reported by a frame that is not a counting frame. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "gi/vpl/vpl_internal.h"
#include "test_vpl_harness.h"
#include "test_pass_work.h"

static vpl_h H;
enum { W = 64, HH = 64 };

static int setup(void **state)
{
    (void)state;
    return h_init(&H, false, W, HH);
}

static int teardown(void **state)
{
    (void)state;
    h_free(&H);
    return 0;
}

static void rsm_fragments_and_generation_reads_by_hand(void **state)
{
    (void)state;
    static const char *const budgets[] = {"vpl_n=256,vpl_m=4,vpl_vis=vsm", "vpl_n=1024,vpl_m=8,vpl_vis=cssm"};
    static const double vpls[] = {256, 1024};
    for (int b = 0; b < 2; b++) {
        assert_int_equal(h_budget(&H, budgets[b]), 0);
        assert_int_equal(h_frame(&H, 0), 0);
        assert_true(tpw_fetches(H.m, H.self, "gi.vpl_rsm", "raster_r16f_depth_fill") < 0.0); /* not counting */
        H.count_work = true;
        assert_int_equal(h_frame(&H, 0), 0);
        H.count_work = false;
        double fragments = tpw_fetches(H.m, H.self, "gi.vpl_rsm", "raster_r16f_depth_fill");
        double reads = tpw_fetches(H.m, H.self, "gi.vpl_rsm", "tex2d_rgba32f_nearest");
        print_message("# %s: RSM %.0f fragments, generation %.0f texels\n", budgets[b], fragments, reads);
        assert_true(fragments == (double)VPL_RSM_RES * VPL_RSM_RES);
        assert_true(reads == 3.0 * vpls[b]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rsm_fragments_and_generation_reads_by_hand),
    };
    return cmocka_run_group_tests_name("vpl_rsm_work", tests, setup, teardown);
}
