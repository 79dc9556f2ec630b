/* Light sampling, emission and photon emission (see lights.h). */
#include "lights.h"

#include <float.h>
#include <math.h>

#include "materials.h"

static bool is_delta(enum gk_ref_light_kind k) { return k == GK_REF_POINT || k == GK_REF_SPOT || k == GK_REF_DIRECTIONAL; }

static int pick_cdf(const float *cdf, int n, float u, float *prob)
{
    float total = cdf[n];
    if (!(total > 0.0f))
        return -1;
    float x = u * total;
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
    *prob = (cdf[lo + 1] - cdf[lo]) / total;
    return *prob > 0.0f ? lo : -1;
}

static float pick_prob(const float *cdf, int n, int i) { return cdf[n] > 0.0f ? (cdf[i + 1] - cdf[i]) / cdf[n] : 0.0f; }

float gk_light_window(const gk_ref_light *L, float dist)
{
    if (L->range <= 0.0f)
        return 1.0f;
    float r = dist / L->range, r4 = r * r * r * r;
    float w = 1.0f - r4;
    w = w < 0.0f ? 0.0f : (w > 1.0f ? 1.0f : w);
    return w * w;
}

float gk_spot_falloff(const gk_ref_light *L, vec3 w)
{
    if (!L->spot_mask)
        return 1.0f;
    float c = v3_dot(w, L->axis);
    float t = (c - L->cos_outer) / (L->cos_inner - L->cos_outer);
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    return t * t;
}

/* A uniformly distributed point on a disc or rectangle emitter (next-event estimation and light
   tracing sample the same way). */
static vec3 planar_emitter_point(const gk_ref_light *L, float u1, float u2)
{
    if (L->kind == GK_REF_DISC) {
        float dx, dy;
        gk_sample_uniform_disc(u1, u2, &dx, &dy);
        return v3_add(L->pos, v3_add(v3_scale(L->u, dx * L->radius), v3_scale(L->v, dy * L->radius)));
    }
    return v3_add(L->pos, v3_add(v3_scale(L->u, (2.0f * u1 - 1.0f) * L->half_w),
                                 v3_scale(L->v, (2.0f * u2 - 1.0f) * L->half_h)));
}

