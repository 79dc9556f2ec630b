/* Temporal behaviour of the vpl method on T5 (Cornell corner with cuboids, 64×64, kiosk defaults
 * N = 256, M = 8, block 4, half-resolution indirect, CSSM):
 *  - F8 (dong-001.md §10): flicker under a light turning 0.1° per frame, fixed Halton VPLs
 *    against a random VPL pattern per frame (the oracle that shows what the fixed pattern buys);
 *  - cluster popping when M changes (§8.2 item 3): the mean indirect radiance of the frame where M
 *    steps 8 -> 16 must not jump, thanks to nested seeds and the crossfade. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "test_vpl_harness.h"

VPL_H_BOX_GROUP
#define PIX (W * HH)


/* Mean over frames of mean_p |L_t − L_{t−1}|, relative to the mean radiance. */
static double flicker(bool random_pattern, int frames)
{
    gk_vpl_debug d;
    gk_vpl_default_debug(&d);
    d.random_pattern = random_pattern;
    gk_vpl_set_debug(H.self, &d);
    assert_int_equal(h_budget(&H, "vpl_n=256,vpl_m=8,vpl_vis=cssm"), 0);
    float *prev = malloc(sizeof(float) * PIX * 4);
    double sum = 0, mean = 0;
    for (int f = 0; f <= frames; f++) {
        /* Turn the spot about the vertical axis through its position, 0.1° per frame. */
        float a = (float)f * 0.1f * 3.14159265f / 180.0f;
        vec3 dir0 = v3_sub(v3(0, 0, 0), v3(0.5f, 0.95f, 0.9f));
        vec3 dir = v3(dir0.x * cosf(a) - dir0.z * sinf(a), dir0.y, dir0.x * sinf(a) + dir0.z * cosf(a));
        h_aim(&H, v3_add(v3(0.5f, 0.95f, 0.9f), dir));
        assert_int_equal(h_frame(&H, f / 30.0), 0);
        if (f > 0) {
            double diff = 0;
            for (int i = 0; i < PIX; i++)
                diff += fabs(h_lum(&H.img[i * 4]) - h_lum(&prev[i * 4]));
            sum += diff / PIX;
        }
        mean += h_mean(H.img, PIX);
        memcpy(prev, H.img, sizeof(float) * PIX * 4);
    }
    free(prev);
    h_aim(&H, v3(0, 0, 0));
    mean /= frames + 1;
    return sum / frames / mean;
}

static void test_f8_flicker(void **state)
{
    (void)state;
    double fixed = flicker(false, 6), random = flicker(true, 6);
    print_message("# F8: mean |dL| per frame / mean L: fixed Halton %.4f, random pattern per frame %.4f\n", fixed,
                  random);
    /* Measured: fixed 0.0048, random 0.135 (28x). The fixed pattern's 0.5% per frame includes the
       light's true change (not subtracted: no per-frame reference here). Bounds: fixed below 1%
       (2x measured) and random at least 5x worse (the pattern is what the test is sensitive to). */
    assert_true(fixed < 0.01);
    assert_true(random > 5.0 * fixed);
}

/* Mean indirect of each frame while M goes 8, 8, 8, 16, 16, 16, 16, 16. */
static void m_step(int fade_frames, double *jump, double *settled_change)
{
    gk_vpl_debug d;
    gk_vpl_default_debug(&d);
    d.fade_frames = fade_frames;
    gk_vpl_set_debug(H.self, &d);
    double means[8];
    float *before = malloc(sizeof(float) * PIX * 4);
    for (int f = 0; f < 8; f++) {
        assert_int_equal(h_budget(&H, f < 3 ? "vpl_n=256,vpl_m=8,vpl_vis=cssm" : "vpl_n=256,vpl_m=16,vpl_vis=cssm"), 0);
        assert_int_equal(h_frame(&H, 0), 0);
        means[f] = h_mean(H.img, PIX);
        if (f == 2)
            memcpy(before, H.img, sizeof(float) * PIX * 4);
        if (f == 3) {
            double diff = 0;
            for (int i = 0; i < PIX; i++)
                diff += fabs(h_lum(&H.img[i * 4]) - h_lum(&before[i * 4]));
            *jump = diff / PIX / means[2];
        }
    }
    *settled_change = fabs(means[7] - means[2]) / means[2];
    free(before);
}

static void test_m_change_no_pop(void **state)
{
    (void)state;
    double jump_fade, settled, jump_pop, settled_pop;
    m_step(4, &jump_fade, &settled);
    m_step(0, &jump_pop, &settled_pop);
    print_message("# M 8->16: per-pixel mean |dL| on the switch frame / mean L: crossfade %.4f, none %.4f; "
                  "mean change once settled %.4f\n", jump_fade, jump_pop, settled);
    /* Measured: crossfade 0.0018, none 0.0089 (nested seeds alone already keep the step under 1%),
       settled change 0.0048. The bound is the brief's: one M step moves the frame by < 5%; the
       crossfade must also cut the switch-frame change. */
    assert_true(jump_fade < 0.05);
    assert_true(jump_fade < jump_pop);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_f8_flicker),
        cmocka_unit_test(test_m_change_no_pop),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
