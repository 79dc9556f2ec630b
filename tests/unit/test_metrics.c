/* Image metrics on synthetic images with answers computed by hand (see metrics.h for the
 * definitions), plus PSNR/RMSE cross-checked against OpenImageIO's idiff as an independent oracle. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/tonemap.h"
#include "metrics/metrics.h"

static void make_constant(gk_image *img, int w, int h, int ch, float v)
{
    assert_int_equal(gk_image_alloc(img, w, h, ch), 0);
    for (size_t i = 0; i < (size_t)w * h * ch; i++)
        img->pixels[i] = v;
}

static void copy_image(gk_image *dst, const gk_image *src)
{
    assert_int_equal(gk_image_alloc(dst, src->width, src->height, src->channels), 0);
    memcpy(dst->pixels, src->pixels, (size_t)src->width * src->height * src->channels * sizeof(float));
}

/* A smooth, textured HDR image: gradients plus a sine pattern, values in [0.05, 2]. */
static void make_textured(gk_image *img, int w, int h)
{
    assert_int_equal(gk_image_alloc(img, w, h, 3), 0);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++)
                img->pixels[((size_t)y * w + x) * 3 + c] =
                    0.05f + (float)(x + y) / (float)(w + h) + 0.5f * (1.0f + sinf(0.4f * x + 0.7f * y + c));
}

/* Deterministic standard normal numbers (xorshift + Box-Muller), so the noise test is repeatable. */
static double normal(uint64_t *s)
{
    double u[2];
    for (int i = 0; i < 2; i++) {
        *s ^= *s << 13;
        *s ^= *s >> 7;
        *s ^= *s << 17;
        u[i] = ((*s >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2.0 * log(u[0])) * cos(6.283185307179586 * u[1]);
}

static void add_noise(gk_image *img, double sigma, uint64_t seed)
{
    for (size_t i = 0; i < (size_t)img->width * img->height * img->channels; i++)
        img->pixels[i] += (float)(sigma * normal(&seed));
}

static void identical_images_give_exactly_zero_error(void **state)
{
    (void)state;
    gk_image a, b;
    make_textured(&a, 48, 40);
    copy_image(&b, &a);
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&a, &b, 0, &m, &e), 0);
    assert_true(m.rmse == 0.0);
    assert_true(m.rel_rmse == 0.0);
    assert_true(m.rel_mse == 0.0);
    assert_true(m.max_error == 0.0);
    assert_true(isinf(m.psnr) && m.psnr > 0);
    assert_true(m.ssim == 1.0); /* exactly: numerator and denominator are the same numbers */
    assert_true(m.mean_ratio == 1.0);
    assert_int_equal(m.pixels, 48 * 40);
    gk_image_free(&a);
    gk_image_free(&b);
}

/* ref 0.5 grey, test 0.6 grey: rmse 0.1, rel_rmse 0.2, rel_mse 0.01/0.26, mean_ratio 1.2. The
 * exposure is 0.18/0.5 = 0.36; on constant images SSIM is its luminance term alone,
 * (2TR + C1)/(T^2 + R^2 + C1), and the tonemapped luminance of grey T is T (709 weights sum to 1). */
static void constant_offset(void **state)
{
    (void)state;
    gk_image r, t;
    make_constant(&r, 16, 12, 3, 0.5f);
    make_constant(&t, 16, 12, 3, 0.6f);
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    double d = (double)0.6f - (double)0.5f;
    assert_float_equal(m.rmse, d, 1e-12);
    assert_float_equal(m.rel_rmse, d / 0.5, 1e-12);
    assert_float_equal(m.rel_mse, d * d / (0.25 + 0.01), 1e-12);
    assert_float_equal(m.mean_ratio, (double)0.6f / 0.5, 1e-12);
    assert_float_equal(m.max_error, d, 1e-12);
    assert_int_equal(m.max_error_at[0], 0); /* all equal: the first in scan order */
    assert_int_equal(m.max_error_at[1], 0);
    assert_float_equal(m.exposure, 0.36, 1e-6);
    double T = gk_tonemap(0.6f, 0.36f), R = gk_tonemap(0.5f, 0.36f);
    assert_float_equal(m.psnr, -20.0 * log10(fabs(T - R)), 1e-4);
    double lum_T = gk_luminance((float)T, (float)T, (float)T), lum_R = gk_luminance((float)R, (float)R, (float)R);
    double C1 = 1e-4;
    assert_float_equal(m.ssim, (2 * lum_T * lum_R + C1) / (lum_T * lum_T + lum_R * lum_R + C1), 1e-6);
    assert_true(m.ssim < 1.0);
    gk_image_free(&r);
    gk_image_free(&t);
}

