/* Image I/O through the OpenImageIO shim: round trips (PNG 8 bit, EXR half and float), metadata,
 * channel counts, row order, and clear errors for missing/corrupt files and unknown formats. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/image_io.h"

typedef struct { char dir[64]; char path[128]; } tmpdir;

static int setup(void **state)
{
    tmpdir *t = calloc(1, sizeof *t);
    snprintf(t->dir, sizeof t->dir, "/tmp/gk-imageio.XXXXXX");
    if (!mkdtemp(t->dir))
        return -1;
    *state = t;
    return 0;
}

static int teardown(void **state)
{
    tmpdir *t = *state;
    char cmd[160];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", t->dir);
    if (system(cmd) != 0)
        return -1;
    free(t);
    return 0;
}

static const char *tmp_path(void **state, const char *name)
{
    tmpdir *t = *state;
    snprintf(t->path, sizeof t->path, "%s/%s", t->dir, name);
    return t->path;
}

/* A gradient that differs in every pixel and channel, so a flipped or transposed read shows. */
static void fill_gradient(gk_image *img, float scale)
{
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++)
            for (int c = 0; c < img->channels; c++)
                img->pixels[((size_t)y * img->width + x) * img->channels + c] =
                    scale * (float)(x + 3 * y + 7 * c) / (float)(img->width + 3 * img->height + 28);
}

static float max_abs_diff(const gk_image *a, const gk_image *b)
{
    float m = 0;
    for (size_t i = 0; i < (size_t)a->width * a->height * a->channels; i++)
        m = fmaxf(m, fabsf(a->pixels[i] - b->pixels[i]));
    return m;
}

static void round_trip(void **state, const char *name, int channels, float scale, int as_float, float tolerance)
{
    gk_image a, b;
    gk_err e = {0};
    assert_int_equal(gk_image_alloc(&a, 37, 21, channels), 0);
    fill_gradient(&a, scale);
    const char *p = tmp_path(state, name);
    int rc = as_float ? gk_image_write_float(p, &a, NULL, &e) : gk_image_write(p, &a, NULL, &e);
    assert_int_equal(rc, 0);
    assert_int_equal(gk_image_read(p, &b, &e), 0);
    assert_int_equal(b.width, 37);
    assert_int_equal(b.height, 21);
    assert_int_equal(b.channels, channels);
    float d = max_abs_diff(&a, &b);
    if (d > tolerance)
        fail_msg("%s: max error %g > %g", name, d, tolerance);
    gk_image_free(&a);
    gk_image_free(&b);
}

/* 8-bit quantisation: at most half a step, 0.5/255 = 0.00196. */
static void png_round_trip_rgb_and_rgba(void **state)
{
    round_trip(state, "a.png", 3, 1.0f, 0, 0.5f / 255 + 1e-6f);
    round_trip(state, "b.png", 4, 1.0f, 0, 0.5f / 255 + 1e-6f);
    round_trip(state, "c.png", 1, 1.0f, 0, 0.5f / 255 + 1e-6f);
}

/* Half has an 11-bit significand: relative error <= 2^-11 = 4.9e-4; values up to 40 -> 0.02. */
static void exr_half_round_trip(void **state)
{
    round_trip(state, "h.exr", 3, 40.0f, 0, 40.0f * 4.9e-4f);
    round_trip(state, "h2.exr", 2, 1.0f, 0, 4.9e-4f);
}

static void exr_float_round_trip_is_exact(void **state)
{
    round_trip(state, "f.exr", 4, 1234.5f, 1, 0.0f);
}

