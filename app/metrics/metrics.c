/* Reference-against-test error metrics (definitions in metrics.h), over the whole image or a mask. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/tonemap.h"
#include "metrics/metrics.h"

int gk_metrics_check_same_shape(const gk_image *ref, const gk_image *test, gk_err *e)
{
    if (ref->width == test->width && ref->height == test->height && ref->channels == test->channels)
        return 0;
    return gk_fail(e, GK_EINPUT,
                   "size mismatch: reference is %dx%d with %d channels, test is %dx%d with %d channels",
                   ref->width, ref->height, ref->channels, test->width, test->height, test->channels);
}

/* Sums over the selected pixels, in double so 256x256 images lose nothing to rounding. */
typedef struct sums {
    double ref, test, sq, rel_sq, tonemapped_sq, max_error;
    long pixels, nonfinite;
    size_t max_at;
} sums;

static void accumulate(const gk_image *ref, const gk_image *test, float exposure, const unsigned char *mask, sums *s)
{
    size_t n = (size_t)ref->width * ref->height;
    int nc = gk_image_color_channels(ref), ch = ref->channels;
    memset(s, 0, sizeof *s);
    for (size_t p = 0; p < n; p++) {
        if (mask && !mask[p])
            continue;
        s->pixels++;
        for (int c = 0; c < nc; c++) {
            float r = ref->pixels[p * ch + c], t = test->pixels[p * ch + c];
            double d = (double)t - (double)r, ad = fabs(d);
            s->ref += r;
            s->test += t;
            s->sq += d * d;
            s->rel_sq += d * d / ((double)r * r + 0.01);
            double dt = (double)gk_tonemap(t, exposure) - (double)gk_tonemap(r, exposure);
            s->tonemapped_sq += dt * dt;
            if (!isfinite(t))
                s->nonfinite++;
            /* A NaN wins over any number (and the first NaN stays), so its place gets reported. */
            if (ad > s->max_error || (isnan(ad) && !isnan(s->max_error))) {
                s->max_error = ad;
                s->max_at = p;
            }
        }
    }
}

static double ratio_or_limit(double num, double den)
{
    if (den != 0.0)
        return num / den;
    return num == 0.0 ? 0.0 : INFINITY;
}

int gk_metrics_compute_masked(const gk_image *ref, const gk_image *test, double exposure,
                              const unsigned char *mask, gk_metrics *m, gk_err *e)
{
    memset(m, 0, sizeof *m);
    if (gk_metrics_check_same_shape(ref, test, e) != 0)
        return -1;
    if (!ref->pixels || !test->pixels || ref->width <= 0 || ref->height <= 0)
        return gk_fail(e, GK_EINPUT, "cannot compare empty images");
    if (!(exposure > 0.0) || !isfinite(exposure))
        exposure = gk_metrics_auto_exposure(ref);

    sums s;
    accumulate(ref, test, (float)exposure, mask, &s);
    if (s.pixels == 0)
        return gk_fail(e, GK_EINPUT, "the mask selects no pixel of the %dx%d image", ref->width, ref->height);
    double values = (double)s.pixels * gk_image_color_channels(ref);

    m->exposure = exposure;
    m->pixels = s.pixels;
    m->nonfinite = s.nonfinite;
    m->ref_mean = s.ref / values;
    m->test_mean = s.test / values;
    m->rmse = sqrt(s.sq / values);
    m->rel_rmse = ratio_or_limit(m->rmse, m->ref_mean);
    m->rel_mse = s.rel_sq / values;
    m->mean_ratio = (m->ref_mean == 0.0 && m->test_mean == 0.0) ? 1.0 : ratio_or_limit(m->test_mean, m->ref_mean);
    m->max_error = s.max_error;
    m->max_error_at[0] = (int)(s.max_at % (size_t)ref->width);
    m->max_error_at[1] = (int)(s.max_at / (size_t)ref->width);
    double mse_tonemapped = s.tonemapped_sq / values;
    m->psnr = mse_tonemapped > 0.0 ? 10.0 * log10(1.0 / mse_tonemapped) : (mse_tonemapped == 0.0 ? INFINITY : NAN);

    gk_image ref_tm = {0}, test_tm = {0};
    float *ref_lum = NULL, *test_lum = NULL;
    int rc = -1;
    if (gk_image_tonemap(ref, exposure, &ref_tm, e) != 0 || gk_image_tonemap(test, exposure, &test_tm, e) != 0)
        goto out;
    ref_lum = gk_image_luminance_plane(&ref_tm);
    test_lum = gk_image_luminance_plane(&test_tm);
    if (!ref_lum || !test_lum) {
        gk_fail(e, GK_ERUNTIME, "out of memory for SSIM of a %dx%d image", ref->width, ref->height);
        goto out;
    }
    m->ssim = gk_ssim_plane(test_lum, ref_lum, ref->width, ref->height, mask, NULL);
    rc = 0;
out:
    free(ref_lum);
    free(test_lum);
    gk_image_free(&ref_tm);
    gk_image_free(&test_tm);
    return rc;
}

int gk_metrics_compute(const gk_image *ref, const gk_image *test, double exposure, gk_metrics *m, gk_err *e)
{
    return gk_metrics_compute_masked(ref, test, exposure, NULL, m, e);
}

unsigned char *gk_mask_from_predicate(int width, int height, gk_pixel_predicate pred, void *ctx)
{
    if (width <= 0 || height <= 0)
        return NULL;
    unsigned char *mask = malloc((size_t)width * height);
    if (!mask)
        return NULL;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            mask[(size_t)y * width + x] = pred(x, y, ctx) ? 1 : 0;
    return mask;
}

unsigned char *gk_mask_from_pixels(int width, int height, const int *xy, int n)
{
    if (width <= 0 || height <= 0)
        return NULL;
    unsigned char *mask = calloc((size_t)width * height, 1);
    if (!mask)
        return NULL;
    for (int i = 0; i < n; i++) {
        int x = xy[2 * i], y = xy[2 * i + 1];
        if (x >= 0 && x < width && y >= 0 && y < height)
            mask[(size_t)y * width + x] = 1;
    }
    return mask;
}

typedef struct rect { int x0, y0, x1, y1; } rect;

static int inside_rect(int x, int y, void *ctx)
{
    const rect *r = ctx;
    return x >= r->x0 && x < r->x1 && y >= r->y0 && y < r->y1;
}

unsigned char *gk_mask_from_rect(int width, int height, int x0, int y0, int x1, int y1)
{
    rect r = {x0, y0, x1, y1};
    return gk_mask_from_predicate(width, height, inside_rect, &r);
}