static void single_pixel_error_is_located(void **state)
{
    (void)state;
    gk_image r, t;
    make_textured(&r, 32, 24);
    copy_image(&t, &r);
    size_t idx = ((size_t)9 * 32 + 5) * 3 + 1; /* pixel x=5, y=9, green */
    t.pixels[idx] += 2.0f;
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    double n = 32.0 * 24 * 3, err = (double)t.pixels[idx] - (double)r.pixels[idx];
    assert_int_equal(m.max_error_at[0], 5);
    assert_int_equal(m.max_error_at[1], 9);
    assert_float_equal(m.max_error, err, 1e-12);
    assert_float_equal(m.rmse, sqrt(err * err / n), 1e-12);
    double mean_r = gk_image_mean(&r);
    assert_float_equal(m.mean_ratio, (mean_r + err / n) / mean_r, 1e-9);
    assert_float_equal(m.rel_rmse, sqrt(err * err / n) / mean_r, 1e-9);
    assert_true(m.ssim < 1.0 && m.ssim > 0.99); /* one pixel of 768 only dents the mean SSIM */
    gk_image_free(&r);
    gk_image_free(&t);
}

/* Gaussian noise lowers SSIM, more noise lowers it more. Measured on this 64x64 image at exposure
 * 1: sigma 0.01 -> 0.9994, 0.1 -> 0.937, 0.5 -> 0.318; the bounds leave margins around them. */
static void ssim_drops_with_noise(void **state)
{
    (void)state;
    gk_image r, t1, t2, t3;
    make_textured(&r, 64, 64);
    copy_image(&t1, &r);
    copy_image(&t2, &r);
    copy_image(&t3, &r);
    add_noise(&t1, 0.01, 1);
    add_noise(&t2, 0.1, 2);
    add_noise(&t3, 0.5, 3);
    gk_metrics m1, m2, m3;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&r, &t1, 1.0, &m1, &e), 0);
    assert_int_equal(gk_metrics_compute(&r, &t2, 1.0, &m2, &e), 0);
    assert_int_equal(gk_metrics_compute(&r, &t3, 1.0, &m3, &e), 0);
    print_message("# ssim for noise 0.01 / 0.1 / 0.5: %.4f %.4f %.4f; rmse %.4f %.4f %.4f\n", m1.ssim, m2.ssim,
                  m3.ssim, m1.rmse, m2.rmse, m3.rmse);
    assert_true(m1.ssim > 0.99 && m1.ssim < 1.0);
    assert_true(m2.ssim > 0.85 && m2.ssim < m1.ssim - 0.03);
    assert_true(m3.ssim < 0.5 && m3.ssim < m2.ssim - 0.3);
    /* rmse of added N(0, sigma) noise is sigma within sampling error (12288 values: ~1%). */
    assert_float_equal(m2.rmse, 0.1, 0.005);
    gk_image_free(&r);
    gk_image_free(&t1);
    gk_image_free(&t2);
    gk_image_free(&t3);
}

/* The separable, border-renormalised window must equal the textbook 2D 11x11 Gaussian window at
 * interior pixels (where no clipping happens): SSIM computed directly from the definition. */
static double ssim_direct(const float *a, const float *b, int w, int x, int y)
{
    double wsum = 0, ma = 0, mb = 0, maa = 0, mbb = 0, mab = 0;
    for (int dy = -5; dy <= 5; dy++)
        for (int dx = -5; dx <= 5; dx++) {
            double g = exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
            double va = a[(y + dy) * w + x + dx], vb = b[(y + dy) * w + x + dx];
            wsum += g;
            ma += g * va;
            mb += g * vb;
            maa += g * va * va;
            mbb += g * vb * vb;
            mab += g * va * vb;
        }
    ma /= wsum, mb /= wsum, maa /= wsum, mbb /= wsum, mab /= wsum;
    double C1 = 1e-4, C2 = 9e-4;
    return (2 * ma * mb + C1) * (2 * (mab - ma * mb) + C2) /
           ((ma * ma + mb * mb + C1) * (maa - ma * ma + mbb - mb * mb + C2));
}

