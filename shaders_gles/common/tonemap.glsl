// The display transform, mirroring app/core/tonemap.h exactly:
// display = srgb_oetf(aces_fitted(exposure * linear)), Narkowicz's ACES fit.
highp vec3 gk_aces_fitted(highp vec3 x)
{
    const highp float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

highp vec3 gk_srgb_oetf(highp vec3 x)
{
    x = clamp(x, 0.0, 1.0);
    highp vec3 lo = 12.92 * x;
    highp vec3 hi = 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, lo, vec3(lessThanEqual(x, vec3(0.0031308))));
}

highp vec3 gk_tonemap(highp vec3 linear, highp float exposure) { return gk_srgb_oetf(gk_aces_fitted(linear * exposure)); }
