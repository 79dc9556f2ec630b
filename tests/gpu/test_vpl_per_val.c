/* The gather's visibility once per VAL (gather.frag VIS_PER_VAL, vpl_gather.c vpl_per_val_define):
 * Ṽ_C(i)(x) depends on the VPL's VAL alone, so evaluating it once per VAL per receiver and looking it
 * up per VPL must give the very image the per-VPL call gives (the debug switch vis_per_vpl forces
 * that). On the harness's box with its two blocks (occluders, so the visibility is not 1), for CSSM
 * and VSM, interleaved and multires: the HDR image bit-identical both ways, and the variant taken
 * exactly where the VALs are fewer than the VPLs a receiver takes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "test_vpl_harness.h"

VPL_H_BOX_GROUP

static void per_vpl(gk_vpl_debug *d) { d->fade_frames = 0, d->vis_per_vpl = true; }
static void per_val(gk_vpl_debug *d) { d->fade_frames = 0; }

/* One frame under `budget` with the debug edit; the HDR image into out, whether VIS_PER_VAL ran. */
static bool render(const char *budget, void (*edit)(gk_vpl_debug *), float *out)
{
    h_set_debug(&H, edit);
    assert_int_equal(h_budget(&H, budget), 0);
    assert_int_equal(h_frame(&H, 0), 0);
    memcpy(out, H.img, sizeof(float) * 4 * W * HH);
    return gk_vpl_get_stats(H.self)->vis_per_val;
}

static void same_image_both_ways(void **state)
{
    (void)state;
    static const struct {
        const char *budget;
        int per_receiver; /* VPLs a receiver takes: n / B² interleaved, n multires */
    } cases[] = {
        {"vpl_n=256,vpl_m=8,vpl_block=4,vpl_vis=cssm,vpl_gather=interleaved", 16},
        {"vpl_n=256,vpl_m=8,vpl_block=4,vpl_vis=vsm,vpl_gather=interleaved", 16},
        {"vpl_n=256,vpl_m=4,vpl_block=2,vpl_vis=cssm,vpl_gather=interleaved", 64},
        {"vpl_n=256,vpl_m=8,vpl_vis=cssm,vpl_gather=multires", 256},
        {"vpl_n=256,vpl_m=32,vpl_block=4,vpl_vis=cssm,vpl_gather=interleaved", 16},
    };
    static float a[4 * W * HH], b[4 * W * HH], c[4 * W * HH];
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        bool forced = render(cases[k].budget, per_vpl, a);
        bool again = render(cases[k].budget, per_vpl, c);
        bool chosen = render(cases[k].budget, per_val, b);
        int m = gk_vpl_get_stats(H.self)->m;
        int differ = 0;
        for (int i = 0; i < 4 * W * HH; i++)
            differ += memcmp(&a[i], &b[i], sizeof(float)) != 0;
        print_message("# %s: M = %d, %d VPLs a receiver, visibility per %s; %d of %d floats differ, mean %.6g\n",
                      cases[k].budget, m, cases[k].per_receiver, chosen ? "VAL" : "VPL", differ, 4 * W * HH,
                      h_mean(b, W * HH));
        assert_false(forced || again);
        /* the frames are reproducible (else the comparison below would say nothing) */
        assert_memory_equal(a, c, sizeof a);
        assert_true(chosen == (m < cases[k].per_receiver));
        assert_true(h_mean(b, W * HH) > 0.0);
        assert_int_equal(differ, 0);
    }
    h_set_debug(&H, NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_image_both_ways),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
