/* The calibration table the kiosk chooses methods from: parsing with file:line errors, the choice
 * rules (lowest error under the target, the fastest when nothing fits, never a method worse than
 * none), and the shipped table itself (config/calibration/llvmpipe.csv): it parses, and for every
 * scene at any target the automatic choice is never worse than `none`. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "render/renderer.h"
#include "sched/calibration.h"

static const char *write_tmp(const char *text)
{
    static char path[64];
    snprintf(path, sizeof path, "/tmp/gk-calib-XXXXXX");
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, text, strlen(text)), (int)strlen(text));
    close(fd);
    return path;
}

#define HEADER "# comment\nscene,method,width,height,frame_ms,error,metric,ruler\n"

static void parses_and_finds(void **state)
{
    (void)state;
    const char *p = write_tmp(HEADER "spot,none,160,120,3,0.376,rel_rmse,spot-1bounce\n"
                                     "spot,vct,160,120,32.5,0.467,rel_rmse,spot-1bounce\n\n"
                                     "spot,vpl,160,120,70,0.114,rel_rmse,spot-1bounce\n");
    gk_calibration c;
    gk_err e = {0};
    assert_int_equal(gk_calibration_load(p, &c, &e), 0);
    assert_int_equal(c.n, 3);
    const gk_calib_row *r = gk_calibration_find(&c, "spot", "vpl");
    assert_non_null(r);
    assert_true(r->frame_ms == 70 && r->error == 0.114 && r->width == 160);
    assert_null(gk_calibration_find(&c, "spot", "ispm"));
    gk_calibration_free(&c);
    remove(p);
}

#define HEADER2 "scene,method,width,height,frame_ms,error,metric,ruler,knob,value,passes\n"

static void knob_rows_and_passes(void **state)
{
    (void)state;
    const char *p = write_tmp(HEADER2 "spot,vct,640,360,300,0.48,rel_rmse,r,,,gi=290.5 gi.vct_trace=275\n"
                                      "spot,vct,640,360,440,0.47,rel_rmse,r,vct_cones,9,gi=430 gi.vct_trace=424.25\n"
                                      "spot,vct,640,360,250,0.49,rel_rmse,r,vct_cones,4,\n");
    gk_calibration c;
    gk_err e = {0};
    assert_int_equal(gk_calibration_load(p, &c, &e), 0);
    assert_int_equal(c.n, 3);
    const gk_calib_row *d = gk_calibration_find(&c, "spot", "vct");
    assert_non_null(d);
    assert_true(d->frame_ms == 300 && d->knob[0] == '\0'); /* the default row, not a knob's */
    assert_true(gk_calib_row_pass_ms(d, "gi") == 290.5);
    assert_true(gk_calib_row_pass_ms(d, "gi.vct_trace") == 275);
    assert_true(isnan(gk_calib_row_pass_ms(d, "gi.vct"))); /* a prefix is not a pass */
    assert_true(isnan(gk_calib_row_pass_ms(d, "shadow")));
    const gk_calib_row *r = gk_calibration_find_level(&c, "spot", "vct", "vct_cones", "9");
    assert_non_null(r);
    assert_true(r->frame_ms == 440 && r->error == 0.47 && gk_calib_row_pass_ms(r, "gi.vct_trace") == 424.25);
    r = gk_calibration_find_level(&c, "spot", "vct", "vct_cones", "4");
    assert_non_null(r);
    assert_true(isnan(gk_calib_row_pass_ms(r, "gi")));
    assert_null(gk_calibration_find_level(&c, "spot", "vct", "vct_cones", "6"));
    assert_null(gk_calibration_find_level(&c, "spot", "vpl", "vct_cones", "9"));
    gk_calibration_free(&c);
    remove(p);
}

