/* Image error metrics between a reference and a test image (linear HDR radiance), and temporal
 * stability of a frame sequence. Used by `gikiosk compare`, the bench and the accuracy tests.
 *
 * Channels: the "colour channels" are R, G, B for 3- and 4-channel images and channel 0 for 1- and
 * 2-channel (grey, grey+alpha) images; alpha never counts. "Mean over RGB" below means the mean over
 * every pixel and every colour channel. Luminance is gk_luminance (Rec. 709) of R, G, B, or the grey
 * value.
 *
 * Definitions (t = test, r = reference, values linear):
 *   rmse       = sqrt(mean over RGB of (t - r)^2)
 *   rel_rmse   = rmse / (mean over RGB of r): a normalised RMSE, well defined where single pixels
 *                of r are 0. 0 when rmse is 0; +inf when rmse > 0 and r's mean is 0.
 *   rel_mse    = mean over RGB of (t - r)^2 / (r^2 + 0.01): the per-pixel relative MSE (0.01 keeps
 *                dark pixels from dominating).
 *   mean_ratio = (mean over RGB of t) / (mean over RGB of r): the energy ratio. 1 when both means
 *                are 0; +inf when only r's mean is 0.
 *   max_error  = the largest |t - r| over RGB, at pixel max_error_at = [x, y] (x from the left, y
 *                from the top; the first in scan order on ties; a NaN in either image wins, so its
 *                place is reported, and max_error is then NaN).
 *   psnr, ssim = on the tonemapped images: display = gk_tonemap(exposure * linear) per colour channel
 *                (app/core/tonemap.h), with exposure = 0.18 / (mean luminance of r) — 1 when that mean
 *                is 0 — unless an exposure is given. Both images use the reference's exposure.
 *                psnr = 10 log10(1 / mean over RGB of (T - R)^2) in dB (peak 1); +inf if identical.
 *                ssim = mean over pixels of the SSIM map of the tonemapped luminance, Gaussian window
 *                11x11 with sigma 1.5 (Wang et al. 2004), clipped and renormalised at the borders,
 *                C1 = 0.01^2, C2 = 0.03^2 (dynamic range L = 1). Exactly 1 for identical images.
 */
#ifndef GK_METRICS_H
#define GK_METRICS_H

#include "base/err.h"
#include "../io/image_io.h"

typedef struct gk_metrics {
    double rel_rmse, rel_mse, rmse, psnr, ssim, mean_ratio, max_error;
    int max_error_at[2];         /* [x, y] */
    double exposure;             /* the exposure used for psnr and ssim */
    double ref_mean, test_mean;  /* means over RGB (of the selected pixels when masked) */
    long pixels;                 /* pixels that entered the metrics */
    long nonfinite;              /* NaN/inf values in the test image's colour channels (selected pixels) */
} gk_metrics;

/* Colour channels of an image (see above): 3 for RGB(A), 1 for grey(+alpha). */
int gk_image_color_channels(const gk_image *img);
/* Mean over every pixel and colour channel. 0 for an empty image. */
double gk_image_mean(const gk_image *img);
/* Mean Rec. 709 luminance (grey value for 1-2 channel images). */
double gk_image_luminance_mean(const gk_image *img);
/* The auto exposure of the metrics: 0.18 / mean luminance, 1 when that mean is <= 0 or not finite. */
double gk_metrics_auto_exposure(const gk_image *ref);
/* dst = gk_tonemap(exposure * src) on colour channels; alpha copied. dst is allocated here. */
int gk_image_tonemap(const gk_image *src, double exposure, gk_image *dst, gk_err *e);
/* Luminance plane (width * height floats, malloc'd) of an image; NULL when out of memory. */
float *gk_image_luminance_plane(const gk_image *img);

/* Checks that two images can be compared: same width, height and channels, else GK_EINPUT
 * "size mismatch: reference is WxH with C channels, test is WxH with C channels". */
int gk_metrics_check_same_shape(const gk_image *ref, const gk_image *test, gk_err *e);