static bool sample_one(const gk_ref_scene *rs, int li, vec3 p, float u1, float u2, float u3, gk_light_sample *s)
{
    const gk_ref_light *L = &rs->lights[li];
    s->delta = is_delta(L->kind);
    switch (L->kind) {
    case GK_REF_POINT:
    case GK_REF_SPOT: {
        vec3 dv = v3_sub(L->pos, p);
        float d2 = v3_dot(dv, dv);
        if (d2 <= 0.0f)
            return false;
        s->dist = sqrtf(d2);
        s->wi = v3_scale(dv, 1.0f / s->dist);
        float f = gk_spot_falloff(L, v3_scale(s->wi, -1.0f)) * gk_light_window(L, s->dist) / d2;
        s->li = v3_scale(L->intensity, f);
        s->pdf = 1.0f;
        return f > 0.0f;
    }
    case GK_REF_DIRECTIONAL:
        s->wi = v3_scale(L->axis, -1.0f);
        s->dist = INFINITY;
        s->li = L->intensity;
        s->pdf = 1.0f;
        return true;
    case GK_REF_SUN: {
        vec3 t, b, n = v3_scale(L->axis, -1.0f);
        gk_onb(n, &t, &b);
        s->wi = gk_to_world(gk_sample_uniform_cone(u1, u2, L->sun_cos_max), t, b, n);
        s->dist = INFINITY;
        s->li = L->radiance;
        s->pdf = 1.0f / (2.0f * GK_PI * (1.0f - L->sun_cos_max));
        return true;
    }
    case GK_REF_SPHERE: {
        vec3 dc = v3_sub(L->pos, p);
        float dc2 = v3_dot(dc, dc), r2 = L->radius * L->radius;
        if (dc2 <= r2 * 1.0001f)
            return false; /* inside the light: it is not sampled (its emission is still hit) */
        float dcl = sqrtf(dc2);
        float cos_max = sqrtf(fmaxf(0.0f, 1.0f - r2 / dc2));
        vec3 n = v3_scale(dc, 1.0f / dcl), t, b;
        gk_onb(n, &t, &b);
        s->wi = gk_to_world(gk_sample_uniform_cone(u1, u2, cos_max), t, b, n);
        /* Distance to the sphere along wi (nearest root). */
        float bq = v3_dot(s->wi, dc), disc = bq * bq - (dc2 - r2);
        s->dist = bq - sqrtf(fmaxf(0.0f, disc));
        s->li = L->radiance;
        s->pdf = 1.0f / (2.0f * GK_PI * (1.0f - cos_max));
        return true;
    }
    case GK_REF_DISC:
    case GK_REF_RECT: {
        vec3 x = planar_emitter_point(L, u1, u2);
        vec3 dv = v3_sub(x, p);
        float d2 = v3_dot(dv, dv);
        if (d2 <= 0.0f)
            return false;
        s->dist = sqrtf(d2);
        s->wi = v3_scale(dv, 1.0f / s->dist);
        float cos_l = -v3_dot(s->wi, L->axis);
        if (cos_l <= 0.0f)
            return false; /* behind the one-sided emitter */
        s->li = v3_scale(L->radiance, gk_spot_falloff(L, v3_scale(s->wi, -1.0f)));
        s->pdf = d2 / (cos_l * L->area);
        return true;
    }
    case GK_REF_ENV:
        s->dist = INFINITY;
        return gk_ref_env_sample(&rs->env, u1, u2, &s->wi, &s->li, &s->pdf) &&
               (s->li.x > 0.0f || s->li.y > 0.0f || s->li.z > 0.0f);
    case GK_REF_MESH: {
        float pt;
        int k = pick_cdf(rs->emissive_cdf, rs->n_emissive, u3, &pt);
        if (k < 0)
            return false;
        const gk_ref_tri *tr = &rs->tris[rs->emissive_tris[k]];
        float b1, b2;
        gk_sample_triangle(u1, u2, &b1, &b2);
        vec3 x = v3_add(v3_add(v3_scale(tr->p[0], 1.0f - b1 - b2), v3_scale(tr->p[1], b1)), v3_scale(tr->p[2], b2));
        vec3 dv = v3_sub(x, p);
        float d2 = v3_dot(dv, dv);
        if (d2 <= 0.0f)
            return false;
        s->dist = sqrtf(d2);
        s->wi = v3_scale(dv, 1.0f / s->dist);
        float cos_l = fabsf(v3_dot(s->wi, tr->ng));
        if (cos_l <= 1e-7f)
            return false;
        s->li = gk_tri_emission(rs, tr, b1, b2, s->wi);
        s->pdf = pt * d2 / (cos_l * tr->area);
        return s->li.x > 0.0f || s->li.y > 0.0f || s->li.z > 0.0f;
    }
    }
    return false;
}

bool gk_light_sample_from(const gk_ref_scene *rs, vec3 p, gk_rng *rng, gk_light_sample *out)
{
    float u0 = gk_rng_float(rng), u1 = gk_rng_float(rng), u2 = gk_rng_float(rng), u3 = gk_rng_float(rng);
    float pl;
    int li = pick_cdf(rs->light_cdf, rs->n_lights, u0, &pl);
    if (li < 0 || !sample_one(rs, li, p, u1, u2, u3, out))
        return false;
    out->pdf *= pl;
    return out->pdf > 0.0f;
}

bool gk_light_sample_one(const gk_ref_scene *rs, int li, vec3 p, float u1, float u2, float u3, gk_light_sample *out)
{
    if (li < 0 || li >= rs->n_lights)
        return false;
    return sample_one(rs, li, p, u1, u2, u3, out) && out->pdf > 0.0f;
}