static void bad_rows_name_file_and_line(void **state)
{
    (void)state;
    const char *bad[] = {
        HEADER "spot,none,160,120,3,0.3\n",                       /* 6 fields */
        HEADER "spot,none,160,x,3,0.3,rel_rmse,r\n",              /* height */
        HEADER "spot,none,160,120,-3,0.3,rel_rmse,r\n",           /* negative time */
        HEADER "spot,none,160,120,3,nan,rel_rmse,r\n",            /* error not finite */
        HEADER "spot,none,160,120,3,0.3,psnr,r\n",                /* metric */
        HEADER "spot,none,160,120,3,0.3,rel_rmse,r\nspot,none,160,120,3,0.3,rel_rmse,r\n", /* twice */
        "scene,method\nspot,none\n",                              /* header */
        HEADER2 "spot,none,160,120,3,0.3,rel_rmse,r\n",          /* 8 fields under the 11-field header */
        HEADER2 "spot,none,160,120,3,0.3,rel_rmse,r,shadow,,\n", /* a knob without a value */
        HEADER2 "spot,none,160,120,3,0.3,rel_rmse,r,,,gi=fast\n", /* a pass time */
        HEADER2 "spot,none,160,120,3,0.3,rel_rmse,r,,,gi 3\n",   /* PATH=MS */
        HEADER2 "spot,none,160,120,3,0.3,rel_rmse,r,shadow,hard,\nspot,none,160,120,3,0.3,rel_rmse,r,shadow,hard,\n",
    };
    const int line[] = {3, 3, 3, 3, 3, 4, 1, 2, 2, 2, 2, 3};
    for (int i = 0; i < (int)(sizeof bad / sizeof bad[0]); i++) {
        const char *p = write_tmp(bad[i]);
        gk_calibration c;
        gk_err e = {0};
        assert_int_equal(gk_calibration_load(p, &c, &e), -1);
        assert_int_equal(e.code, GK_EINPUT);
        char where[80];
        snprintf(where, sizeof where, "%s:%d:", p, line[i]);
        assert_non_null(strstr(e.msg, where));
        remove(p);
    }
    gk_calibration c;
    gk_err e = {0};
    assert_int_equal(gk_calibration_load("/nonexistent/llvmpipe.csv", &c, &e), -1);
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_int_equal(gk_calibration_load("/tmp", &c, &e), -1); /* a directory */
    assert_int_equal(e.code, GK_EINPUT);
}

static void choice_rules(void **state)
{
    (void)state;
    const char *p = write_tmp(HEADER "spot,none,100,100,3,0.376,rel_rmse,r\n"
                                     "spot,vct,100,100,30,0.467,rel_rmse,r\n"
                                     "spot,vpl,100,100,70,0.114,rel_rmse,r\n"
                                     "leak,none,100,100,5,0.007,rmse,r\n"
                                     "leak,vct,100,100,40,0.139,rmse,r\n");
    gk_calibration c;
    gk_err e = {0};
    assert_int_equal(gk_calibration_load(p, &c, &e), 0);
    const char *m[] = {"none", "vct", "vpl"};
    char why[256];
    /* lowest error under the target; vct (worse than none) never, even when it would fit */
    assert_int_equal(gk_calibration_choose(&c, "spot", m, 3, 100, 1e4, why, sizeof why), 2);
    assert_non_null(strstr(why, "vct 0.467 worse than none"));
    /* vpl over the target (4x the pixels: ~280 ms): none, the best that fits */
    assert_int_equal(gk_calibration_choose(&c, "spot", m, 3, 100, 4e4, why, sizeof why), 0);
    /* nothing fits: the fastest candidate */
    assert_int_equal(gk_calibration_choose(&c, "spot", m, 3, 1, 1e4, why, sizeof why), 0);
    /* without none in the list, a method worse than none is still not chosen */
    const char *gi[] = {"vct", "vpl"};
    assert_int_equal(gk_calibration_choose(&c, "spot", gi, 2, 1000, 1e4, NULL, 0), 1);
    const char *only_vct[] = {"vct"};
    assert_int_equal(gk_calibration_choose(&c, "spot", only_vct, 1, 1000, 1e4, NULL, 0), -1);
    /* light-leak: none has the least error (the ruler is black) */
    assert_int_equal(gk_calibration_choose(&c, "leak", m, 3, 1000, 1e4, NULL, 0), 0);
    /* an uncalibrated scene: no choice */
    assert_int_equal(gk_calibration_choose(&c, "atrium", m, 3, 1000, 1e4, NULL, 0), -1);
    gk_calibration_free(&c);
    remove(p);
    char cls[32];
    gk_calibration_class("llvmpipe (LLVM 15.0.6, 256 bits)", cls, sizeof cls);
    assert_string_equal(cls, "llvmpipe");
    gk_calibration_class("V3D 4.2", cls, sizeof cls);
    assert_string_equal(cls, "v3d");
}

