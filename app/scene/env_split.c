/* The thesis's greedy split of an environment into area lights (env_split.h). */
#include "env_split.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "core/tonemap.h"
#include "environment.h"

void gk_sh9_basis(vec3 n, float y[9])
{
    y[0] = 0.282095f;
    y[1] = 0.488603f * n.y;
    y[2] = 0.488603f * n.z;
    y[3] = 0.488603f * n.x;
    y[4] = 1.092548f * n.x * n.y;
    y[5] = 1.092548f * n.y * n.z;
    y[6] = 0.315392f * (3.0f * n.z * n.z - 1.0f);
    y[7] = 1.092548f * n.x * n.z;
    y[8] = 0.546274f * (n.x * n.x - n.y * n.y);
}

vec3 gk_sh9_irradiance(const float c[9][3], vec3 n)
{
    float y[9];
    gk_sh9_basis(n, y);
    float e[3] = {0, 0, 0};
    for (int i = 0; i < 9; i++)
        for (int k = 0; k < 3; k++)
            e[k] += c[i][k] * y[i];
    return v3(e[0], e[1], e[2]);
}

/* Radiance-to-irradiance factors per SH band (the clamped cosine's coefficients). */
static const float kBand[9] = {3.14159265f, 2.0943951f, 2.0943951f, 2.0943951f, 0.78539816f,
                               0.78539816f, 0.78539816f, 0.78539816f, 0.78539816f};

typedef struct split_map {
    int w, h;
    float *res;      /* residual radiance, w * h * 3 */
    float *omega;    /* solid angle per row */
    float mean[3];   /* mean radiance of the residual map before the current light */
} split_map;

static float *px(const split_map *m, int i, int j) { return m->res + 3 * ((size_t)j * (size_t)m->w + (size_t)i); }

/* Direction through the centre of pixel (i, j). */
static vec3 pixel_dir(const split_map *m, int i, int j)
{
    return gk_env_dir((i + 0.5f) / (float)m->w, (j + 0.5f) / (float)m->h);
}

/* Excess over the mean, per channel, of one pixel (radiance). */
static void excess(const split_map *m, int i, int j, float out[3])
{
    const float *p = px(m, ((i % m->w) + m->w) % m->w, j);
    for (int c = 0; c < 3; c++)
        out[c] = p[c] > m->mean[c] ? p[c] - m->mean[c] : 0.0f;
}

static float excess_energy(const split_map *m, int i, int j)
{
    float x[3];
    excess(m, i, j, x);
    return gk_luminance(x[0], x[1], x[2]) * m->omega[j];
}

/* Energy of the columns i0..i0+wi-1 (wrapping) x rows j0..j1. */
static double rect_energy(const split_map *m, int i0, int wi, int j0, int j1)
{
    double e = 0;
    for (int j = j0; j <= j1; j++)
        for (int k = 0; k < wi; k++)
            e += excess_energy(m, i0 + k, j);
    return e;
}

/* The SH projection of a radiance region (excess or whole map) added into c with the given sign,
   as irradiance coefficients. */
static void sh_add(const split_map *m, int i, int j, const float rad[3], float sign, float c[9][3])
{
    float y[9];
    gk_sh9_basis(pixel_dir(m, i, j), y);
    float w = sign * m->omega[j];
    for (int b = 0; b < 9; b++)
        for (int k = 0; k < 3; k++)
            c[b][k] += kBand[b] * y[b] * rad[k] * w;
}

static quat rotation_from_minus_z(vec3 dir)
{
    float d = -dir.z; /* dot((0, 0, -1), dir) */
    if (d < -0.9999f)
        return (quat){0, 1, 0, 0};
    vec3 axis = v3_cross(v3(0, 0, -1), dir);
    return q_normalize((quat){axis.x, axis.y, axis.z, 1.0f + d});
}

/* Greedy growth of the light seeded at (si, sj); returns its rectangle. */
static void grow(const split_map *m, int si, int sj, int *i0, int *wi, int *j0, int *j1)
{
    *i0 = si, *wi = 1, *j0 = sj, *j1 = sj;
    int max_w = m->w / 4, max_h = m->h / 4;
    double total = rect_energy(m, *i0, *wi, *j0, *j1);
    for (bool grew = true; grew;) {
        grew = false;
        for (int side = 0; side < 4; side++) {
            double strip;
            if (side < 2) { /* left, right */
                if (*wi >= max_w)
                    continue;
                strip = rect_energy(m, side == 0 ? *i0 - 1 : *i0 + *wi, 1, *j0, *j1);
            } else { /* up, down */
                if (*j1 - *j0 + 1 >= max_h || (side == 2 ? *j0 == 0 : *j1 == m->h - 1))
                    continue;
                int row = side == 2 ? *j0 - 1 : *j1 + 1;
                strip = rect_energy(m, *i0, *wi, row, row);
            }
            if (!(strip > 0.0) || strip / (total + strip) <= GK_ENV_SPLIT_T)
                continue;
            total += strip;
            grew = true;
            if (side == 0)
                *i0 = (*i0 - 1 + m->w) % m->w, (*wi)++;
            else if (side == 1)
                (*wi)++;
            else if (side == 2)
                (*j0)--;
            else
                (*j1)++;
        }
    }
}

