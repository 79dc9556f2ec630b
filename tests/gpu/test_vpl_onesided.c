/* L5 of research A.4 (photon-mapping-000-004.md): the VPL kernel is one-sided. The seed's gather
 * takes |cos| at the VPL (erratum), so a VPL on the front face of a thin wall lights receivers
 * behind the wall; the fixed kernel max(-n_i.w, 0) gives them nothing. ispm's indirect part is
 * vpl's gather (shaders_gles/vpl/gather.frag), so this holds for both methods.
 * Scene: the harness's unit Cornell corner with its two cuboids (tests/gpu/test_vpl_harness.h). The
 * spot is narrowed to a 5-degree cone aimed at the tall cuboid's top face (y = 0.6, normal up, a
 * 0.3 m square), so every VPL sits on that face. Visibility is switched off in the method
 * (vis_override = none): nothing but the kernel can keep the light from the receivers below the
 * face's plane. The camera at y = 0.5 looks horizontally, so the image's lower half shows only
 * surfaces below y = 0.5 (floor, walls, the cuboids' sides), all behind the VPLs' plane, most of
 * them facing it (the floor faces up at the face's underside): a two-sided kernel would light them.
 * The ceiling and the upper walls are in front of the plane and must be lit (the control). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "test_vpl_harness.h"

VPL_H_BOX_GROUP


/* mean luminance of rows [y0, y1) (row 0 is the image's bottom: glReadPixels order) */
static double rows_mean(const float *img, int y0, int y1)
{
    double s = 0;
    for (int y = y0; y < y1; y++)
        for (int x = 0; x < W; x++)
            s += h_lum(&img[(y * W + x) * 4]);
    return s / ((double)(y1 - y0) * W);
}

static void vpls_do_not_light_what_is_behind_them(void **state)
{
    (void)state;
    H.box.lights[0].inner_cone = 4.0f * 3.14159265f / 180.0f;
    H.box.lights[0].outer_cone = 5.0f * 3.14159265f / 180.0f;
    assert_true(H.scene.lights == H.box.lights); /* the harness's scene reads the box's lights */
    h_aim(&H, v3(0.45f, 0.6f, 0.5f));            /* the tall cuboid's top face, centre */
    gk_vpl_debug d;
    gk_vpl_default_debug(&d);
    d.vis_override = GK_VPL_VIS_NONE;
    d.fade_frames = 0;
    gk_vpl_set_debug(H.self, &d);
    /* full resolution, no interleave, the smallest blur: nothing spreads across the image */
    assert_int_equal(h_budget(&H, "vpl_n=256,vpl_m=8,vpl_block=1,vpl_res=1,vpl_blur=2"), 0);
    assert_int_equal(h_frame(&H, 0), 0);
    const gk_vpl_stats *st = gk_vpl_get_stats(H.self);
    int valid = 0;
    double worst_y = 0, worst_n = 0;
    for (int i = 0; i < st->n; i++) {
        const gk_vpl *v = &st->vpl[i];
        if (!(v->flux.x + v->flux.y + v->flux.z > 0))
            continue;
        valid++;
        worst_y = fmax(worst_y, fabs(v->pos.y - 0.6));
        worst_n = fmax(worst_n, 1.0 - v->nrm.y);
    }
    /* Rows: the lower 28 (surfaces at y < 0.5, 4 rows clear of the horizon for the blur) and the
       upper 16 (the ceiling and the back wall's top, y > 0.75: in front of the plane). */
    double behind = rows_mean(H.img, 0, 28), front = rows_mean(H.img, HH - 16, HH);
    print_message("# L5: %d VPLs with flux, largest |y - 0.6| %.2e m, largest 1 - n.y %.2e; mean indirect "
                  "radiance behind the VPLs' plane %.3e, in front %.3e\n",
                  valid, worst_y, worst_n, behind, front);
    /* every VPL on the face, facing up (else the set-up, not the kernel, is what is tested) */
    assert_true(valid > 0);
    assert_true(worst_y < 0.01 && worst_n < 1e-3);
    /* the control: the light does reach what is in front of the plane (measured 2.14e-3) */
    assert_true(front > 2e-4);
    /* Behind the plane: exactly nothing with the one-sided kernel (measured 0). With the seed's
       |cos| at the VPL (gather.frag edited to abs(dot(ni, w)) to check that this test can fail):
       1.23e-3, 0.58 of the front's. Bound: 1e-4 of the front's. */
    assert_true(behind <= 1e-4 * front);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(vpls_do_not_light_what_is_behind_them),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
