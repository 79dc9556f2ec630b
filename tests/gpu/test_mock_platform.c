/* The mock platform on real Mesa (llvmpipe, EGL surfaceless): the FBO the app draws into, the
 * virtual clock, and scripted button events coming out as gestures at the right virtual times. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <GLES3/gl32.h>

#include "base/log.h"
#include "platform/platform.h"

static gk_platform *open_mock_quit(const char *script, double period, bool quit_at_end, gk_err *e)
{
    gk_platform_desc d;
    gk_platform_desc_defaults(&d);
    d.kind = GK_PLATFORM_MOCK;
    d.width = 64;
    d.height = 48;
    d.frame_period_s = period;
    d.buttons.hold_ms = 800;
    if (script)
        snprintf(d.script_path, sizeof d.script_path, "%s", script);
    d.quit_at_script_end = quit_at_end;
    return gk_platform_open(&d, e);
}

static gk_platform *open_mock(const char *script, double period, gk_err *e)
{
    return open_mock_quit(script, period, false, e);
}

static void fbo_is_complete_and_reads_back_a_clear(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_platform *p = open_mock(NULL, 1.0 / 60, &e);
    assert_non_null(p);
    assert_string_equal(gk_platform_name(p), "mock");
    int w = 0, h = 0;
    gk_platform_size(p, &w, &h);
    assert_int_equal(w, 64);
    assert_int_equal(h, 48);
    int v = gk_platform_gles_version(p);
    assert_true(v == 31 || v == 32);
    unsigned fbo = gk_platform_framebuffer(p);
    assert_true(fbo != 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    assert_int_equal(glCheckFramebufferStatus(GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    GLint tex_w = 0, tex_h = 0, tex = 0;
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &tex);
    glBindTexture(GL_TEXTURE_2D, (GLuint)tex);
    glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &tex_w);
    glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &tex_h);
    assert_int_equal(tex_w, 64);
    assert_int_equal(tex_h, 48);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    static unsigned char px[64 * 48 * 4];
    glReadPixels(0, 0, 64, 48, GL_RGBA, GL_UNSIGNED_BYTE, px);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    /* RGBA8 quantises 0.25 to 64 (63.75 rounded) and 0.75 to 191; +-1 for the rounding mode. */
    for (int i = 0; i < 64 * 48; i += 97) {
        assert_in_range(px[4 * i + 0], 63, 65);
        assert_in_range(px[4 * i + 1], 127, 128);
        assert_in_range(px[4 * i + 2], 190, 192);
        assert_int_equal(px[4 * i + 3], 255);
    }
    assert_int_equal(gk_platform_present(p, &e), 0);
    gk_platform_close(p);
}

static void virtual_clock_advances_by_the_period(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_platform *p = open_mock(NULL, 0.04, &e);
    assert_non_null(p);
    assert_true(gk_platform_now(p) == 0.0);
    for (int i = 1; i <= 25; i++) {
        assert_int_equal(gk_platform_present(p, &e), 0);
        assert_true(fabs(gk_platform_now(p) - 0.04 * i) < 1e-12);
    }
    /* Polling does not move virtual time, even with a timeout. */
    gk_input_event ev[8];
    assert_int_equal(gk_platform_poll(p, 100, ev, 8), 0);
    assert_true(fabs(gk_platform_now(p) - 1.0) < 1e-12);
    gk_platform_close(p);
}

