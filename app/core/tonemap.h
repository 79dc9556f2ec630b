/* The display transform, shared by the renderer's compose shader (shaders_gles/common/tonemap.glsl
 * mirrors it) and the metrics (SSIM/PSNR are computed on tonemapped images):
 *   display = srgb_oetf(aces_fitted(exposure * linear))
 * with Narkowicz's ACES fit. Linear HDR captures are taken before exposure. Exposure is a scale
 * factor: a scene's extras may give "exposure" (EV, 2^EV), else the key 0.18 / mean luminance. */
#ifndef GK_TONEMAP_H
#define GK_TONEMAP_H

#include <math.h>

static inline float gk_aces_fitted(float x)
{
    const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
    float y = (x * (a * x + b)) / (x * (c * x + d) + e);
    return y < 0.0f ? 0.0f : (y > 1.0f ? 1.0f : y);
}

static inline float gk_srgb_oetf(float x)
{
    x = x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
}

static inline float gk_srgb_to_linear(float x)
{
    return x <= 0.04045f ? x / 12.92f : powf((x + 0.055f) / 1.055f, 2.4f);
}

static inline float gk_tonemap(float linear, float exposure) { return gk_srgb_oetf(gk_aces_fitted(linear * exposure)); }

static inline float gk_luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

#endif