float gk_light_pdf(const gk_ref_scene *rs, int li, int tri, vec3 p, vec3 x, vec3 d)
{
    if (li < 0 || li >= rs->n_lights)
        return 0.0f;
    const gk_ref_light *L = &rs->lights[li];
    float pl = pick_prob(rs->light_cdf, rs->n_lights, li);
    if (pl <= 0.0f)
        return 0.0f;
    vec3 dv = v3_sub(x, p);
    float d2 = v3_dot(dv, dv);
    switch (L->kind) {
    case GK_REF_SUN:
        return pl / (2.0f * GK_PI * (1.0f - L->sun_cos_max));
    case GK_REF_ENV:
        return pl * gk_ref_env_pdf(&rs->env, d);
    case GK_REF_SPHERE: {
        vec3 dc = v3_sub(L->pos, p);
        float dc2 = v3_dot(dc, dc), r2 = L->radius * L->radius;
        if (dc2 <= r2 * 1.0001f)
            return 0.0f;
        float cos_max = sqrtf(fmaxf(0.0f, 1.0f - r2 / dc2));
        return pl / (2.0f * GK_PI * (1.0f - cos_max));
    }
    case GK_REF_DISC:
    case GK_REF_RECT: {
        float cos_l = -v3_dot(d, L->axis);
        return cos_l > 0.0f ? pl * d2 / (cos_l * L->area) : 0.0f;
    }
    case GK_REF_MESH: {
        if (tri < 0)
            return 0.0f;
        const gk_ref_tri *tr = &rs->tris[tri];
        float cos_l = fabsf(v3_dot(d, tr->ng));
        if (tr->emissive < 0 || cos_l <= 1e-7f)
            return 0.0f;
        float pt = pick_prob(rs->emissive_cdf, rs->n_emissive, tr->emissive);
        return pl * pt * d2 / (cos_l * tr->area);
    }
    default:
        return 0.0f;
    }
}

static float hit_light(const gk_ref_light *L, vec3 o, vec3 d, float tmax)
{
    if (L->kind == GK_REF_SPHERE) {
        vec3 oc = v3_sub(o, L->pos);
        float b = v3_dot(oc, d), c = v3_dot(oc, oc) - L->radius * L->radius;
        float disc = b * b - c;
        if (disc < 0.0f)
            return INFINITY;
        float sq = sqrtf(disc), t = -b - sq;
        if (t <= 1e-5f)
            t = -b + sq;
        return t > 1e-5f && t < tmax ? t : INFINITY;
    }
    if (L->kind == GK_REF_DISC || L->kind == GK_REF_RECT) {
        float dn = v3_dot(d, L->axis);
        if (fabsf(dn) < 1e-12f)
            return INFINITY;
        float t = v3_dot(v3_sub(L->pos, o), L->axis) / dn;
        if (t <= 1e-5f || t >= tmax)
            return INFINITY;
        vec3 q = v3_sub(v3_add(o, v3_scale(d, t)), L->pos);
        float a = v3_dot(q, L->u), b = v3_dot(q, L->v);
        if (L->kind == GK_REF_DISC)
            return a * a + b * b <= L->radius * L->radius ? t : INFINITY;
        return fabsf(a) <= L->half_w && fabsf(b) <= L->half_h ? t : INFINITY;
    }
    return INFINITY;
}

int gk_area_lights_intersect(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax, float *t)
{
    int best = -1;
    for (int i = 0; i < rs->n_lights; i++) {
        float th = hit_light(&rs->lights[i], o, d, tmax);
        if (th < tmax) {
            tmax = th;
            best = i;
        }
    }
    *t = tmax;
    return best;
}

bool gk_area_lights_occlude(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax)
{
    for (int i = 0; i < rs->n_lights; i++)
        if (hit_light(&rs->lights[i], o, d, tmax) < tmax)
            return true;
    return false;
}

