/* PCG32 seeding by hashing and the warps of sample.h. */
#include "sample.h"

#include <math.h>

static uint64_t splitmix64(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

void gk_rng_seed(gk_rng *r, uint64_t seed, uint64_t a, uint64_t b, uint64_t c)
{
    uint64_t h = splitmix64(seed);
    h = splitmix64(h ^ a);
    h = splitmix64(h ^ b);
    h = splitmix64(h ^ c);
    r->state = 0;
    r->inc = (splitmix64(h ^ 0xA5A5A5A5ULL) << 1u) | 1u;
    gk_rng_u32(r);
    r->state += h;
    gk_rng_u32(r);
}

void gk_onb(vec3 n, vec3 *t, vec3 *b)
{
    float sign = copysignf(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float bb = n.x * n.y * a;
    *t = v3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x);
    *b = v3(bb, sign + n.y * n.y * a, -n.y);
}

vec3 gk_sample_cosine_hemisphere(float u1, float u2)
{
    float r = sqrtf(u1), phi = 2.0f * GK_PI * u2;
    return v3(r * cosf(phi), r * sinf(phi), sqrtf(fmaxf(0.0f, 1.0f - u1)));
}

vec3 gk_sample_uniform_sphere(float u1, float u2)
{
    float z = 1.0f - 2.0f * u1, r = sqrtf(fmaxf(0.0f, 1.0f - z * z)), phi = 2.0f * GK_PI * u2;
    return v3(r * cosf(phi), r * sinf(phi), z);
}

vec3 gk_sample_uniform_cone(float u1, float u2, float cos_max)
{
    float z = 1.0f - u1 * (1.0f - cos_max), r = sqrtf(fmaxf(0.0f, 1.0f - z * z)), phi = 2.0f * GK_PI * u2;
    return v3(r * cosf(phi), r * sinf(phi), z);
}

void gk_sample_uniform_disc(float u1, float u2, float *x, float *y)
{
    float r = sqrtf(u1), phi = 2.0f * GK_PI * u2;
    *x = r * cosf(phi);
    *y = r * sinf(phi);
}

void gk_sample_triangle(float u1, float u2, float *b1, float *b2)
{
    float su = sqrtf(u1);
    *b1 = 1.0f - su;
    *b2 = u2 * su;
}
