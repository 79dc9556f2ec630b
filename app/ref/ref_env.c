/* Environment importance sampling for the path tracer (ref_env.h). */
#include "ref_env.h"

#include <math.h>
#include <stdlib.h>

#include "core/tonemap.h"
#include "scene/environment.h"

/* Pixel weight: luminance x solid angle, floored (see the header) once the mean is known. */
static float raw_weight(const gk_environment *env, int i, int j)
{
    const float *p = env->rgb + 3 * ((size_t)j * (size_t)env->width + (size_t)i);
    return gk_luminance(p[0], p[1], p[2]) * gk_env_pixel_solid_angle(env, j);
}

int gk_ref_env_build(gk_ref_env *re, const gk_environment *env)
{
    re->env = NULL;
    re->row_cdf = re->col_cdf = NULL;
    re->total = re->flux_density = 0.0f;
    if (!env || !env->present || !env->rgb)
        return 0;
    int w = env->width, h = env->height;
    re->row_cdf = malloc(sizeof(float) * (size_t)(h + 1));
    re->col_cdf = malloc(sizeof(float) * (size_t)h * (size_t)(w + 1));
    if (!re->row_cdf || !re->col_cdf) {
        gk_ref_env_free(re);
        return -1;
    }
    double sum = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            sum += raw_weight(env, i, j);
    re->flux_density = (float)sum;
    float floor_lum = (float)(1e-3 * sum / (4.0 * M_PI)); /* 1e-3 of the mean luminance */
    re->row_cdf[0] = 0.0f;
    double rows = 0;
    for (int j = 0; j < h; j++) {
        float *c = re->col_cdf + (size_t)j * (size_t)(w + 1);
        double acc = 0;
        c[0] = 0.0f;
        for (int i = 0; i < w; i++) {
            float x = raw_weight(env, i, j);
            acc += fmaxf(x, floor_lum * gk_env_pixel_solid_angle(env, j));
            c[i + 1] = (float)acc;
        }
        rows += acc;
        re->row_cdf[j + 1] = (float)rows;
    }
    re->total = (float)rows;
    re->env = env;
    return re->total > 0.0f ? 0 : (re->env = NULL, 0);
}

void gk_ref_env_free(gk_ref_env *re)
{
    free(re->row_cdf);
    free(re->col_cdf);
    re->row_cdf = re->col_cdf = NULL;
    re->env = NULL;
}

/* Index k with cdf[k] <= x < cdf[k + 1], skipping empty cells. */
static int find(const float *cdf, int n, float x)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (cdf[mid + 1] <= x)
            lo = mid + 1;
        else
            hi = mid;
    }
    while (lo < n - 1 && cdf[lo + 1] - cdf[lo] <= 0.0f)
        lo++;
    return lo;
}

static float pixel_pdf(const gk_ref_env *re, int i, int j)
{
    const gk_environment *env = re->env;
    const float *c = re->col_cdf + (size_t)j * (size_t)(env->width + 1);
    float p = (c[i + 1] - c[i]) / re->total;      /* probability of the pixel */
    return p / gk_env_pixel_solid_angle(env, j);  /* uniform in solid angle inside it */
}

bool gk_ref_env_sample(const gk_ref_env *re, float u1, float u2, vec3 *wi, vec3 *radiance, float *pdf)
{
    if (!re->env)
        return false;
    const gk_environment *env = re->env;
    int w = env->width, h = env->height;
    int j = find(re->row_cdf, h, u1 * re->total);
    const float *c = re->col_cdf + (size_t)j * (size_t)(w + 1);
    float row_w = c[w];
    if (!(row_w > 0.0f))
        return false;
    /* u2 picks the column; the remainders of u1 and u2 inside their cells place the point in the
       pixel, uniform in solid angle (cos theta uniform across the row's band) */
    float xr = u2 * row_w;
    int i = find(c, w, xr);
    float cell = c[i + 1] - c[i];
    float fu = cell > 0.0f ? (xr - c[i]) / cell : 0.5f;
    float row_lo = re->row_cdf[j], row_span = re->row_cdf[j + 1] - row_lo;
    float fv = row_span > 0.0f ? (u1 * re->total - row_lo) / row_span : 0.5f;
    fu = fu < 0.0f ? 0.0f : (fu > 1.0f ? 1.0f : fu);
    fv = fv < 0.0f ? 0.0f : (fv > 1.0f ? 1.0f : fv);
    double t0 = M_PI * j / h, t1 = M_PI * (j + 1) / h;
    double ct = cos(t0) + fv * (cos(t1) - cos(t0));
    float theta = (float)acos(ct < -1 ? -1 : (ct > 1 ? 1 : ct));
    float u = ((float)i + fu) / (float)w;
    *wi = gk_env_dir(u, theta / (float)M_PI);
    const float *p = env->rgb + 3 * ((size_t)j * (size_t)w + (size_t)i); /* the pixel whose pdf this is */
    *radiance = v3(p[0], p[1], p[2]);
    *pdf = pixel_pdf(re, i, j);
    return *pdf > 0.0f;
}

float gk_ref_env_pdf(const gk_ref_env *re, vec3 d)
{
    if (!re->env)
        return 0.0f;
    int i, j;
    gk_env_pixel(re->env, d, &i, &j);
    return pixel_pdf(re, i, j);
}
