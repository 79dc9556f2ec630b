/* Caustic photons: generators, cones, Halton directions, progressive retracing (lm_caustics.h). */
#include "lm_caustics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lm_photons.h"
#include "ref/lights.h"
#include "ref/materials.h"
#include "ref/sample.h"
#include "ref/trace.h"

/* The caustic photons' random streams (a dielectric's reflect/refract choice): any fixed number,
   other than the indirect photons' so the two sets are unrelated. */
#define LM_CAUSTIC_SEED 0x636175737469ULL
#define LM_CAUSTIC_MAX_BOUNCES 8

float lm_caustic_weight(int i, int j)
{
    return sqrtf((float)(1 + 2 * LM_CAUSTIC_K * LM_CAUSTIC_K - (i * i + j * j)));
}

/* A triangle whose surface has no non-delta lobe at its centre: a caustic generator. */
static bool is_generator(const gk_ref_scene *rs, uint32_t t)
{
    gk_surface sf;
    gk_surface_init(&sf, rs, &rs->tris[t], 1.0f / 3.0f, 1.0f / 3.0f);
    return !gk_surface_has_smooth_part(&sf);
}

/* The generators' bounding sphere: centre of their box, radius to the farthest vertex. */
static uint32_t generator_sphere(const gk_ref_scene *rs, vec3 *centre, float *radius)
{
    vec3 lo = v3(INFINITY, INFINITY, INFINITY), hi = v3(-INFINITY, -INFINITY, -INFINITY);
    uint32_t generators = 0;
    for (uint32_t t = 0; t < rs->n_tris; t++) {
        if (!is_generator(rs, t))
            continue;
        generators++;
        for (int k = 0; k < 3; k++)
            lo = v3_min(lo, rs->tris[t].p[k]), hi = v3_max(hi, rs->tris[t].p[k]);
    }
    *centre = v3_scale(v3_add(lo, hi), 0.5f);
    *radius = 0.0f;
    for (uint32_t t = 0; generators > 0 && t < rs->n_tris; t++)
        if (is_generator(rs, t))
            for (int k = 0; k < 3; k++)
                *radius = fmaxf(*radius, v3_len(v3_sub(rs->tris[t].p[k], *centre)));
    return generators;
}

static bool caustic_light(const gk_ref_light *L)
{
    return L->kind == GK_REF_POINT || L->kind == GK_REF_SPOT;
}

void lm_caustics_aim(lm_caustics *c, const gk_ref_scene *rs)
{
    vec3 centre;
    float radius;
    generator_sphere(rs, &centre, &radius);
    for (int i = 0; i < c->n_lights; i++) {
        lm_caustic_light *cl = &c->lights[i];
        const gk_ref_light *L = &rs->lights[cl->light];
        vec3 to = v3_sub(centre, L->pos);
        float d = v3_len(to);
        if (d <= radius * 1.0001f) { /* inside the sphere: every direction may meet a generator */
            cl->axis = v3(0, 0, 1);
            cl->cos_max = -1.0f;
        } else {
            cl->axis = v3_scale(to, 1.0f / d);
            cl->cos_max = sqrtf(fmaxf(0.0f, 1.0f - (radius / d) * (radius / d)));
        }
    }
}

int lm_caustics_init(lm_caustics *c, const gk_ref_scene *rs, int n, int window, gk_err *e)
{
    memset(c, 0, sizeof *c);
    c->window = window < 1 ? 1 : window;
    vec3 centre;
    float radius;
    uint32_t generators = generator_sphere(rs, &centre, &radius);
    int usable = 0;
    for (int l = 0; l < rs->n_lights; l++)
        usable += caustic_light(&rs->lights[l]);
    if (generators == 0 || usable == 0 || n <= 0)
        return 0; /* no caustics in this scene: n stays 0 */
    c->lights = calloc((size_t)usable, sizeof *c->lights);
    c->pos = calloc((size_t)n, sizeof *c->pos);
    c->power = calloc((size_t)n, sizeof *c->power);
    c->has = calloc((size_t)n, sizeof *c->has);
    if (!c->lights || !c->pos || !c->power || !c->has) {
        lm_caustics_free(c);
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory for %d caustic photons", n);
    }
    c->n = n;
    for (int l = 0; l < rs->n_lights; l++) {
        if (!caustic_light(&rs->lights[l]))
            continue;
        lm_caustic_light *cl = &c->lights[c->n_lights];
        cl->light = l;
        /* an even split: light i gets photons [n i / L, n (i + 1) / L) */
        cl->first = (int)((long)n * c->n_lights / usable);
        cl->count = (int)((long)n * (c->n_lights + 1) / usable) - cl->first;
        c->n_lights++;
    }
    lm_caustics_aim(c, rs);
    return 0;
}

void lm_caustics_free(lm_caustics *c)
{
    free(c->lights), free(c->pos), free(c->power), free(c->has);
    memset(c, 0, sizeof *c);
}

/* Photon k's slice: its rank within its light's photons cut into W runs of consecutive Halton
   indices. A run of consecutive Halton points covers the cone evenly; k mod W would not (its low
   base-2 digits are the first Halton coordinate's: each slice would be one ring of the cone). */
