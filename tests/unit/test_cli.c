/* `gikiosk run` command line: every option, `--opt=value`, and an exit-2 message naming the option
 * and the value for each kind of mistake. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "cli/cli.h"

static int parse(gk_run_opts *o, gk_err *e, const char *a0, ...)
{
    char *argv[40];
    int argc = 0;
    argv[argc++] = "run";
    va_list ap;
    va_start(ap, a0);
    for (const char *a = a0; a && argc < 40; a = va_arg(ap, const char *))
        argv[argc++] = (char *)a;
    va_end(ap);
    return gk_run_parse_args(argc, argv, o, e);
}

static void every_option_parses(void **state)
{
    (void)state;
    gk_run_opts o;
    gk_err e = {0};
    int rc = parse(&o, &e, "--config", "c.ini", "--platform", "mock", "--size=160x90", "--scene", "cornell,box",
                   "--method", "vct", "--frames", "12", "--target-ms", "33.3", "--script", "s.txt", "--capture",
                   "out", "--capture-every", "4", "--hdr", "--stats", "s.csv", "--gles", "3.1", "--budget",
                   "shadow_map=512,render_scale=0.5", "--shader-dir", "shaders_gles", "--scenes-dir", "sc", NULL);
    if (rc)
        print_message("# %s\n", e.msg);
    assert_int_equal(rc, 0);
    assert_string_equal(o.config_path, "c.ini");
    assert_true(o.platform_set && o.platform == GK_PLATFORM_MOCK);
    assert_true(o.size_set && o.width == 160 && o.height == 90);
    assert_string_equal(o.scene, "cornell,box");
    assert_string_equal(o.method, "vct");
    assert_int_equal(o.frames, 12);
    assert_true(o.target_set && o.target_ms > 33.2 && o.target_ms < 33.4);
    assert_int_equal(o.capture_every, 4);
    assert_true(o.hdr);
    assert_int_equal(o.gles, 31);
    assert_string_equal(o.scenes_dir, "sc");

    gk_kiosk_config c;
    gk_kiosk_config_defaults(&c);
    gk_run_opts_apply(&o, &c);
    assert_int_equal(c.platform, GK_PLATFORM_MOCK);
    assert_int_equal(c.width, 160);
    assert_int_equal(c.n_scenes, 2);
    assert_string_equal(c.scenes[1], "box");
    assert_true(c.target_ms > 33.2 && c.target_ms < 33.4);
}

static void defaults_leave_config_alone(void **state)
{
    (void)state;
    gk_run_opts o;
    gk_err e = {0};
    assert_int_equal(parse(&o, &e, "--seconds", "2.5", NULL), 0);
    assert_true(o.seconds == 2.5 && o.frames == 0);
    assert_string_equal(o.scenes_dir, "config/scenes");
    gk_kiosk_config c;
    gk_kiosk_config_defaults(&c);
    c.target_ms = 20;
    c.width = 333;
    gk_run_opts_apply(&o, &c);
    assert_true(c.target_ms == 20 && c.width == 333 && c.platform == GK_PLATFORM_AUTO);
}

static void expect(const char *want, const char *a0, ...)
{
    char *argv[20];
    int argc = 0;
    argv[argc++] = "run";
    va_list ap;
    va_start(ap, a0);
    for (const char *a = a0; a && argc < 20; a = va_arg(ap, const char *))
        argv[argc++] = (char *)a;
    va_end(ap);
    gk_run_opts o;
    gk_err e = {0};
    assert_int_equal(gk_run_parse_args(argc, argv, &o, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    if (strcmp(e.msg, want))
        print_message("# got: %s\n# want: %s\n", e.msg, want);
    assert_string_equal(e.msg, want);
}

static void bad_values_name_option_and_value(void **state)
{
    (void)state;
    expect("--size: '12x' is not WxH", "--size", "12x", NULL);
    expect("--platform: 'wayland' is not auto, kms or mock", "--platform=wayland", NULL);
    expect("--method: 'rtx' is not a method (none, vct, vpl, ispm, lgv, lightmap, volcaustics, radiosity)", "--method", "rtx", NULL);
    expect("--frames: '0' is not a positive integer", "--frames", "0", NULL);
    expect("--frames: '3x' is not a positive integer", "--frames", "3x", NULL);
    expect("--seconds: '-1' is not a positive number of seconds", "--seconds", "-1", NULL);
    expect("--target-ms: '0' is not a frame time in 1..1000 ms", "--target-ms", "0", NULL);
    expect("--gles: '3.0' is not 3.1 or 3.2", "--gles", "3.0", NULL);
    expect("--budget: 'shadow_map' is not KNOB=VALUE", "--budget", "render_scale=1,shadow_map", NULL);
    expect("--capture-every: 'often' is not a positive integer", "--capture", "d", "--capture-every", "often", NULL);
    expect("run: --frames and --seconds exclude each other (give one)", "--frames", "3", "--seconds", "1", NULL);
    expect("--capture-every: needs --capture DIR", "--capture-every", "2", NULL);
    expect("--hdr: needs --capture DIR", "--hdr", NULL);
    expect("--stats: missing value", "--stats", NULL);
    expect("--config: empty value", "--config=", NULL);
    expect("run: unknown option '--fps' (see gikiosk run --help)", "--fps", "60", NULL);
    expect("run: unexpected argument 'cornell' (see gikiosk run --help)", "cornell", NULL);
    expect("--scene: '../x' is not a scene name", "--scene", "../x", NULL);
}

static void help_is_recognised(void **state)
{
    (void)state;
    gk_run_opts o;
    gk_err e = {0};
    assert_int_equal(parse(&o, &e, "--frames", "2", "--help", NULL), 0);
    assert_true(o.help);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_option_parses),
        cmocka_unit_test(defaults_leave_config_alone),
        cmocka_unit_test(bad_values_name_option_and_value),
        cmocka_unit_test(help_is_recognised),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
