/* The environment as a light of the path tracer: radiance on escape, importance sampling of
 * directions in proportion to luminance x solid angle over the lat-long map (a marginal CDF over
 * rows, a conditional CDF over the columns of each row; piecewise constant inside a pixel, as the
 * map is: environment.h), and the matching solid-angle pdf for multiple importance sampling with
 * BSDF sampling (power heuristic, trace.c). Every pixel with radiance has a non-zero pdf (a floor
 * of 1e-3 of the mean weight keeps dim sky pixels reachable by light sampling too, so MIS sees both
 * strategies everywhere). */
#ifndef GK_REF_ENV_H
#define GK_REF_ENV_H

#include <stdbool.h>

#include "scene/scene.h"

typedef struct gk_ref_env {
    const gk_environment *env; /* borrowed from the gk_scene; NULL: no environment */
    float *row_cdf;            /* height + 1 */
    float *col_cdf;            /* height * (width + 1), each row's own, unnormalised */
    float total;               /* sum of the pixel weights */
    float flux_density;        /* ∫ luminance(L) dω over the sphere (lux through a surface facing
                                  everything: for choosing this light in proportion to power) */
} gk_ref_env;

/* Builds the CDFs; 0, or -1 out of memory. Without an environment re->env stays NULL. */
int gk_ref_env_build(gk_ref_env *re, const gk_environment *env);
void gk_ref_env_free(gk_ref_env *re);

/* A direction towards the environment from two uniforms: its radiance and solid-angle pdf. */
bool gk_ref_env_sample(const gk_ref_env *re, float u1, float u2, vec3 *wi, vec3 *radiance, float *pdf);
/* The solid-angle pdf of gk_ref_env_sample for direction d. */
float gk_ref_env_pdf(const gk_ref_env *re, vec3 d);

#endif
