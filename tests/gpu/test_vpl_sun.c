/* vpl from a directional light (issue 11: the sun of 000 §3.2 / 001 ch. 6 had no RSM and added no
 * VPL, so atrium got no bounce): the orthographic RSM over the view's region. On the harness's unit
 * Cornell corner (tests/gpu/test_vpl_harness.h) with its light turned into a sun shining straight
 * down, what the sun reaches first is the ceiling's top, 1 m² of grey (rho 0.75): the VPLs must all
 * sit on it (y = 1, normal up), and their fluxes must add up to the flux it reflects,
 * rho E A = 0.75 E (E: the sun's illuminance across its beam), independently of the grid they were
 * drawn from. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "test_vpl_harness.h"

VPL_H_BOX_GROUP


static void sun_vpls_carry_the_flux_the_ceiling_reflects(void **state)
{
    (void)state;
    const float E = 3.0f; /* lux */
    H.box.lights[0].type = GK_LIGHT_DIRECTIONAL;
    H.box.lights[0].intensity = E;
    assert_true(H.scene.lights == H.box.lights);   /* the harness's scene reads the box's lights */
    assert_true(gk_gi_vpl.applies(&H.scene));
    H.gl_light.direction = v3(0, -1, 0);
    H.gl_light.position = v3(0.5f, 5.0f, 0.5f);
    H.gl_light.radiant = v3(E, E, E);
    assert_int_equal(h_budget(&H, "vpl_n=256,vpl_m=8,vpl_vis=cssm"), 0);
    assert_int_equal(h_frame(&H, 0), 0);
    const gk_vpl_stats *st = gk_vpl_get_stats(H.self);
    double flux = 0, area = 0, worst_y = 0, worst_n = 0;
    for (int i = 0; i < st->n; i++) {
        const gk_vpl *v = &st->vpl[i];
        if (!(v->flux.x + v->flux.y + v->flux.z > 0))
            continue;
        flux += v->flux.y;
        area += v->area;
        worst_y = fmax(worst_y, fabs(v->pos.y - 1.0));
        worst_n = fmax(worst_n, 1.0 - v->nrm.y);
    }
    double expect = 0.75 * E * 1.0;
    print_message("# sun straight down: %d of %d VPLs valid, flux sum %.4f W (expected rho E A = %.4f: ratio %.4f), "
                  "area sum %.4f, largest |y - 1| %.2e m, largest 1 - n.y %.2e\n",
                  st->n_valid, st->n, flux, expect, flux / expect, area, worst_y, worst_n);
    /* The face covers the region's bounding sphere (radius sqrt(3)/2 for the unit box): the ceiling is
       1/3 of it, so about 85 of 256 VPLs land there. Each VPL carries its texel's flux times
       texels / VPLs, so the sum is a Halton estimate of the ceiling's reflected flux: measured
       88 valid, ratio 1.011 (area sum 1.011 m^2); bound 5%, ~4.5x the measured error. */
    assert_true(st->n_valid > 60 && st->n_valid < 110);
    assert_true(fabs(flux / expect - 1.0) < 0.05);
    assert_true(worst_y < 0.01 && worst_n < 1e-3);
    /* and the box is lit indirectly: nothing, since every VPL faces up, away from the interior */
    double mean = h_mean(H.img, W * HH);
    print_message("# sun straight down: mean indirect radiance inside the closed box %.3e\n", mean);
    assert_true(mean < 1e-3 * E);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sun_vpls_carry_the_flux_the_ceiling_reflects),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
