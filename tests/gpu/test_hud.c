/* The kiosk's HUD (app/kiosk/hud.h) rendered offscreen on llvmpipe at 640x360, 1280x720 and
 * 1920x1080 over a key colour (magenta): every pixel it touches lies outside the image centre (the
 * middle third in both directions), its capitals are at least GK_TEST_MIN_CAP_PX high, and its
 * content regions hold what they should: the scene line and the frame-time bars top-left, the knob
 * levels bottom-left, the speed-vs-error plot with its highlighted point bottom-right. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "kiosk/hud.h"
#include "kiosk/live_error.h"

/* Capital height of the smallest HUD text (GK_FONT_MIN_PX, 14 px at 640x360): measured 8 px, 12 at
 * 1280x720, 18 at 1920x1080 (12 px text gave 7). 8 px is the floor asserted: a capital of fewer
 * rows is hard to read at kiosk distance. */
#define GK_TEST_MIN_CAP_PX 8

static gkt_gl gl;

static int setup(void **state)
{
    (void)state;
    return gkt_gl_open(&gl);
}

static int teardown(void **state)
{
    (void)state;
    gkt_gl_close(&gl);
    return 0;
}

static const gk_knob_def knob_scale = {
    .name = "render_scale", .owner = "render", .n_values = 3,
    .values = {"0.5", "0.75", "1"}, .cost = {1, 2.25f, 4}, .default_level = 2,
};
static const gk_knob_def knob_shadow = {
    .name = "shadow_map", .owner = "render", .n_values = 4,
    .values = {"256", "512", "1024", "2048"}, .cost = {1, 2, 4, 8}, .default_level = 2,
};

typedef struct hud_image {
    int w, h;
    unsigned char *px; /* RGBA, GL rows: row 0 at the bottom */
} hud_image;

static const unsigned char *at(const hud_image *im, int x, int y) /* y from the top */
{
    return im->px + 4 * ((size_t)(im->h - 1 - y) * im->w + x);
}

static bool is_key(const unsigned char *p) { return p[0] == 255 && p[1] == 0 && p[2] == 255; }
/* white text on the panel (the key shows through the panel as dark magenta: green stays 0) */
static bool is_white(const unsigned char *p) { return p[0] > 200 && p[1] > 200 && p[2] > 200; }
static bool is_grey_text(const unsigned char *p) { return p[1] > 120; }
static bool is_bar(const unsigned char *p) { return (p[1] > 150 && p[0] < 150) || (p[0] > 200 && p[1] < 150 && p[2] < 120); }

static void render(int w, int h, const gk_hud_info *info, hud_image *out)
{
    gk_target t;
    GLenum fmt = GL_RGBA8;
    assert_int_equal(gkt_target(&t, "hud", w, h, 1, &fmt, false), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    glClearColor(1, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    gk_err e = {0};
    gk_hud *hud = gk_hud_create(w, h, gkt_shader_dir(), gl.egl.gles_version >= 32 ? 32 : 31, NULL, &e);
    assert_non_null(hud);
    assert_true(gk_hud_has_text(hud)); /* fonts-dejavu-core is a build dependency */
    gk_hud_draw(hud, t.fbo, info);
    out->w = w;
    out->h = h;
    out->px = malloc((size_t)w * h * 4);
    gkt_read_rgba(&t, 0, GL_UNSIGNED_BYTE, out->px);
    gk_hud_destroy(hud);
    gk_target_destroy(&t);
}

static long count_in(const hud_image *im, int x0, int y0, int x1, int y1, bool (*pred)(const unsigned char *))
{
    long n = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            n += pred(at(im, x, y));
    return n;
}

static void hud_at_size(int w, int h)
{
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &knob_scale);
    gk_budget_add(&b, &knob_shadow);
    gk_recent rec;
    gk_recent_clear(&rec);
    for (int i = 0; i < GK_RECENT_FRAMES; i++)
        gk_recent_push(&rec, (float)(10 + (i % 20)));
    gk_live_point pts[3] = {
        {.method = "vct", .levels = "vct_res=64", .ms_sum = 120, .frames = 10, .error = 0.18},
        {.method = "none", .levels = "", .ms_sum = 50, .frames = 10, .error = 0.34},
        {.method = "vct", .levels = "vct_res=32", .ms_sum = 80, .frames = 10, .error = 0.25},
    };
    gk_hud_info info = {
        .scene = "HHHH", .method = "vct", .method_mode = "auto", .frame_ms = 12.3, .median_ms = 12.0,
        .p95_ms = 15.1, .target_ms = 16.7, .recent = &rec, .budget = &b, .truth_note = "", .error = 0.1834,
        .truth_noise = 0.0123, .truth_spp = 256, .points = pts, .n_points = 3, .current_point = 0,
    };
    hud_image im;
    render(w, h, &info, &im);

    /* 1. the bounding box of everything drawn, and nothing in the centre */
    int bx0 = w, by0 = h, bx1 = -1, by1 = -1;
    long centre = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            if (is_key(at(&im, x, y)))
                continue;
            bx0 = x < bx0 ? x : bx0;
            by0 = y < by0 ? y : by0;
            bx1 = x > bx1 ? x : bx1;
            by1 = y > by1 ? y : by1;
            centre += x >= w * GK_HUD_CENTRE_LO && x < w * GK_HUD_CENTRE_HI && y >= h * GK_HUD_CENTRE_LO &&
                      y < h * GK_HUD_CENTRE_HI;
        }
    print_message("%dx%d: HUD pixels in [%d,%d]x[%d,%d], %ld in the centre third\n", w, h, bx0, bx1, by0, by1, centre);
    assert_true(bx1 >= 0); /* it drew something */
    assert_int_equal(centre, 0);

    /* 2. capital height: the rows of white pixels under the scene name "HHHH", top-left */
    int first = -1, last = -1;
    for (int y = 0; y < h / 3; y++) {
        bool white = count_in(&im, 0, y, w / 8, y + 1, is_white) > 0;
        if (white && first < 0)
            first = y;
        if (white)
            last = y;
        if (!white && first >= 0)
            break;
    }
    int cap = first >= 0 ? last - first + 1 : 0;
    print_message("%dx%d: capital H %d px high\n", w, h, cap);
    assert_true(cap >= GK_TEST_MIN_CAP_PX);

    /* 3. content regions */
    /* top-left third: text lines (scene, frame, error) and the frame-time bars */
    assert_true(count_in(&im, 0, 0, w / 2, h / 3, is_white) > 50);
    assert_true(count_in(&im, 0, 0, w / 2, h / 3, is_bar) > 100);
    /* bottom-left: the knob levels in grey text */
    assert_true(count_in(&im, 0, 2 * h / 3, w / 3, h, is_grey_text) > 50);
    /* bottom-right: the plot, its current point ringed in white */
    assert_true(count_in(&im, 2 * w / 3, 2 * h / 3, w, h, is_white) > 10);
    /* the top-right corner is the image's */
    assert_int_equal(count_in(&im, 2 * w / 3, 0, w, h / 3, is_key), (long)(w - 2 * w / 3) * (h / 3));
    free(im.px);
}

static void hud_640x360(void **state)
{
    (void)state;
    hud_at_size(640, 360);
}

static void hud_1280x720(void **state)
{
    (void)state;
    hud_at_size(1280, 720);
}

static void hud_1920x1080(void **state)
{
    (void)state;
    hud_at_size(1920, 1080);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(hud_640x360),
        cmocka_unit_test(hud_1280x720),
        cmocka_unit_test(hud_1920x1080),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