static void ssim_window_matches_direct_definition(void **state)
{
    (void)state;
    enum { W = 24, H = 20 };
    float a[W * H], b[W * H], map[W * H];
    uint64_t seed = 99;
    for (int i = 0; i < W * H; i++) {
        a[i] = 0.5f + 0.3f * sinf(0.3f * (float)i);
        b[i] = a[i] + (float)(0.05 * normal(&seed));
    }
    double mean = gk_ssim_plane(a, b, W, H, NULL, map);
    double sum = 0;
    for (int i = 0; i < W * H; i++)
        sum += map[i];
    assert_float_equal(mean, sum / (W * H), 1e-6);
    int points[][2] = {{5, 5}, {12, 9}, {18, 14}};
    for (int k = 0; k < 3; k++) {
        int x = points[k][0], y = points[k][1];
        double want = ssim_direct(a, b, W, x, y);
        if (fabs(map[y * W + x] - want) > 1e-5)
            fail_msg("ssim at (%d, %d): %g, direct %g", x, y, map[y * W + x], want);
    }
}

static void scaled_image_mean_ratio(void **state)
{
    (void)state;
    gk_image r, t;
    make_textured(&r, 20, 20);
    copy_image(&t, &r);
    for (size_t i = 0; i < 20 * 20 * 3; i++)
        t.pixels[i] *= 1.5f;
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    assert_float_equal(m.mean_ratio, 1.5, 1e-6);
    /* rmse = 0.5 * sqrt(mean r^2) */
    double sq = 0;
    for (size_t i = 0; i < 20 * 20 * 3; i++)
        sq += (double)r.pixels[i] * r.pixels[i];
    assert_float_equal(m.rmse, 0.5 * sqrt(sq / 1200), 1e-6);
    gk_image_free(&r);
    gk_image_free(&t);
}

static void black_reference_limits(void **state)
{
    (void)state;
    gk_image r, t;
    make_constant(&r, 8, 8, 3, 0.0f);
    make_constant(&t, 8, 8, 3, 0.0f);
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    assert_true(m.mean_ratio == 1.0 && m.rel_rmse == 0.0 && m.exposure == 1.0);
    t.pixels[5] = 0.25f;
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    assert_true(isinf(m.mean_ratio) && isinf(m.rel_rmse));
    assert_float_equal(m.max_error, 0.25, 0);
    assert_int_equal(m.max_error_at[0], 1); /* value 5 = pixel 1, blue */
    gk_image_free(&r);
    gk_image_free(&t);
}

static void alpha_is_ignored_and_grey_works(void **state)
{
    (void)state;
    gk_image r, t;
    make_constant(&r, 8, 8, 4, 1.0f);
    copy_image(&t, &r);
    for (int p = 0; p < 64; p++)
        t.pixels[p * 4 + 3] = 0.0f; /* alpha only */
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    assert_true(m.rmse == 0.0 && m.ssim == 1.0);
    gk_image_free(&r);
    gk_image_free(&t);

    make_constant(&r, 8, 8, 1, 2.0f);
    make_constant(&t, 8, 8, 1, 3.0f);
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    assert_float_equal(m.rmse, 1.0, 0);
    assert_float_equal(m.mean_ratio, 1.5, 0);
    assert_float_equal(m.exposure, 0.09, 1e-9);
    gk_image_free(&r);
    gk_image_free(&t);
}

static void mismatch_names_both_sizes(void **state)
{
    (void)state;
    gk_image r, t;
    make_constant(&r, 8, 6, 3, 1.0f);
    make_constant(&t, 6, 8, 3, 1.0f);
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_non_null(strstr(e.msg, "8x6 with 3 channels"));
    assert_non_null(strstr(e.msg, "6x8 with 3 channels"));
    gk_image_free(&t);
    make_constant(&t, 8, 6, 4, 1.0f);
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), -1);
    assert_non_null(strstr(e.msg, "8x6 with 4 channels"));
    gk_image_free(&r);
    gk_image_free(&t);
}