vec3 gk_area_light_emission(const gk_ref_scene *rs, int li, vec3 d)
{
    const gk_ref_light *L = &rs->lights[li];
    if (L->kind == GK_REF_SPHERE)
        return L->radiance;
    vec3 w = v3_scale(d, -1.0f); /* leaving the light towards the ray's origin */
    if (v3_dot(w, L->axis) <= 0.0f)
        return v3(0, 0, 0);
    return v3_scale(L->radiance, gk_spot_falloff(L, w));
}

vec3 gk_tri_emission(const gk_ref_scene *rs, const gk_ref_tri *t, float b1, float b2, vec3 d)
{
    const gk_material *m = &rs->materials[t->material];
    if (!m->double_sided && v3_dot(d, t->ng) >= 0.0f)
        return v3(0, 0, 0); /* seen from the back */
    /* emissiveFactor x emissiveTexture; the emitter CDF weighs triangles by the factor alone,
       still unbiased (the texture only makes some picks worth less). */
    return v3_mul(v3(m->emissive[0], m->emissive[1], m->emissive[2]), gk_tri_texture_rgb(rs, t, m->emissive_tex, &m->tex_uv[GK_SLOT_EMISSIVE], b1, b2));
}

vec3 gk_sky_emission(const gk_ref_scene *rs, vec3 d, int *light)
{
    vec3 sum = v3(0, 0, 0);
    *light = -1;
    for (int i = 0; i < rs->n_lights; i++) {
        const gk_ref_light *L = &rs->lights[i];
        if (L->kind == GK_REF_SUN && -v3_dot(d, L->axis) >= L->sun_cos_max) {
            sum = v3_add(sum, L->radiance);
            *light = i;
        }
    }
    return sum;
}

static vec3 cosine_about(vec3 n, float u1, float u2)
{
    vec3 t, b;
    gk_onb(n, &t, &b);
    return gk_to_world(gk_sample_cosine_hemisphere(u1, u2), t, b, n);
}

int gk_light_pick(const gk_ref_scene *rs, float u, float *prob)
{
    return pick_cdf(rs->light_cdf, rs->n_lights, u, prob);
}

bool gk_light_photon(const gk_ref_scene *rs, gk_rng *rng, vec3 *o, vec3 *d, vec3 *flux, int *light)
{
    float u0 = gk_rng_float(rng), u[5];
    for (int k = 0; k < 5; k++)
        u[k] = gk_rng_float(rng);
    float pl;
    int li = gk_light_pick(rs, u0, &pl);
    if (li < 0)
        return false;
    *light = li;
    return gk_light_photon_of(rs, li, pl, u, o, d, flux);
}

