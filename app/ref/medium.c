/* The reference tracer's homogeneous medium (see medium.h). */
#include "medium.h"

#include <math.h>

bool gk_medium_clip(const gk_ref_medium *m, vec3 o, vec3 d, float tmax, float *t0, float *t1)
{
    if (!m->present)
        return false;
    float lo = 0.0f, hi = tmax;
    if (m->bounded) {
        const float os[3] = {o.x, o.y, o.z}, ds[3] = {d.x, d.y, d.z};
        const float bmin[3] = {m->box_min.x, m->box_min.y, m->box_min.z};
        const float bmax[3] = {m->box_max.x, m->box_max.y, m->box_max.z};
        for (int a = 0; a < 3; a++) {
            if (ds[a] == 0.0f) {
                if (os[a] < bmin[a] || os[a] > bmax[a])
                    return false;
                continue;
            }
            float inv = 1.0f / ds[a];
            float ta = (bmin[a] - os[a]) * inv, tb = (bmax[a] - os[a]) * inv;
            if (ta > tb) {
                float s = ta;
                ta = tb;
                tb = s;
            }
            lo = fmaxf(lo, ta);
            hi = fminf(hi, tb);
        }
    }
    if (!(hi > lo))
        return false;
    *t0 = lo;
    *t1 = hi;
    return true;
}

static vec3 v3_exp_neg(vec3 s, float len)
{
    return v3(expf(-s.x * len), expf(-s.y * len), expf(-s.z * len));
}

vec3 gk_medium_transmittance(const gk_ref_medium *m, vec3 o, vec3 d, float dist)
{
    float t0, t1;
    if (!gk_medium_clip(m, o, d, dist, &t0, &t1))
        return v3(1, 1, 1);
    return v3_exp_neg(m->sigma_t, t1 - t0);
}

bool gk_medium_sample_distance(const gk_ref_medium *m, vec3 o, vec3 d, float tmax, gk_rng *rng, float *t,
                               vec3 *weight)
{
    float t0, t1;
    *weight = v3(1, 1, 1);
    if (!gk_medium_clip(m, o, d, tmax, &t0, &t1))
        return false;
    float u = gk_rng_float(rng);
    float sm = m->sigma_mean;
    if (sm <= 0.0f) /* a medium of zero extinction changes nothing */
        return false;
    /* Inverse CDF of sigma exp(-sigma s) on s >= 0; s past the overlap = no event. */
    float s = -logf(1.0f - u) / sm;
    if (s < t1 - t0) {
        vec3 tr = v3_exp_neg(m->sigma_t, s);
        float pdf = sm * expf(-sm * s);
        *t = t0 + s;
        *weight = v3_scale(v3_mul(tr, m->sigma_s), 1.0f / pdf);
        return true;
    }
    float len = t1 - t0; /* INFINITY when the ray leaves an unbounded medium: weight 0 */
    if (isinf(len)) {
        *weight = v3(0, 0, 0);
        return false;
    }
    *weight = v3_scale(v3_exp_neg(m->sigma_t, len), 1.0f / expf(-sm * len));
    return false;
}

float gk_phase_hg(float g, float cos_theta)
{
    float g2 = g * g;
    float den = 1.0f + g2 - 2.0f * g * cos_theta;
    return (1.0f - g2) / (4.0f * GK_PI * den * sqrtf(den));
}

vec3 gk_phase_hg_sample(float g, vec3 d, float u1, float u2)
{
    float cos_t;
    if (fabsf(g) < 1e-3f) {
        cos_t = 1.0f - 2.0f * u1;
    } else {
        /* Inverse CDF of HG in cos (Pharr et al., PBRT 3 §15.2.3, with cos measured from the
           propagation direction, so g > 0 favours cos near 1). */
        float sq = (1.0f - g * g) / (1.0f + g - 2.0f * g * u1);
        cos_t = (1.0f + g * g - sq * sq) / (2.0f * g);
    }
    cos_t = fmaxf(-1.0f, fminf(1.0f, cos_t));
    float sin_t = sqrtf(fmaxf(0.0f, 1.0f - cos_t * cos_t)), phi = 2.0f * GK_PI * u2;
    vec3 tx, ty;
    gk_onb(d, &tx, &ty);
    return gk_to_world(v3(sin_t * cosf(phi), sin_t * sinf(phi), cos_t), tx, ty, d);
}
