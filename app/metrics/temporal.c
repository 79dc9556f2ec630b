/* Temporal stability (flicker) of a frame sequence, streamed one frame at a time (see metrics.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/metrics.h"

int gk_flicker_begin(gk_flicker *f, int width, int height, int channels, gk_err *e)
{
    memset(f, 0, sizeof *f);
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
        return gk_fail(e, GK_EINPUT, "flicker: bad frame shape %dx%d with %d channels", width, height, channels);
    size_t n = (size_t)width * height;
    int nc = channels >= 3 ? 3 : 1;
    f->previous = malloc(n * nc * sizeof *f->previous);
    f->pixel_diff = calloc(n, sizeof *f->pixel_diff);
    if (!f->previous || !f->pixel_diff) {
        gk_flicker_free(f);
        return gk_fail(e, GK_ERUNTIME, "flicker: out of memory for %dx%d frames", width, height);
    }
    f->width = width;
    f->height = height;
    f->channels = channels;
    return 0;
}

int gk_flicker_add(gk_flicker *f, const gk_image *frame, gk_err *e)
{
    if (frame->width != f->width || frame->height != f->height || frame->channels != f->channels)
        return gk_fail(e, GK_EINPUT, "flicker: frame %d is %dx%d with %d channels, the first was %dx%d with %d",
                       f->frames, frame->width, frame->height, frame->channels, f->width, f->height, f->channels);
    size_t n = (size_t)f->width * f->height;
    int nc = gk_image_color_channels(frame), ch = frame->channels;
    for (size_t p = 0; p < n; p++) {
        double diff = 0.0;
        for (int c = 0; c < nc; c++) {
            float v = frame->pixels[p * ch + c];
            f->sum_values += v;
            if (f->frames > 0)
                diff += fabs((double)v - f->previous[p * nc + c]);
            f->previous[p * nc + c] = v;
        }
        f->pixel_diff[p] += diff / nc;
    }
    f->frames++;
    return 0;
}

static double relative(double change, double mean)
{
    if (mean != 0.0)
        return change / mean;
    return change == 0.0 ? 0.0 : INFINITY;
}

int gk_flicker_result_get(const gk_flicker *f, gk_flicker_result *out, gk_err *e)
{
    memset(out, 0, sizeof *out);
    if (f->frames < 2)
        return gk_fail(e, GK_EINPUT, "flicker: needs at least 2 frames, got %d", f->frames);
    size_t n = (size_t)f->width * f->height;
    int nc = f->channels >= 3 ? 3 : 1, pairs = f->frames - 1;
    double mean = f->sum_values / ((double)f->frames * n * nc);
    double total = 0.0, worst = -1.0;
    size_t worst_at = 0;
    for (size_t p = 0; p < n; p++) {
        double per_pixel = f->pixel_diff[p] / pairs;
        total += per_pixel;
        if (per_pixel > worst || (isnan(per_pixel) && !isnan(worst))) {
            worst = per_pixel;
            worst_at = p;
        }
    }
    out->frames = f->frames;
    out->flicker = relative(total / (double)n, mean);
    out->max_flicker = relative(worst, mean);
    out->max_flicker_at[0] = (int)(worst_at % (size_t)f->width);
    out->max_flicker_at[1] = (int)(worst_at / (size_t)f->width);
    return 0;
}

void gk_flicker_free(gk_flicker *f)
{
    free(f->previous);
    free(f->pixel_diff);
    f->previous = NULL;
    f->pixel_diff = NULL;
}

int gk_temporal_flicker(const gk_image *frames, int n, gk_flicker_result *out, gk_err *e)
{
    if (n < 2) {
        memset(out, 0, sizeof *out);
        return gk_fail(e, GK_EINPUT, "flicker: needs at least 2 frames, got %d", n);
    }
    gk_flicker f;
    if (gk_flicker_begin(&f, frames[0].width, frames[0].height, frames[0].channels, e) != 0)
        return -1;
    int rc = 0;
    for (int i = 0; i < n && rc == 0; i++)
        rc = gk_flicker_add(&f, &frames[i], e);
    if (rc == 0)
        rc = gk_flicker_result_get(&f, out, e);
    gk_flicker_free(&f);
    return rc;
}
