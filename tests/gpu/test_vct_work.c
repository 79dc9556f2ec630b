/* The cone trace's work (app/gi/vct/vct_work.c, #21) on llvmpipe: the samples vct/trace.comp counts
 * against the open-space model, where the model is exact -- a lone floor seen from above through a
 * narrow view, cones short enough (max_dist) to stay inside the volume and over nothing opaque, so
 * only their length stops them. Then every traced pixel takes the model's samples, split below and
 * from lod 1 as the model splits them, and the pass_work the bench reads is their fetches. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "test_vct_util.h"

static vt_gl g;

static int group_setup(void **state)
{
    (void)state;
    return vt_gl_init(&g);
}

static int group_teardown(void **state)
{
    (void)state;
    vt_gl_fini(&g);
    return 0;
}

/* One traced frame of a floor quad at budget `pins` with options o; returns the stats. */
static void trace_floor(const char *pins, const gk_vct_options *o, gk_vct_stats *st, gk_pass_work *work, int *n_work)
{
    vt_scene sc;
    vt_scene_init(&sc);
    vt_add_quad(&sc, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), v3(0.5f, 0.5f, 0.5f));
    vt_scene_finish(&sc);
    gk_gi_light L = vt_light(&sc, GK_LIGHT_POINT, v3(0.5f, 1, 0.5f), v3(0, -1, 0), v3(1, 1, 1), 1);
    vt_frame f;
    /* 2 m above the centre, 0.2 rad: the view spans [0.3, 0.7] of the floor, every pixel on it */
    vt_frame_create(&f, 32, 32, v3(0.5f, 2, 0.5f), v3(0.5f, 0, 0.5f), v3(0, 0, -1), 0.2f);
    vt_gbuffer(&g, &f, &sc);
    void *vct = vt_create(&g);
    gk_vct_set_options(vct, o);
    gk_budget b;
    vt_budget(&b, pins);
    assert_int_equal(vt_render(vct, &f, &sc, &b, &L, 1, NULL, NULL), 0);
    gk_vct_get_stats(vct, st);
    *n_work = gk_gi_vct.pass_work(vct, work, GK_MAX_PASS_WORK);
    gk_gi_vct.destroy(vct);
    vt_frame_destroy(&f);
    vt_scene_free(&sc);
}

static void check_count_against_model(const char *pins, int cones, int res, bool aniso)
{
    gk_vct_options o;
    gk_vct_default_options(&o);
    /* 0.15 of the volume (~10 voxels at 64³): from pixels within [0.3, 0.7] a cone reaches at most
       0.15 sideways, never the volume's border, and nothing above the floor stops it */
    o.max_dist = 0.15f;
    gk_vct_stats st;
    gk_pass_work work[GK_MAX_PASS_WORK];
    int n_work = 0;
    trace_floor(pins, &o, &st, work, &n_work);
    double fine, coarse;
    gk_vct_trace_model(cones, res, 1.0f, aniso, &o, &fine, &coarse);
    double pixels = (double)st.trace_w * st.trace_h;
    printf("# %s: %lu pixels traced of %.0f; counted %lu samples (%lu below lod 1), model %.0f + %.0f a pixel\n", pins,
           st.last_trace_pixels, pixels, st.last_trace_steps, st.last_trace_fine_steps, fine, coarse);
    assert_true(fine + coarse > 10.0); /* the cones take steps at all: the check is not of zeros */
    assert_true(aniso ? coarse > 0.0 : coarse == 0.0);
    assert_int_equal(st.last_trace_pixels, (unsigned long)pixels);
    assert_int_equal(st.last_trace_fine_steps, (unsigned long)(pixels * fine));
    assert_int_equal(st.last_trace_steps, (unsigned long)(pixels * (fine + coarse)));
    /* the first frame also rebuilt the mips: with anisotropic ones, their loads come second */
    assert_int_equal(n_work, aniso ? 2 : 1);
    if (aniso) {
        assert_string_equal(work[1].pass, "gi.vct_mips");
        assert_string_equal(work[1].kind, "image3d_rgba16f_load");
        /* hand-computed once: 6 views x 8 loads x (32³ + 16³ + 8³ + 4³ + 2³) texels at 64³ (the
           chains stop at 2³, vct_grid.c) */
        assert_true(work[1].fetches == 48.0 * (32768 + 4096 + 512 + 64 + 8));
    }
    assert_string_equal(work[0].pass, "gi.vct_trace");
    assert_string_equal(work[0].kind, "tex3d_rgba16f_trilinear");
    assert_true(work[0].fetches == pixels * (aniso ? 4.0 * fine + 3.0 * coarse : fine + coarse));
}

static void aniso_count_matches_model(void **state)
{
    (void)state;
    check_count_against_model("vct_res=64,vct_cones=9,vct_step=1,vct_trace_scale=1,vct_mips=aniso", 9, 64, true);
}

static void iso_count_matches_model(void **state)
{
    (void)state;
    check_count_against_model("vct_res=32,vct_cones=4,vct_step=1,vct_trace_scale=1,vct_mips=iso", 4, 32, false);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(aniso_count_matches_model),
        cmocka_unit_test(iso_count_matches_model),
    };
    return cmocka_run_group_tests_name("vct_work", tests, group_setup, group_teardown);
}