int lm_caustics_slice(const lm_caustics *c, int k)
{
    for (int i = 0; i < c->n_lights; i++) {
        const lm_caustic_light *cl = &c->lights[i];
        if (k >= cl->first && k < cl->first + cl->count)
            return (int)((long)(k - cl->first) * c->window / cl->count);
    }
    return 0;
}

bool lm_caustics_due(const lm_caustics *c, int k)
{
    return c->ticks == 0 || (uint64_t)lm_caustics_slice(c, k) == c->ticks % (uint64_t)c->window;
}

static vec3 offset_point(const gk_ref_scene *rs, vec3 p, vec3 ng, vec3 dir)
{
    float eps = 1e-5f * (rs->radius + fmaxf(fabsf(p.x), fmaxf(fabsf(p.y), fabsf(p.z))));
    return v3_add(p, v3_scale(ng, v3_dot(dir, ng) > 0.0f ? eps : -eps));
}

void lm_caustics_trace(const lm_caustics *c, const gk_ref_scene *rs, int k, vec3 *pos, vec3 *power, bool *has)
{
    *has = false;
    *pos = v3(0, 0, 0), *power = v3(0, 0, 0);
    const lm_caustic_light *cl = NULL;
    for (int i = 0; i < c->n_lights; i++)
        if (k >= c->lights[i].first && k < c->lights[i].first + c->lights[i].count)
            cl = &c->lights[i];
    if (!cl || cl->count <= 0)
        return;
    const gk_ref_light *L = &rs->lights[cl->light];
    /* Halton index within the light, + 1: index 0 is the all-zero point */
    uint32_t i = (uint32_t)(k - cl->first) + 1;
    vec3 t, b;
    gk_onb(cl->axis, &t, &b);
    vec3 d = gk_to_world(gk_sample_uniform_cone(lm_halton(i, 2), lm_halton(i, 3), cl->cos_max), t, b, cl->axis);
    float solid_angle = 2.0f * (float)M_PI * (1.0f - cl->cos_max);
    vec3 flux = v3_scale(L->intensity, solid_angle / (float)cl->count);
    if (L->kind == GK_REF_SPOT)
        flux = v3_scale(flux, gk_spot_falloff(L, d));
    if (!(v3_maxc(flux) > 0.0f))
        return;
    gk_rng rng;
    gk_rng_seed(&rng, LM_CAUSTIC_SEED, (uint64_t)k, 0, 0);
    vec3 o = L->pos;
    int specular = 0;
    for (int depth = 0; depth < LM_CAUSTIC_MAX_BOUNCES; depth++) {
        gk_scene_hit h;
        if (!gk_scene_intersect(rs, o, d, INFINITY, &h) || h.light >= 0)
            return;
        if (depth == 0)
            flux = v3_scale(flux, gk_light_window(L, h.t));
        vec3 x = v3_add(o, v3_scale(d, h.t));
        gk_surface sf;
        gk_surface_init(&sf, rs, &rs->tris[h.tri], h.b1, h.b2);
        if (gk_surface_has_smooth_part(&sf)) {
            if (specular > 0) { /* L S+ D: a caustic photon, kept here */
                *pos = x, *power = flux, *has = true;
            }
            return; /* the first diffuse hit ends a caustic path (L D is the direct pass's) */
        }
        gk_bsdf_sample bs;
        if (!gk_bsdf_sample_dir(&sf, v3_scale(d, -1.0f), false, &rng, &bs) || !bs.delta)
            return;
        flux = v3_mul(flux, bs.weight);
        if (!(v3_maxc(flux) > 0.0f))
            return;
        specular++;
        o = offset_point(rs, x, sf.ng, bs.wi);
        d = bs.wi;
    }
}

bool lm_caustics_apply(lm_caustics *c, const vec3 *pos, const vec3 *power, const bool *has)
{
    int retraced = 0;
    bool changed = false;
    for (int k = 0; k < c->n; k++) {
        if (!lm_caustics_due(c, k))
            continue;
        retraced++;
        changed |= c->has[k] != has[k] || memcmp(&c->pos[k], &pos[k], sizeof *pos) ||
                   memcmp(&c->power[k], &power[k], sizeof *power);
        c->has[k] = has[k], c->pos[k] = pos[k], c->power[k] = power[k];
    }
    c->retraced = retraced;
    c->changed = changed;
    c->ticks++;
    return changed;
}

void lm_caustics_update(lm_caustics *c, const gk_ref_scene *rs)
{
    vec3 *pos = malloc(sizeof *pos * (size_t)(c->n > 0 ? c->n : 1));
    vec3 *power = malloc(sizeof *power * (size_t)(c->n > 0 ? c->n : 1));
    bool *has = malloc(sizeof *has * (size_t)(c->n > 0 ? c->n : 1));
    if (!pos || !power || !has) { /* out of memory: this update retraces nothing */
        free(pos), free(power), free(has);
        return;
    }
    for (int k = 0; k < c->n; k++)
        if (lm_caustics_due(c, k))
            lm_caustics_trace(c, rs, k, &pos[k], &power[k], &has[k]);
    lm_caustics_apply(c, pos, power, has);
    free(pos), free(power), free(has);
}
