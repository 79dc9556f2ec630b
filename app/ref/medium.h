/* The homogeneous participating medium of the reference path tracer (scene.h, gk_medium): its
 * extent (all space or an axis-aligned box), transmittance, free-flight distance sampling and the
 * Henyey-Greenstein phase function.
 *
 * Conventions (binding for the tracer and the volcaustics shaders alike):
 *   T(a, b) = exp(-sigma_t * |[a, b] inside the medium's extent|), sigma_t = sigma_s + sigma_a (RGB);
 *   p_HG(cos) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^(3/2)), with the 1/(4 pi) the seed's Eq. 2.22
 *   loses (research dong-001.md §14.1); cos is the cosine between the direction light travelled
 *   before the scattering and the direction it travels after (g > 0: forward scattering).
 * Free-flight sampling draws a distance with the pdf sigma exp(-sigma t) of the mean extinction
 * sigma = (sigma_t.r + sigma_t.g + sigma_t.b) / 3 over the part of the ray inside the extent, and
 * returns RGB weights (T sigma_s / pdf for a scattering event, T / P(pass) past the end), so a
 * coloured medium stays unbiased with one distance per path. */
#ifndef GK_REF_MEDIUM_H
#define GK_REF_MEDIUM_H

#include <stdbool.h>

#include "core/vecmath.h"
#include "sample.h"

typedef struct gk_ref_medium {
    bool present;
    vec3 sigma_s, sigma_a, sigma_t;
    float sigma_mean; /* mean of sigma_t over RGB: the free-flight sampling rate */
    float g;
    bool bounded;
    vec3 box_min, box_max;
} gk_ref_medium;

/* The part [*t0, *t1] of the ray o + t d, t in [0, tmax] (tmax may be INFINITY), inside the medium's
 * extent. False when it is empty (or there is no medium). */
bool gk_medium_clip(const gk_ref_medium *m, vec3 o, vec3 d, float tmax, float *t0, float *t1);

/* Transmittance along o + t d, t in [0, dist], d unit. (1, 1, 1) without a medium. */
vec3 gk_medium_transmittance(const gk_ref_medium *m, vec3 o, vec3 d, float dist);

/* Free-flight sampling along o + t d, t in [0, tmax] (see above). Returns true with *t and *weight
 * (T(0, t) sigma_s / pdf) for a scattering event before tmax; false with *weight (T(0, tmax) /
 * P(no event)) when the ray passes. Draws exactly one random number whenever the ray overlaps the
 * medium, none otherwise. */
bool gk_medium_sample_distance(const gk_ref_medium *m, vec3 o, vec3 d, float tmax, gk_rng *rng, float *t,
                               vec3 *weight);

/* Henyey-Greenstein phase function (above), and sampling of the outgoing direction for light
 * travelling along d (pdf = the phase function itself). */
float gk_phase_hg(float g, float cos_theta);
vec3 gk_phase_hg_sample(float g, vec3 d, float u1, float u2);

#endif