bool gk_light_photon_of(const gk_ref_scene *rs, int li, float pl, const float u[5], vec3 *o, vec3 *d, vec3 *flux)
{
    float u1 = u[0], u2 = u[1], u3 = u[2], u4 = u[3], u5 = u[4];
    const gk_ref_light *L = &rs->lights[li];
    float eps = 1e-5f * rs->radius;
    switch (L->kind) {
    case GK_REF_POINT:
        *o = L->pos;
        *d = gk_sample_uniform_sphere(u1, u2);
        *flux = v3_scale(L->intensity, 4.0f * GK_PI / pl);
        return true;
    case GK_REF_SPOT: {
        vec3 t, b;
        gk_onb(L->axis, &t, &b);
        *o = L->pos;
        *d = gk_to_world(gk_sample_uniform_cone(u1, u2, L->cos_outer), t, b, L->axis);
        *flux = v3_scale(L->intensity, gk_spot_falloff(L, *d) * 2.0f * GK_PI * (1.0f - L->cos_outer) / pl);
        return true;
    }
    case GK_REF_ENV: {
        /* A direction from the environment's importance sampling (u3, u4), then a point on a disc
           covering the scene's bounding sphere upstream of it (u1, u2), as for directional lights:
           flux = L / pdf(direction) x disc area. */
        vec3 wi, le;
        float pdf;
        if (!gk_ref_env_sample(&rs->env, u3, u4, &wi, &le, &pdf))
            return false;
        *d = v3_scale(wi, -1.0f);
        vec3 t, b;
        gk_onb(*d, &t, &b);
        float dx, dy;
        gk_sample_uniform_disc(u1, u2, &dx, &dy);
        vec3 c = v3_add(rs->centre, v3_scale(wi, 2.0f * rs->radius));
        *o = v3_add(c, v3_add(v3_scale(t, dx * rs->radius), v3_scale(b, dy * rs->radius)));
        *flux = v3_scale(le, GK_PI * rs->radius * rs->radius / (pdf * pl));
        return true;
    }
    case GK_REF_DIRECTIONAL:
    case GK_REF_SUN: {
        /* A disc covering the scene's bounding sphere, upstream of it; a sun's directions spread
           uniformly over its disc (radiance * solid angle = its lux). */
        vec3 t, b;
        gk_onb(L->axis, &t, &b);
        float dx, dy;
        gk_sample_uniform_disc(u1, u2, &dx, &dy);
        vec3 c = v3_sub(rs->centre, v3_scale(L->axis, 2.0f * rs->radius));
        *o = v3_add(c, v3_add(v3_scale(t, dx * rs->radius), v3_scale(b, dy * rs->radius)));
        *d = L->kind == GK_REF_SUN ? gk_to_world(gk_sample_uniform_cone(u3, u4, L->sun_cos_max), t, b, L->axis) : L->axis;
        *flux = v3_scale(L->intensity, GK_PI * rs->radius * rs->radius / pl);
        return true;
    }
    case GK_REF_SPHERE: {
        vec3 n = gk_sample_uniform_sphere(u1, u2);
        *o = v3_add(L->pos, v3_scale(n, L->radius + eps));
        *d = cosine_about(n, u3, u4);
        *flux = v3_scale(L->radiance, 4.0f * GK_PI * L->radius * L->radius * GK_PI / pl);
        return true;
    }
    case GK_REF_DISC:
    case GK_REF_RECT: {
        vec3 x = planar_emitter_point(L, u1, u2);
        *o = v3_add(x, v3_scale(L->axis, eps));
        *d = cosine_about(L->axis, u3, u4);
        *flux = v3_scale(L->radiance, gk_spot_falloff(L, *d) * L->area * GK_PI / pl);
        return true;
    }
    case GK_REF_MESH: {
        float pt;
        int k = pick_cdf(rs->emissive_cdf, rs->n_emissive, u5, &pt);
        if (k < 0)
            return false;
        const gk_ref_tri *tr = &rs->tris[rs->emissive_tris[k]];
        const gk_material *m = &rs->materials[tr->material];
        float b1, b2, sides = m->double_sided ? 2.0f : 1.0f;
        gk_sample_triangle(u1, u2, &b1, &b2);
        vec3 x = v3_add(v3_add(v3_scale(tr->p[0], 1.0f - b1 - b2), v3_scale(tr->p[1], b1)), v3_scale(tr->p[2], b2));
        /* Double-sided: pick a face with probability 1/2 (u3 reused after rescaling). */
        vec3 n = tr->ng;
        if (m->double_sided && u3 >= 0.5f)
            n = v3_scale(n, -1.0f);
        float u3r = m->double_sided ? fmodf(u3 * 2.0f, 1.0f) : u3;
        *o = v3_add(x, v3_scale(n, eps));
        *d = cosine_about(n, u3r, u4);
        vec3 le = v3_mul(v3(m->emissive[0], m->emissive[1], m->emissive[2]),
                         gk_tri_texture_rgb(rs, tr, m->emissive_tex, &m->tex_uv[GK_SLOT_EMISSIVE], b1, b2));
        *flux = v3_scale(le, tr->area * GK_PI * sides / (pt * pl));
        return true;
    }
    }
    return false;
}