static int append_light(gk_scene *s, int k, vec3 to_light, float omega, const double phi[3], gk_err *e)
{
    gk_light *lights = realloc(s->lights, (size_t)(s->n_lights + 2) * sizeof *lights);
    if (!lights)
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory splitting the environment", s->path);
    s->lights = lights;
    gk_node *nodes = realloc(s->nodes, (size_t)(s->n_nodes + 2) * sizeof *nodes);
    if (!nodes)
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory splitting the environment", s->path);
    s->nodes = nodes;
    gk_light *l = &s->lights[s->n_lights];
    memset(l, 0, sizeof *l);
    snprintf(l->name, sizeof l->name, "environment %d", k);
    l->type = GK_LIGHT_DIRECTIONAL;
    l->shape = GK_SHAPE_DISC;
    float c = 1.0f - omega / (2.0f * (float)M_PI);
    l->radius = acosf(c < -1.0f ? -1.0f : c);
    double peak = fmax(phi[0], fmax(phi[1], phi[2]));
    l->intensity = (float)peak;
    for (int ch = 0; ch < 3; ch++)
        l->color[ch] = peak > 0 ? (float)(phi[ch] / peak) : 0.0f;
    l->env_part = true;
    gk_node *n = &s->nodes[s->n_nodes];
    memset(n, 0, sizeof *n);
    snprintf(n->name, sizeof n->name, "environment %d", k);
    n->parent = -1;
    n->rotation = rotation_from_minus_z(v3_scale(to_light, -1.0f));
    n->scale = v3(1, 1, 1);
    n->light = s->n_lights;
    n->camera = -1;
    n->mesh_count = 0;
    s->n_lights++;
    s->n_nodes++;
    return 0;
}

int gk_env_split(gk_scene *s, int max_lights, gk_err *e)
{
    gk_environment *env = &s->environment;
    if (!env->present || !env->rgb)
        return 0;
    if (max_lights > GK_ENV_MAX_LIGHTS)
        max_lights = GK_ENV_MAX_LIGHTS;
    split_map m = {.w = env->width, .h = env->height};
    size_t n = (size_t)m.w * (size_t)m.h;
    m.res = malloc(n * 3 * sizeof *m.res);
    m.omega = malloc((size_t)m.h * sizeof *m.omega);
    env->ambient_sh = calloc((size_t)max_lights + 1, sizeof *env->ambient_sh);
    if (!m.res || !m.omega || !env->ambient_sh) {
        free(m.res), free(m.omega);
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory splitting the environment", s->path);
    }
    memcpy(m.res, env->rgb, n * 3 * sizeof *m.res);
    double sum[3] = {0, 0, 0};
    for (int j = 0; j < m.h; j++) {
        m.omega[j] = gk_env_pixel_solid_angle(env, j);
        for (int i = 0; i < m.w; i++) {
            for (int c = 0; c < 3; c++)
                sum[c] += (double)px(&m, i, j)[c] * m.omega[j];
            sh_add(&m, i, j, px(&m, i, j), 1.0f, env->ambient_sh[0]);
        }
    }
    env->env_light_first = s->n_lights;
    env->n_env_lights = 0;
    int rc = 0;
    for (int k = 0; k < max_lights && rc == 0; k++) {
        /* the average the residual holds now: each light lowers it, so later lights reach further
           down into the map (the sky's gradient once the panels are out) */
        for (int c = 0; c < 3; c++)
            m.mean[c] = (float)(sum[c] / (4.0 * M_PI));
        int si = 0, sj = 0;
        float best = 0.0f;
        for (int j = 0; j < m.h; j++)
            for (int i = 0; i < m.w; i++) {
                float en = excess_energy(&m, i, j);
                if (en > best)
                    best = en, si = i, sj = j;
            }
        if (!(best > 0.0f))
            break; /* the residual is the mean everywhere: nothing left to light with a shadow */
        int i0, wi, j0, j1;
        grow(&m, si, sj, &i0, &wi, &j0, &j1);
        double phi[3] = {0, 0, 0}, omega = 0;
        vec3 centroid = v3(0, 0, 0);
        memcpy(env->ambient_sh[k + 1], env->ambient_sh[k], sizeof env->ambient_sh[k]);
        for (int j = j0; j <= j1; j++)
            for (int q = 0; q < wi; q++) {
                int i = (i0 + q) % m.w;
                float x[3];
                excess(&m, i, j, x);
                float lum = gk_luminance(x[0], x[1], x[2]) * m.omega[j];
                centroid = v3_add(centroid, v3_scale(pixel_dir(&m, i, j), lum));
                for (int c = 0; c < 3; c++)
                    phi[c] += (double)x[c] * m.omega[j];
                omega += m.omega[j];
                sh_add(&m, i, j, x, -1.0f, env->ambient_sh[k + 1]);
                float *p = px(&m, i, j);
                for (int c = 0; c < 3; c++) {
                    p[c] -= x[c]; /* the light takes the excess, the mean stays */
                    sum[c] -= (double)x[c] * m.omega[j];
                }
            }
        rc = append_light(s, k, v3_norm(centroid), (float)omega, phi, e);
        if (rc == 0)
            env->n_env_lights++;
    }
    free(m.res), free(m.omega);
    return rc;
}