static void png_clamps_out_of_range_values(void **state)
{
    gk_image a, b;
    gk_err e = {0};
    assert_int_equal(gk_image_alloc(&a, 2, 1, 3), 0);
    float v[6] = {-1.0f, 0.5f, 7.0f, NAN, 1.0f, 0.0f};
    memcpy(a.pixels, v, sizeof v);
    const char *p = tmp_path(state, "clamp.png");
    assert_int_equal(gk_image_write(p, &a, NULL, &e), 0);
    assert_int_equal(gk_image_read(p, &b, &e), 0);
    assert_float_equal(b.pixels[0], 0.0f, 1e-6);
    assert_float_equal(b.pixels[1], 128.0f / 255, 1e-6); /* 0.5 * 255 = 127.5 rounds to 128 */
    assert_float_equal(b.pixels[2], 1.0f, 1e-6);
    assert_float_equal(b.pixels[3], 0.0f, 1e-6);
    assert_float_equal(b.pixels[4], 1.0f, 1e-6);
    gk_image_free(&a);
    gk_image_free(&b);
}

static void top_row_first(void **state)
{
    gk_image a, b;
    gk_err e = {0};
    assert_int_equal(gk_image_alloc(&a, 4, 3, 1), 0);
    a.pixels[0] = 1.0f; /* top-left only */
    const char *p = tmp_path(state, "corner.exr");
    assert_int_equal(gk_image_write(p, &a, NULL, &e), 0);
    assert_int_equal(gk_image_read(p, &b, &e), 0);
    assert_float_equal(b.pixels[0], 1.0f, 0);
    for (int i = 1; i < 12; i++)
        assert_float_equal(b.pixels[i], 0.0f, 0);
    gk_image_free(&a);
    gk_image_free(&b);
}

static void exr_metadata_round_trip(void **state)
{
    gk_image a;
    gk_err e = {0};
    assert_int_equal(gk_image_alloc(&a, 8, 8, 3), 0);
    gk_image_meta meta = {.count = 2,
                          .keys = {"gikiosk:command", "gikiosk:seed"},
                          .values = {"gikiosk reference --scene cornell --spp 64 --out x.exr", "42"}};
    const char *p = tmp_path(state, "meta.exr");
    assert_int_equal(gk_image_write(p, &a, &meta, &e), 0);
    char out[256];
    assert_int_equal(gk_image_read_attr(p, "gikiosk:command", out, sizeof out, &e), 0);
    assert_string_equal(out, "gikiosk reference --scene cornell --spp 64 --out x.exr");
    assert_int_equal(gk_image_read_attr(p, "gikiosk:seed", out, sizeof out, &e), 0);
    assert_string_equal(out, "42");
    assert_int_equal(gk_image_read_attr(p, "gikiosk:absent", out, sizeof out, &e), 1);
    assert_string_equal(out, "");
    /* Truncation into a short buffer stays NUL-terminated. */
    assert_int_equal(gk_image_read_attr(p, "gikiosk:command", out, 8, &e), 0);
    assert_string_equal(out, "gikiosk");
    gk_image_free(&a);
}

static void png_metadata_round_trip(void **state)
{
    gk_image a;
    gk_err e = {0};
    assert_int_equal(gk_image_alloc(&a, 8, 8, 3), 0);
    gk_image_meta meta = {.count = 1, .keys = {"gikiosk:scene"}, .values = {"cornell"}};
    const char *p = tmp_path(state, "meta.png");
    assert_int_equal(gk_image_write(p, &a, &meta, &e), 0);
    char out[64];
    assert_int_equal(gk_image_read_attr(p, "gikiosk:scene", out, sizeof out, &e), 0);
    assert_string_equal(out, "cornell");
    gk_image_free(&a);
}

static void missing_file_is_input_error_naming_it(void **state)
{
    gk_image b = {0};
    gk_err e = {0};
    const char *p = tmp_path(state, "does-not-exist.exr");
    assert_int_equal(gk_image_read(p, &b, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "does-not-exist.exr"));
    assert_null(b.pixels);
    char out[8];
    gk_err e2 = {0};
    assert_int_equal(gk_image_read_attr(p, "k", out, sizeof out, &e2), -1);
    assert_int_equal(e2.code, GK_EINPUT);
}

