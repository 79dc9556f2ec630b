/* Whole-image statistics the metrics build on: means, luminance, the display tonemap of an image,
 * and the reference-driven auto exposure. */
#include <math.h>
#include <stdlib.h>

#include "core/tonemap.h"
#include "metrics/metrics.h"

int gk_image_color_channels(const gk_image *img)
{
    return img->channels >= 3 ? 3 : 1;
}

static size_t pixel_count(const gk_image *img)
{
    return img->pixels ? (size_t)img->width * (size_t)img->height : 0;
}

double gk_image_mean(const gk_image *img)
{
    size_t n = pixel_count(img);
    if (n == 0)
        return 0.0;
    int nc = gk_image_color_channels(img), ch = img->channels;
    double sum = 0.0;
    for (size_t p = 0; p < n; p++)
        for (int c = 0; c < nc; c++)
            sum += img->pixels[p * ch + c];
    return sum / ((double)n * nc);
}

static float pixel_luminance(const gk_image *img, size_t p)
{
    const float *v = img->pixels + p * img->channels;
    return img->channels >= 3 ? gk_luminance(v[0], v[1], v[2]) : v[0];
}

double gk_image_luminance_mean(const gk_image *img)
{
    size_t n = pixel_count(img);
    if (n == 0)
        return 0.0;
    double sum = 0.0;
    for (size_t p = 0; p < n; p++)
        sum += pixel_luminance(img, p);
    return sum / (double)n;
}

float *gk_image_luminance_plane(const gk_image *img)
{
    size_t n = pixel_count(img);
    float *plane = malloc((n ? n : 1) * sizeof *plane);
    if (!plane)
        return NULL;
    for (size_t p = 0; p < n; p++)
        plane[p] = pixel_luminance(img, p);
    return plane;
}

double gk_metrics_auto_exposure(const gk_image *ref)
{
    double mean = gk_image_luminance_mean(ref);
    return (mean > 0.0 && isfinite(mean)) ? 0.18 / mean : 1.0;
}

int gk_image_tonemap(const gk_image *src, double exposure, gk_image *dst, gk_err *e)
{
    if (gk_image_alloc(dst, src->width, src->height, src->channels) != 0)
        return gk_fail(e, GK_ERUNTIME, "out of memory for a %dx%d image", src->width, src->height);
    size_t n = pixel_count(src);
    int nc = gk_image_color_channels(src), ch = src->channels;
    for (size_t p = 0; p < n; p++)
        for (int c = 0; c < ch; c++) {
            float v = src->pixels[p * ch + c];
            dst->pixels[p * ch + c] = c < nc ? gk_tonemap(v, (float)exposure) : v;
        }
    return 0;
}
