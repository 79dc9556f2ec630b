/* Masks from images: the caustic mask (pixels above a fraction of the peak luminance) and a mask
 * read back from a mask image (see metrics.h). */
#include <math.h>
#include <stdlib.h>

#include "metrics/metrics.h"

unsigned char *gk_mask_above_peak(const gk_image *img, double fraction, float *peak_out)
{
    size_t n = (size_t)img->width * img->height;
    float *lum = gk_image_luminance_plane(img);
    unsigned char *mask = calloc(n ? n : 1, 1);
    if (!lum || !mask) {
        free(lum);
        free(mask);
        return NULL;
    }
    float peak = 0.0f;
    for (size_t p = 0; p < n; p++)
        if (isfinite(lum[p]) && lum[p] > peak)
            peak = lum[p];
    /* A black image has no caustic: the mask stays empty (0 > 0 is false). */
    double threshold = fraction * peak;
    for (size_t p = 0; p < n; p++)
        mask[p] = peak > 0.0f && isfinite(lum[p]) && lum[p] > threshold;
    if (peak_out)
        *peak_out = peak;
    free(lum);
    return mask;
}

unsigned char *gk_mask_from_image(const gk_image *img)
{
    size_t n = (size_t)img->width * img->height;
    int colour = gk_image_color_channels(img);
    unsigned char *mask = calloc(n ? n : 1, 1);
    if (!mask)
        return NULL;
    for (size_t p = 0; p < n; p++)
        for (int c = 0; c < colour; c++)
            if (img->pixels[p * img->channels + c] >= 0.5f)
                mask[p] = 1;
    return mask;
}

long gk_mask_count(const unsigned char *mask, int width, int height)
{
    long count = 0;
    for (size_t p = 0; p < (size_t)width * height; p++)
        count += mask[p] != 0;
    return count;
}