static void scripted_events_arrive_at_their_virtual_times(void **state)
{
    (void)state;
    char path[] = "/tmp/gk-script-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("# a click, then a hold of the mode button\n"
          "0.5 next click\n"
          "\n"
          "1.0 mode hold 1200   # held past hold_ms (800): HOLD at 1.8 while still down\n", f);
    fclose(f);
    gk_err e = {0};
    gk_platform *p = open_mock(path, 0.1, &e);
    unlink(path);
    assert_non_null(p);
    struct { enum gk_input_kind kind; enum gk_button b; double t; int seen_at_frame; } seen[16];
    int n_seen = 0;
    for (int frame = 0; frame <= 30; frame++) {
        gk_input_event ev[8];
        int n = gk_platform_poll(p, 0, ev, 8);
        assert_true(n >= 0);
        for (int i = 0; i < n && n_seen < 16; i++) {
            assert_true(ev[i].time_s <= gk_platform_now(p) + 1e-9); /* never from the future */
            seen[n_seen].kind = ev[i].kind;
            seen[n_seen].b = ev[i].button;
            seen[n_seen].t = ev[i].time_s;
            seen[n_seen].seen_at_frame = frame;
            n_seen++;
        }
        assert_int_equal(gk_platform_present(p, &e), 0);
    }
    gk_platform_close(p);
    /* next: press 0.5, release+click 0.55 (seen at frame 6 = 0.6 s); mode: press 1.0, hold 1.8
     * (seen at frame 18), release 2.2 without a click. */
    assert_int_equal(n_seen, 6);
    assert_int_equal(seen[0].kind, GK_INPUT_PRESS);
    assert_int_equal(seen[0].b, GK_BTN_NEXT);
    assert_true(fabs(seen[0].t - 0.5) < 1e-9);
    assert_int_equal(seen[0].seen_at_frame, 5);
    assert_int_equal(seen[1].kind, GK_INPUT_RELEASE);
    assert_int_equal(seen[2].kind, GK_INPUT_CLICK);
    assert_true(fabs(seen[2].t - 0.55) < 1e-9);
    assert_int_equal(seen[2].seen_at_frame, 6);
    assert_int_equal(seen[3].kind, GK_INPUT_PRESS);
    assert_int_equal(seen[3].b, GK_BTN_MODE);
    assert_int_equal(seen[4].kind, GK_INPUT_HOLD);
    assert_int_equal(seen[4].b, GK_BTN_MODE);
    assert_true(fabs(seen[4].t - 1.8) < 1e-9);
    assert_int_equal(seen[4].seen_at_frame, 18);
    assert_int_equal(seen[5].kind, GK_INPUT_RELEASE);
    assert_true(fabs(seen[5].t - 2.2) < 1e-9);
}

static void bad_script_is_input_error_naming_file_and_line(void **state)
{
    (void)state;
    char path[] = "/tmp/gk-script-XXXXXX";
    int fd = mkstemp(path);
    FILE *f = fdopen(fd, "w");
    fputs("0.5 next click\n1.0 jump click\n", f);
    fclose(f);
    gk_err e = {0};
    gk_platform *p = open_mock(path, 0.1, &e);
    unlink(path);
    assert_null(p);
    assert_int_equal(e.code, GK_EINPUT);
    char want[64];
    snprintf(want, sizeof want, "%s:2: unknown button 'jump'", path);
    assert_non_null(strstr(e.msg, want));
    p = open_mock("/nonexistent/script.txt", 0.1, &e);
    assert_null(p);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "/nonexistent/script.txt"));
}

static void quit_after_the_script_when_asked(void **state)
{
    (void)state;
    char path[] = "/tmp/gk-script-XXXXXX";
    int fd = mkstemp(path);
    FILE *f = fdopen(fd, "w");
    fputs("0.2 info press\n0.45 info release\n", f);
    fclose(f);
    gk_err e = {0};
    gk_platform *p = open_mock_quit(path, 0.1, true, &e);
    unlink(path);
    assert_non_null(p);
    int quit_frame = -1;
    for (int frame = 0; frame < 20 && quit_frame < 0; frame++) {
        gk_input_event ev[8];
        int n = gk_platform_poll(p, 0, ev, 8);
        for (int i = 0; i < n; i++)
            if (ev[i].kind == GK_INPUT_QUIT)
                quit_frame = frame;
        gk_platform_present(p, &e);
    }
    gk_platform_close(p);
    assert_int_equal(quit_frame, 5); /* the release at 0.45 s is delivered at 0.5 s */
}

int main(void)
{
    gk_log_set_quiet(1);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fbo_is_complete_and_reads_back_a_clear),
        cmocka_unit_test(virtual_clock_advances_by_the_period),
        cmocka_unit_test(scripted_events_arrive_at_their_virtual_times),
        cmocka_unit_test(bad_script_is_input_error_naming_file_and_line),
        cmocka_unit_test(quit_after_the_script_when_asked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