/* All metrics over the whole image. exposure <= 0 (or NaN) means the auto exposure above. */
int gk_metrics_compute(const gk_image *ref, const gk_image *test, double exposure, gk_metrics *m, gk_err *e);
/* The same metrics restricted to the pixels whose mask byte is non-zero (mask: width * height bytes,
 * row-major, top row first). SSIM is the mean of the full-image SSIM map over the selected pixels
 * (windows still see their whole neighbourhood); the auto exposure comes from the whole reference,
 * so the tonemap is the one the full image gets. An empty selection is a GK_EINPUT error. */
int gk_metrics_compute_masked(const gk_image *ref, const gk_image *test, double exposure,
                              const unsigned char *mask, gk_metrics *m, gk_err *e);

/* Masks (width * height bytes, malloc'd; free with free()). NULL when out of memory. */
typedef int (*gk_pixel_predicate)(int x, int y, void *ctx);
unsigned char *gk_mask_from_predicate(int width, int height, gk_pixel_predicate pred, void *ctx);
/* xy holds n pairs (x0, y0, x1, y1, ...); pairs outside the image are ignored. */
unsigned char *gk_mask_from_pixels(int width, int height, const int *xy, int n);
/* Pixels with x0 <= x < x1 and y0 <= y < y1 (clipped to the image). */
unsigned char *gk_mask_from_rect(int width, int height, int x0, int y0, int x1, int y1);

/* The caustic mask of a reference: pixels whose luminance exceeds fraction x the image's peak
 * luminance (issue 14 uses fraction 1/4); the peak goes to *peak (optional). Empty for a black image. */
unsigned char *gk_mask_above_peak(const gk_image *img, double fraction, float *peak);
/* A mask read back from a mask image (e.g. the PNG `gikiosk reference --caustic-mask` writes):
 * pixels where any colour channel is >= 0.5 (PNG: >= 128 of 255). */
unsigned char *gk_mask_from_image(const gk_image *img);
/* Non-zero bytes of a width x height mask. */
long gk_mask_count(const unsigned char *mask, int width, int height);

/* SSIM of two single-channel planes with values in [0, 1] (see above); map (optional, width *
 * height) receives the per-pixel SSIM. mask (optional) selects the pixels averaged. Returns the
 * mean, or NaN when out of memory or the mask is empty. */
double gk_ssim_plane(const float *a, const float *b, int width, int height, const unsigned char *mask, float *map);

/* Temporal stability of a sequence of frames of the same shape (linear or tonemapped, as given):
 *   flicker     = mean over consecutive pairs, pixels and colour channels of |f[k+1] - f[k]|,
 *                 divided by the mean over all frames, pixels and colour channels (0 if no change;
 *                 +inf if change and the mean is 0).
 *   max_flicker = the largest, over pixels, of that pixel's mean |f[k+1] - f[k]| (over pairs and
 *                 colour channels) divided by the same global mean; at max_flicker_at = [x, y].
 * Frames stream in one at a time so long runs need not be kept in memory. */
typedef struct gk_flicker {
    int width, height, channels;
    int frames;
    float *previous;     /* the last frame's colour values */
    double *pixel_diff;  /* per pixel: sum over pairs of the mean |difference| over colour channels */
    double sum_values;   /* over all frames, pixels and colour channels */
} gk_flicker;

typedef struct gk_flicker_result {
    double flicker, max_flicker;
    int max_flicker_at[2];
    int frames;
} gk_flicker_result;

int gk_flicker_begin(gk_flicker *f, int width, int height, int channels, gk_err *e);
/* Adds one frame; a frame of another shape is a GK_EINPUT error naming both shapes. */
int gk_flicker_add(gk_flicker *f, const gk_image *frame, gk_err *e);
/* Needs at least 2 frames (else GK_EINPUT). Does not free. */
int gk_flicker_result_get(const gk_flicker *f, gk_flicker_result *out, gk_err *e);
void gk_flicker_free(gk_flicker *f);
/* All at once for n frames in memory. */
int gk_temporal_flicker(const gk_image *frames, int n, gk_flicker_result *out, gk_err *e);

#endif
