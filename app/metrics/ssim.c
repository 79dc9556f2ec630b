/* SSIM (Wang, Bovik, Sheikh, Simoncelli 2004) with the standard 11x11 Gaussian window, sigma 1.5.
 * The window is separable; at the borders it is clipped to the image and renormalised, so every
 * pixel gets a value and small (64x64) test images need no padding convention. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "metrics/metrics.h"

enum { RADIUS = 5 };
static const double C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;

/* One pass of the clipped, renormalised 1D Gaussian along x (stride 1) or y (stride width). */
static void blur_1d(const double *in, double *out, int width, int height, int along_y, const double *g)
{
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            int pos = along_y ? y : x, len = along_y ? height : width;
            size_t step = along_y ? (size_t)width : 1, centre = (size_t)y * width + x;
            double sum = 0.0, weight = 0.0;
            for (int k = -RADIUS; k <= RADIUS; k++) {
                if (pos + k < 0 || pos + k >= len)
                    continue;
                sum += g[k + RADIUS] * in[centre + (ptrdiff_t)k * (ptrdiff_t)step];
                weight += g[k + RADIUS];
            }
            out[centre] = sum / weight;
        }
}

static void blur(double *plane, double *tmp, int width, int height, const double *g)
{
    blur_1d(plane, tmp, width, height, 0, g);
    blur_1d(tmp, plane, width, height, 1, g);
}

double gk_ssim_plane(const float *a, const float *b, int width, int height, const unsigned char *mask, float *map)
{
    size_t n = (size_t)width * height;
    if (n == 0)
        return NAN;
    double g[2 * RADIUS + 1];
    for (int k = -RADIUS; k <= RADIUS; k++)
        g[k + RADIUS] = exp(-(double)(k * k) / (2.0 * 1.5 * 1.5));

    /* Moments: mean a, mean b, mean a^2, mean b^2, mean ab, then a scratch plane. */
    double *buf = malloc(6 * n * sizeof *buf);
    if (!buf)
        return NAN;
    double *ma = buf, *mb = buf + n, *maa = buf + 2 * n, *mbb = buf + 3 * n, *mab = buf + 4 * n, *tmp = buf + 5 * n;
    for (size_t p = 0; p < n; p++) {
        ma[p] = a[p];
        mb[p] = b[p];
        maa[p] = (double)a[p] * a[p];
        mbb[p] = (double)b[p] * b[p];
        mab[p] = (double)a[p] * b[p];
    }
    for (int i = 0; i < 5; i++)
        blur(buf + i * n, tmp, width, height, g);

    double sum = 0.0;
    size_t count = 0;
    for (size_t p = 0; p < n; p++) {
        double var_a = maa[p] - ma[p] * ma[p], var_b = mbb[p] - mb[p] * mb[p], cov = mab[p] - ma[p] * mb[p];
        double s = ((2.0 * ma[p] * mb[p] + C1) * (2.0 * cov + C2)) /
                   ((ma[p] * ma[p] + mb[p] * mb[p] + C1) * (var_a + var_b + C2));
        if (map)
            map[p] = (float)s;
        if (mask && !mask[p])
            continue;
        sum += s;
        count++;
    }
    free(buf);
    return count ? sum / (double)count : NAN;
}
