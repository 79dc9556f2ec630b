/* Linearly transformed cosines for the GGX lobe of app/core/brdf_spec.md (Heitz et al. 2016),
 * fitted by tools/ltc_fit.c (`make ltc` regenerates ltc_table.c; nothing is downloaded).
 * GK_LTC_N x GK_LTC_N cells, row t (theta) major: cell (t, a) at index t * GK_LTC_N + a, with
 * a = roughness * (N - 1) (alpha = max(roughness^2, 0.0025)) and t = sqrt(1 - cos(theta_v)) * (N - 1).
 *   gk_ltc_minv[4 * cell]: m0 m1 m2 m3, the inverse transform Minv = [[m0, 0, m1], [0, 1, 0],
 *                          [m2, 0, m3]] (rows) in the frame x = view projected on the tangent
 *                          plane, y = n x x, z = n (scaled: only directions matter);
 *   gk_ltc_amp[2 * cell]:  A = integral of D V cos (F = 1), B = integral of (1 - v.h)^5 D V cos:
 *                          specular = L (F0 A + (F90 - F0) B) * E(Minv polygon) / pi, E the clamped
 *                          cosine integral (the Lambert polygon irradiance per unit radiance). */
#ifndef GK_LTC_TABLE_H
#define GK_LTC_TABLE_H

#define GK_LTC_N 64

extern const float gk_ltc_minv[GK_LTC_N * GK_LTC_N * 4];
extern const float gk_ltc_amp[GK_LTC_N * GK_LTC_N * 2];

#endif