static void corrupt_file_is_input_error(void **state)
{
    const char *p = tmp_path(state, "corrupt.exr");
    FILE *f = fopen(p, "wb");
    assert_non_null(f);
    fputs("v/1\x01 this is not an OpenEXR file at all, only text pretending", f);
    fclose(f);
    gk_image b = {0};
    gk_err e = {0};
    assert_int_equal(gk_image_read(p, &b, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "corrupt.exr"));

    /* A real EXR cut short: the header opens, the pixel read fails. (Not a PNG: OIIO 2.4's PNG
     * reader leaks its error string when libpng longjmps out of a truncated file, which LeakSanitizer
     * in `make asan` would report; our code frees everything either way.) */
    gk_image a;
    assert_int_equal(gk_image_alloc(&a, 64, 64, 3), 0);
    fill_gradient(&a, 1.0f);
    const char *q = tmp_path(state, "cut.exr");
    assert_int_equal(gk_image_write(q, &a, NULL, &e), 0);
    assert_int_equal(truncate(q, 600), 0);
    gk_err e2 = {0};
    assert_int_equal(gk_image_read(q, &b, &e2), -1);
    assert_int_equal(e2.code, GK_EINPUT);
    assert_non_null(strstr(e2.msg, "cut.exr"));
    assert_null(b.pixels);
    gk_image_free(&a);
}

/* Patches 4 bytes of a file at offset. */
static void patch4(const char *path, long at, const unsigned char v[4])
{
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    assert_int_equal(fseek(f, at, SEEK_SET), 0);
    assert_int_equal(fwrite(v, 1, 4, f), 4);
    fclose(f);
}

/* A length in a PNG chunk or an EXR header attribute that runs past the end of the file is refused
 * before OpenImageIO allocates it (found by tests/fuzz/fuzz_image.c: a 350-byte PNG whose tEXt
 * chunk claimed 1.7 GB, a 536-byte EXR whose attribute claimed 1.9 GB, each made the reader use
 * about 2 GB before it failed); the same files with their own lengths read. */
