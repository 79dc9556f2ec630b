/* Random numbers and warping for the reference path tracer.
 *
 * Every random decision is drawn from a PCG32 stream seeded by hashing (seed, pixel or light-path
 * index, sample index, pass): a pixel's samples never depend on which thread renders them or in
 * which order tiles are taken, so a render is bit-identical for a seed whatever the thread count. */
#ifndef GK_REF_SAMPLE_H
#define GK_REF_SAMPLE_H

#include <stdint.h>

#include "core/vecmath.h"

#define GK_PI 3.14159265358979323846f

typedef struct gk_rng {
    uint64_t state, inc;
} gk_rng;

/* Seeds a stream from a render seed and up to three stream coordinates (pixel, sample, pass). */
void gk_rng_seed(gk_rng *r, uint64_t seed, uint64_t a, uint64_t b, uint64_t c);

static inline uint32_t gk_rng_u32(gk_rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
}

/* Uniform in [0, 1) with 24 bits, never 1.0f. */
static inline float gk_rng_float(gk_rng *r) { return (float)(gk_rng_u32(r) >> 8) * (1.0f / 16777216.0f); }

/* Orthonormal basis around a unit normal (Duff et al. 2017). */
void gk_onb(vec3 n, vec3 *t, vec3 *b);
static inline vec3 gk_to_world(vec3 l, vec3 t, vec3 b, vec3 n)
{
    return v3(t.x * l.x + b.x * l.y + n.x * l.z, t.y * l.x + b.y * l.y + n.y * l.z, t.z * l.x + b.z * l.y + n.z * l.z);
}
static inline vec3 gk_to_local(vec3 w, vec3 t, vec3 b, vec3 n) { return v3(v3_dot(w, t), v3_dot(w, b), v3_dot(w, n)); }

vec3 gk_sample_cosine_hemisphere(float u1, float u2);  /* local frame, z up; pdf cos/pi */
vec3 gk_sample_uniform_sphere(float u1, float u2);     /* pdf 1/(4 pi) */
vec3 gk_sample_uniform_cone(float u1, float u2, float cos_max); /* around +z; pdf 1/(2 pi (1-cos_max)) */
void gk_sample_uniform_disc(float u1, float u2, float *x, float *y); /* unit disc, uniform by area */
void gk_sample_triangle(float u1, float u2, float *b1, float *b2);  /* barycentrics, uniform by area */

static inline float gk_power_heuristic(float pa, float pb)
{
    float a = pa * pa, b = pb * pb;
    return a + b > 0.0f ? a / (a + b) : 0.0f;
}

#endif