static int left_half(int x, int y, void *ctx)
{
    (void)y;
    return x < *(int *)ctx;
}

static void mask_metrics(void **state)
{
    (void)state;
    gk_image r, t;
    make_constant(&r, 16, 8, 3, 1.0f);
    copy_image(&t, &r);
    for (int y = 0; y < 8; y++) /* error 0.5 in the right half only */
        for (int x = 8; x < 16; x++)
            for (int c = 0; c < 3; c++)
                t.pixels[((size_t)y * 16 + x) * 3 + c] = 1.5f;
    int half = 8;
    unsigned char *left = gk_mask_from_predicate(16, 8, left_half, &half);
    unsigned char *right = gk_mask_from_rect(16, 8, 8, 0, 100, 100);
    int xy[] = {3, 3, 12, 5, 99, 99}; /* the third lies outside and is ignored */
    unsigned char *two = gk_mask_from_pixels(16, 8, xy, 3);
    unsigned char *none = gk_mask_from_rect(16, 8, 0, 0, 0, 0);
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute_masked(&r, &t, 0, left, &m, &e), 0);
    assert_true(m.rmse == 0.0 && m.mean_ratio == 1.0);
    assert_int_equal(m.pixels, 64);
    assert_int_equal(gk_metrics_compute_masked(&r, &t, 0, right, &m, &e), 0);
    assert_float_equal(m.rmse, 0.5, 0);
    assert_float_equal(m.mean_ratio, 1.5, 0);
    assert_int_equal(m.max_error_at[0], 8);
    assert_int_equal(gk_metrics_compute_masked(&r, &t, 0, two, &m, &e), 0);
    assert_int_equal(m.pixels, 2);
    assert_float_equal(m.rmse, sqrt(0.25 / 2), 1e-12); /* one of the two pixels is off by 0.5 */
    assert_int_equal(m.max_error_at[0], 12);
    assert_int_equal(m.max_error_at[1], 5);
    /* The whole image: exposure from the whole reference (mean lum 1 -> 0.18), same in every mask. */
    assert_float_equal(m.exposure, 0.18, 1e-9);
    assert_int_equal(gk_metrics_compute_masked(&r, &t, 0, none, &m, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    free(left);
    free(right);
    free(two);
    free(none);
    gk_image_free(&r);
    gk_image_free(&t);
}

/* The caustic mask: luminance strictly above a fraction of the peak; NaN pixels never selected and
 * never the peak; a black image gives an empty mask; a mask image reads back where a channel >= 0.5. */
static void caustic_mask_above_peak(void **state)
{
    (void)state;
    gk_image img;
    make_constant(&img, 4, 2, 3, 0.0f);
    /* Grey pixels, so luminance = the value: peak 4, threshold 1. */
    const float v[8] = {4.0f, 1.0f, 1.01f, 0.5f, 2.0f, NAN, 0.0f, 3.0f};
    for (int p = 0; p < 8; p++)
        for (int c = 0; c < 3; c++)
            img.pixels[3 * p + c] = v[p];
    float peak = 0.0f;
    unsigned char *m = gk_mask_above_peak(&img, 0.25, &peak);
    assert_non_null(m);
    assert_true(peak == 4.0f);
    const unsigned char want[8] = {1, 0, 1, 0, 1, 0, 0, 1};
    for (int p = 0; p < 8; p++)
        assert_int_equal(m[p], want[p]);
    assert_int_equal(gk_mask_count(m, 4, 2), 4);
    free(m);
    /* Luminance, not a channel: pure blue 4 has luminance 0.2888, under 1/4 of a grey 4's peak. */
    for (int c = 0; c < 3; c++)
        img.pixels[3 * 1 + c] = c == 2 ? 4.0f : 0.0f;
    m = gk_mask_above_peak(&img, 0.25, NULL);
    assert_int_equal(m[1], 0);
    free(m);
    gk_image_free(&img);

    make_constant(&img, 3, 3, 3, 0.0f);
    m = gk_mask_above_peak(&img, 0.25, &peak);
    assert_non_null(m);
    assert_true(peak == 0.0f);
    assert_int_equal(gk_mask_count(m, 3, 3), 0);
    free(m);
    gk_image_free(&img);

    /* Read back from a mask image: a grey+alpha image, alpha ignored, >= 0.5 selected. */
    make_constant(&img, 3, 1, 2, 1.0f);
    img.pixels[0] = 0.5f, img.pixels[2] = 0.49f, img.pixels[4] = 1.0f;
    /* pixel 1: grey 0.49 under alpha 1 (make_constant): alpha must not select it */
    m = gk_mask_from_image(&img);
    assert_int_equal(m[0], 1);
    assert_int_equal(m[1], 0);
    assert_int_equal(m[2], 1);
    free(m);
    gk_image_free(&img);
}

static void nan_pixel_is_reported(void **state)
{
    (void)state;
    gk_image r, t;
    make_textured(&r, 8, 8);
    copy_image(&t, &r);
    t.pixels[(2 * 8 + 3) * 3] = NAN;
    t.pixels[(6 * 8 + 6) * 3] += 100.0f; /* a bigger finite error later in scan order */
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    assert_int_equal(m.nonfinite, 1);
    assert_true(isnan(m.max_error));
    assert_int_equal(m.max_error_at[0], 3);
    assert_int_equal(m.max_error_at[1], 2);
    gk_image_free(&r);
    gk_image_free(&t);
}

static void means_and_exposure(void **state)
{
    (void)state;
    gk_image a;
    assert_int_equal(gk_image_alloc(&a, 2, 1, 3), 0);
    float v[6] = {1, 0, 0, 0, 1, 0};
    memcpy(a.pixels, v, sizeof v);
    assert_float_equal(gk_image_mean(&a), 2.0 / 6, 1e-12);
    assert_float_equal(gk_image_luminance_mean(&a), (0.2126 + 0.7152) / 2, 1e-6);
    assert_float_equal(gk_metrics_auto_exposure(&a), 0.18 / ((0.2126 + 0.7152) / 2), 1e-5);
    gk_image tm;
    gk_err e = {0};
    assert_int_equal(gk_image_tonemap(&a, 2.0, &tm, &e), 0);
    assert_float_equal(tm.pixels[0], gk_srgb_oetf(gk_aces_fitted(2.0f)), 0);
    assert_float_equal(tm.pixels[1], 0.0f, 0);
    gk_image_free(&tm);
    gk_image_free(&a);
}

/* 4x4 grey frames of 1, except pixel (2, 1) going 1, 3, 1: 2 pairs, that pixel changes by 2 each
 * time, the rest never. Global mean = (48 + 2) / 48; flicker = (2 / 16) / mean; max = 2 / mean. */
static void flicker_by_hand(void **state)
{
    (void)state;
    gk_image f[3];
    for (int i = 0; i < 3; i++)
        make_constant(&f[i], 4, 4, 1, 1.0f);
    f[1].pixels[1 * 4 + 2] = 3.0f;
    gk_flicker_result res;
    gk_err e = {0};
    assert_int_equal(gk_temporal_flicker(f, 3, &res, &e), 0);
    double mean = 50.0 / 48.0;
    assert_float_equal(res.flicker, (2.0 / 16) / mean, 1e-12);
    assert_float_equal(res.max_flicker, 2.0 / mean, 1e-12);
    assert_int_equal(res.max_flicker_at[0], 2);
    assert_int_equal(res.max_flicker_at[1], 1);
    assert_int_equal(res.frames, 3);

    assert_int_equal(gk_temporal_flicker(f, 1, &res, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    gk_image_free(&f[2]);
    make_constant(&f[2], 4, 5, 1, 1.0f);
    assert_int_equal(gk_temporal_flicker(f, 3, &res, &e), -1);
    assert_non_null(strstr(e.msg, "4x5"));
    for (int i = 0; i < 3; i++)
        gk_image_free(&f[i]);

    gk_image s[2];
    make_constant(&s[0], 4, 4, 3, 0.7f);
    make_constant(&s[1], 4, 4, 3, 0.7f);
    assert_int_equal(gk_temporal_flicker(s, 2, &res, &e), 0);
    assert_true(res.flicker == 0.0 && res.max_flicker == 0.0);
    gk_image_free(&s[0]);
    gk_image_free(&s[1]);
}

/* idiff -v prints "RMS error = X" and "Peak SNR = Y" (20 log10(1 / rms) over all channels). Our
 * rmse on the linear pair must match its RMS, and our psnr must match its PSNR of the tonemapped
 * pair (written as float EXR with the exposure the metrics used). */
static int idiff_stats(const char *a, const char *b, double *rms, double *psnr)
{
    char cmd[512], line[256];
    snprintf(cmd, sizeof cmd, "idiff -v '%s' '%s' 2>&1", a, b);
    FILE *p = popen(cmd, "r");
    if (!p)
        return -1;
    int found = 0;
    while (fgets(line, sizeof line, p)) {
        if (sscanf(line, " RMS error = %lf", rms) == 1)
            found |= 1;
        if (sscanf(line, " Peak SNR = %lf", psnr) == 1)
            found |= 2;
    }
    pclose(p);
    return found == 3 ? 0 : -1;
}

static void cross_check_with_idiff(void **state)
{
    (void)state;
    char dir[] = "/tmp/gk-metrics.XXXXXX";
    assert_non_null(mkdtemp(dir));
    char pr[64], pt[64], pr_tm[64], pt_tm[64];
    snprintf(pr, sizeof pr, "%s/r.exr", dir);
    snprintf(pt, sizeof pt, "%s/t.exr", dir);
    snprintf(pr_tm, sizeof pr_tm, "%s/r_tm.exr", dir);
    snprintf(pt_tm, sizeof pt_tm, "%s/t_tm.exr", dir);
    gk_image r, t, r_tm, t_tm;
    make_textured(&r, 64, 48);
    copy_image(&t, &r);
    add_noise(&t, 0.05, 7);
    gk_err e = {0};
    assert_int_equal(gk_image_write_float(pr, &r, NULL, &e), 0);
    assert_int_equal(gk_image_write_float(pt, &t, NULL, &e), 0);
    gk_metrics m;
    assert_int_equal(gk_metrics_compute(&r, &t, 0, &m, &e), 0);
    assert_int_equal(gk_image_tonemap(&r, m.exposure, &r_tm, &e), 0);
    assert_int_equal(gk_image_tonemap(&t, m.exposure, &t_tm, &e), 0);
    assert_int_equal(gk_image_write_float(pr_tm, &r_tm, NULL, &e), 0);
    assert_int_equal(gk_image_write_float(pt_tm, &t_tm, NULL, &e), 0);

    double rms, psnr_linear, rms_tm, psnr;
    assert_int_equal(idiff_stats(pr, pt, &rms, &psnr_linear), 0);
    assert_int_equal(idiff_stats(pr_tm, pt_tm, &rms_tm, &psnr), 0);
    print_message("# rmse %.6g (idiff %.6g), psnr %.4f (idiff %.4f)\n", m.rmse, rms, m.psnr, psnr);
    /* idiff prints 6 significant digits and accumulates in its own order: agree to 1e-5 relative. */
    assert_float_equal(m.rmse, rms, 1e-5 * rms);
    assert_float_equal(m.psnr, psnr, 1e-3);
    gk_image_free(&r);
    gk_image_free(&t);
    gk_image_free(&r_tm);
    gk_image_free(&t_tm);
    char cmd[96];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(identical_images_give_exactly_zero_error),
        cmocka_unit_test(constant_offset),
        cmocka_unit_test(single_pixel_error_is_located),
        cmocka_unit_test(ssim_drops_with_noise),
        cmocka_unit_test(ssim_window_matches_direct_definition),
        cmocka_unit_test(scaled_image_mean_ratio),
        cmocka_unit_test(black_reference_limits),
        cmocka_unit_test(alpha_is_ignored_and_grey_works),
        cmocka_unit_test(mismatch_names_both_sizes),
        cmocka_unit_test(mask_metrics),
        cmocka_unit_test(caustic_mask_above_peak),
        cmocka_unit_test(nan_pixel_is_reported),
        cmocka_unit_test(means_and_exposure),
        cmocka_unit_test(flicker_by_hand),
        cmocka_unit_test(cross_check_with_idiff),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