static void lengths_beyond_the_file_are_refused_before_reading(void **state)
{
    gk_image a, b = {0};
    assert_int_equal(gk_image_alloc(&a, 4, 4, 3), 0);
    fill_gradient(&a, 1.0f);
    gk_err e = {0};
    const char *png = tmp_path(state, "long-chunk.png");
    assert_int_equal(gk_image_write(png, &a, NULL, &e), 0);
    assert_int_equal(gk_image_read(png, &b, &e), 0);
    gk_image_free(&b);
    /* the chunk after IHDR (8 signature + 25 IHDR bytes) claims 0x6a000064 bytes */
    patch4(png, 33, (const unsigned char[4]){0x6a, 0x00, 0x00, 0x64});
    assert_int_equal(gk_image_read(png, &b, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "long-chunk.png: corrupt PNG: chunk"));
    assert_non_null(strstr(e.msg, "at byte 33 claims 1778384996 bytes"));
    assert_null(b.pixels);
    char out[16];
    gk_err e2 = {0};
    assert_int_equal(gk_image_read_attr(png, "k", out, sizeof out, &e2), -1);
    assert_non_null(strstr(e2.msg, "claims 1778384996 bytes"));

    const char *exr = tmp_path(state, "long-attr.exr");
    assert_int_equal(gk_image_write(exr, &a, NULL, &e), 0);
    assert_int_equal(gk_image_read(exr, &b, &e), 0);
    gk_image_free(&b);
    /* the first header attribute, `name\0type\0size` from byte 8: its size claims 0x71ffff00 */
    FILE *f = fopen(exr, "rb");
    assert_non_null(f);
    char head[128];
    assert_int_equal(fread(head, 1, sizeof head, f), sizeof head);
    fclose(f);
    const char *name = head + 8, *type = name + strlen(name) + 1;
    patch4(exr, (long)(type + strlen(type) + 1 - head), (const unsigned char[4]){0x00, 0xff, 0xff, 0x71});
    assert_int_equal(gk_image_read(exr, &b, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    char want[160];
    snprintf(want, sizeof want, "long-attr.exr: corrupt OpenEXR: header attribute '%s' (%s) claims 1912602368 bytes",
             name, type);
    assert_non_null(strstr(e.msg, want));
    assert_null(b.pixels);
    gk_image_free(&a);
}

/* Writes a 4x4 gradient EXR to tmp NAME (checking it reads back) and returns the byte offset of the
 * value of its header attribute `key` (`name\0type`, followed by the 4-byte size): where a test patches
 * the header. */
static long small_exr_attribute(void **state, const char *name, const char *key, size_t key_len, const char **path)
{
    gk_image a, b = {0};
    assert_int_equal(gk_image_alloc(&a, 4, 4, 3), 0);
    fill_gradient(&a, 1.0f);
    gk_err e = {0};
    *path = tmp_path(state, name);
    assert_int_equal(gk_image_write(*path, &a, NULL, &e), 0);
    assert_int_equal(gk_image_read(*path, &b, &e), 0);
    gk_image_free(&b);
    gk_image_free(&a);
    FILE *f = fopen(*path, "rb");
    assert_non_null(f);
    char head[512];
    size_t got = fread(head, 1, sizeof head, f);
    fclose(f);
    const char *at = memmem(head, got, key, key_len);
    assert_non_null(at);
    return (long)(at - head) + (long)key_len + 4;
}

/* The EXR's dataWindow is checked before OpenEXR sizes its line-offset table by it (found by
 * tests/fuzz/fuzz_image.c: a 400-byte EXR whose dataWindow claimed 1.68e9 x 1.70e9 pixels made the
 * reader use 2 GB before it failed): a window over the pixel cap is refused as too large, one whose
 * offset table cannot fit in the file as corrupt; the file with its own window reads. */
static void exr_data_window_is_checked_before_reading(void **state)
{
    gk_image b = {0};
    gk_err e = {0};
    const char *exr;
    const char key[] = "dataWindow\0box2i";
    long value = small_exr_attribute(state, "window.exr", key, sizeof key, &exr);
    /* ymax 2^20 - 1: 4 x 2^20 pixels (under the cap), a 512 KB offset table in a file of a few hundred bytes */
    patch4(exr, value + 12, (const unsigned char[4]){0xff, 0xff, 0x0f, 0x00});
    assert_int_equal(gk_image_read(exr, &b, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "window.exr: corrupt OpenEXR: its dataWindow (4x1048576) needs a 524288-byte line-offset table"));
    assert_null(b.pixels);
    /* the fuzzer's window: 1684957528 x 1698920304 (xmax, ymax as its bytes read) */
    patch4(exr, value + 8, (const unsigned char[4]){0x57, 0x69, 0x6e, 0x64});
    patch4(exr, value + 12, (const unsigned char[4]){0x6f, 0x77, 0x43, 0x65});
    gk_err e2 = {0};
    assert_int_equal(gk_image_read(exr, &b, &e2), -1);
    assert_int_equal(e2.code, GK_EINPUT);
    assert_non_null(strstr(e2.msg, "window.exr: image too large (1684957528x1698920304 in its OpenEXR dataWindow)"));
    /* an inverted window */
    patch4(exr, value + 8, (const unsigned char[4]){0xfe, 0xff, 0xff, 0xff});
    gk_err e3 = {0};
    assert_int_equal(gk_image_read(exr, &b, &e3), -1);
    assert_non_null(strstr(e3.msg, "corrupt OpenEXR: its dataWindow (0,0)-(-2,1698920303) is empty"));
}

/* An attribute of a fixed-size type (float here) whose size field disagrees with its type: OpenEXR
   reads the type's 4 bytes whatever the field says, so its reading of the header and ours part; the
   fuzzer's 502-byte file (tests/fuzz/corpus/image/found-attribute-size-mismatch-2GB.exr) gave a float 3
   bytes, OpenEXR then read an attribute of an unknown type claiming ~2 GB and allocated it. Refused
   before OpenEXR sees the file. */
static void exr_attribute_sizes_match_their_types(void **state)
{
    gk_image b = {0};
    gk_err e = {0};
    const char *exr;
    const char key[] = "pixelAspectRatio\0float";
    long value = small_exr_attribute(state, "sizes.exr", key, sizeof key, &exr);
    patch4(exr, value - 4, (const unsigned char[4]){3, 0, 0, 0}); /* its size field: 3, not 4 */
    assert_int_equal(gk_image_read(exr, &b, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "sizes.exr: corrupt OpenEXR: header attribute 'pixelAspectRatio' (float) has 3 bytes, not 4"));
    assert_null(b.pixels);
}

/* A side over 32768 is refused before OpenImageIO reads the pixels: the fuzzer's one-line EXR
   16,777,219 wide (2^24 pixels, under the pixel cap) made its read_scanlines ask for 34 GB. */
static void images_with_a_side_over_32768_are_refused(void **state)
{
    gk_image a, b = {0};
    gk_err e = {0};
    assert_int_equal(gk_image_alloc(&a, 32769, 1, 3), 0);
    const char *wide = tmp_path(state, "wide.exr");
    assert_int_equal(gk_image_write(wide, &a, NULL, &e), 0);
    gk_err e2 = {0};
    assert_int_equal(gk_image_read(wide, &b, &e2), -1);
    assert_int_equal(e2.code, GK_EINPUT);
    assert_non_null(strstr(e2.msg, "wide.exr: image too large (32769x1: a side over 32768)"));
    gk_image_free(&a);
}

static void write_errors(void **state)
{
    gk_image a;
    gk_err e = {0};
    assert_int_equal(gk_image_alloc(&a, 4, 4, 3), 0);
    assert_int_equal(gk_image_write(tmp_path(state, "x.notaformat"), &a, NULL, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "x.notaformat"));
    gk_err e2 = {0};
    assert_int_equal(gk_image_write(tmp_path(state, "no/such/dir/x.exr"), &a, NULL, &e2), -1);
    assert_int_equal(e2.code, GK_ERUNTIME);
    assert_non_null(strstr(e2.msg, "no/such/dir/x.exr"));
    gk_image_free(&a);
}

static void alloc_rejects_bad_sizes(void **state)
{
    (void)state;
    gk_image a;
    assert_int_equal(gk_image_alloc(&a, 0, 4, 3), -1);
    assert_null(a.pixels);
    assert_int_equal(gk_image_alloc(&a, 4, 4, 5), -1);
    assert_int_equal(gk_image_alloc(&a, 4, -1, 3), -1);
    gk_image_free(&a); /* safe on an empty image */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(png_round_trip_rgb_and_rgba),
        cmocka_unit_test(exr_half_round_trip),
        cmocka_unit_test(exr_float_round_trip_is_exact),
        cmocka_unit_test(png_clamps_out_of_range_values),
        cmocka_unit_test(top_row_first),
        cmocka_unit_test(exr_metadata_round_trip),
        cmocka_unit_test(png_metadata_round_trip),
        cmocka_unit_test(exr_data_window_is_checked_before_reading),
        cmocka_unit_test(exr_attribute_sizes_match_their_types),
        cmocka_unit_test(images_with_a_side_over_32768_are_refused),
        cmocka_unit_test(missing_file_is_input_error_naming_it),
        cmocka_unit_test(corrupt_file_is_input_error),
        cmocka_unit_test(lengths_beyond_the_file_are_refused_before_reading),
        cmocka_unit_test(write_errors),
        cmocka_unit_test(alloc_rejects_bad_sizes),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