/* The shipped table: for each of its scenes, at targets from impossible to unlimited and at the
 * showcase's size, the choice over the scene's calibrated methods is never worse than none. */
static void shipped_table_never_chooses_worse_than_none(void **state)
{
    (void)state;
    gk_calibration c;
    gk_err e = {0};
    assert_int_equal(gk_calibration_load("config/calibration/llvmpipe.csv", &c, &e), 0);
    assert_true(c.n > 0);
    const char *all[] = {"none", "vct", "vpl"};
    const double targets[] = {1, 100, 400, 1e6};
    int checked = 0;
    for (int i = 0; i < c.n; i++) {
        if (strcmp(c.rows[i].method, "none") != 0 || c.rows[i].knob[0])
            continue; /* each scene's default row of none */
        for (int t = 0; t < 4; t++) {
            int pick = gk_calibration_choose(&c, c.rows[i].scene, all, 3, targets[t], 640.0 * 360, NULL, 0);
            assert_true(pick >= 0);
            const gk_calib_row *r = gk_calibration_find(&c, c.rows[i].scene, all[pick]);
            assert_true(r->error <= c.rows[i].error);
            checked++;
        }
    }
    assert_true(checked >= 4 * 7); /* every scene with a reference */
    gk_calibration_free(&c);
}

/* The shipped table has, for every default row, a row for every automatic level of every knob the
 * scheduler may move for that method (the scheduler's cost and quality model reads them): the
 * knob sets are those of `gikiosk bench --sweep each` (gk_bench_each_knob_sweeps), listed here
 * from the knob definitions the renderer and the methods declare. */
static void shipped_table_has_every_knob_level(void **state)
{
    (void)state;
    gk_calibration c;
    gk_err e = {0};
    assert_int_equal(gk_calibration_load("config/calibration/llvmpipe.csv", &c, &e), 0);
    gk_budget b;
    gk_budget_init(&b);
    gk_renderer_declare_knobs(NULL, &b); /* declares only: the renderer is not used */
    /* a full budget refuses further knobs (gk_budget_add returns -1): lightmap_sync was lost so
       once every method's knobs passed 32 */
    assert_true(b.n < GK_MAX_KNOBS);
    assert_true(gk_budget_find(&b, "lightmap_sync") >= 0);
    int checked = 0;
    for (int i = 0; i < c.n; i++) {
        const gk_calib_row *d = &c.rows[i];
        if (d->knob[0])
            continue;
        for (int k = 0; k < b.n; k++) {
            const gk_knob_def *def = b.def[k];
            const char *owner = def->owner ? def->owner : "";
            if (def->fixed || (strcmp(owner, "render") != 0 && strcmp(owner, d->method) != 0))
                continue;
            int top = def->auto_max_level > 0 ? def->auto_max_level : def->n_values - 1;
            for (int l = 0; l <= top; l++) {
                if (l == def->default_level)
                    continue;
                const gk_calib_row *r = gk_calibration_find_level(&c, d->scene, d->method, def->name, def->values[l]);
                if (!r)
                    fail_msg("%s/%s: no row for %s=%s", d->scene, d->method, def->name, def->values[l]);
                assert_true(r->width == d->width && r->height == d->height);
                checked++;
            }
        }
    }
    print_message("# %d knob-level rows checked\n", checked);
    assert_true(checked > 100);
    gk_calibration_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(parses_and_finds),
        cmocka_unit_test(bad_rows_name_file_and_line),
        cmocka_unit_test(choice_rules),
        cmocka_unit_test(shipped_table_never_chooses_worse_than_none),
        cmocka_unit_test(knob_rows_and_passes),
        cmocka_unit_test(shipped_table_has_every_knob_level),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
