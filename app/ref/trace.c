/* Eye-path integrator with NEE + MIS and the scene intersection helpers (see trace.h). */
#include "trace.h"

#include <float.h>
#include <math.h>

#include "lights.h"
#include "materials.h"
#include "medium.h"
#include "scene/environment.h"

/* Offsets for spawning rays off surfaces, relative to the scene size: large enough to escape the
   float error of the hit point, small enough not to skip thin geometry. */
#define EPS_REL 1e-5f

/* The closest surface or area light with tmin < t < tmax along o + t d (h->t from o). */
static bool intersect_from(const gk_ref_scene *rs, vec3 o, vec3 d, float tmin, float tmax, gk_scene_hit *h)
{
    gk_bvh_hit bh;
    h->tri = -1;
    h->light = -1;
    h->t = tmax;
    if (gk_bvh_intersect(&rs->bvh, o, d, tmin, tmax, &bh)) {
        h->t = bh.t;
        h->tri = (int)bh.tri;
        h->b1 = bh.u;
        h->b2 = bh.v;
    }
    float tl;
    int li = gk_area_lights_intersect(rs, o, d, h->t, &tl);
    if (li >= 0) {
        h->t = tl;
        h->light = li;
        h->tri = -1;
    }
    return h->tri >= 0 || h->light >= 0;
}

bool gk_scene_intersect(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax, gk_scene_hit *h)
{
    return intersect_from(rs, o, d, 0.0f, tmax, h);
}

/* Whether a camera ray along d passes through the hit: the back face of a single-sided material. */
static bool camera_passes(const gk_ref_scene *rs, const gk_scene_hit *h, vec3 d)
{
    if (h->tri < 0)
        return false;
    const gk_ref_tri *t = &rs->tris[h->tri];
    return !rs->materials[t->material].double_sided && v3_dot(d, t->ng) > 0.0f;
}

bool gk_scene_intersect_camera(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax, gk_scene_hit *h)
{
    bool hit = intersect_from(rs, o, d, 0.0f, tmax, h);
    /* past each back face, on from just beyond it (EPS_REL as offset_point's) */
    for (int guard = 0; hit && camera_passes(rs, h, d) && guard < 1024; guard++) {
        vec3 x = v3_add(o, v3_scale(d, h->t));
        float eps = EPS_REL * (rs->radius + fmaxf(fabsf(x.x), fmaxf(fabsf(x.y), fabsf(x.z))));
        hit = intersect_from(rs, o, d, h->t + eps, tmax, h);
    }
    return hit;
}

bool gk_scene_camera_sees(const gk_ref_scene *rs, vec3 x)
{
    vec3 to_x = v3_sub(x, rs->eye);
    float dist = v3_len(to_x);
    if (!(dist > 0.0f))
        return false;
    gk_scene_hit h;
    return !gk_scene_intersect_camera(rs, rs->eye, v3_scale(to_x, 1.0f / dist), dist * (1.0f - 1e-4f), &h);
}

bool gk_scene_occluded(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax)
{
    return gk_bvh_occluded(&rs->bvh, o, d, 0.0f, tmax) || gk_area_lights_occlude(rs, o, d, tmax);
}

/* The class of a path ending at a light now; 0 for directly seen caustics (E D S+ L), which the
   light pass renders. */
static unsigned classify(int n_diffuse, bool specular_after_diffuse, bool specular_before_diffuse)
{
    if (n_diffuse >= 2)
        return GK_PATH_INDIRECT;
    if (n_diffuse == 1 && specular_after_diffuse)
        return specular_before_diffuse ? GK_PATH_CAUSTICS : 0;
    return GK_PATH_DIRECT;
}

static vec3 offset_point(const gk_ref_scene *rs, vec3 p, vec3 ng, vec3 dir)
{
    float eps = EPS_REL * (rs->radius + fmaxf(fabsf(p.x), fmaxf(fabsf(p.y), fabsf(p.z))));
    return v3_add(p, v3_scale(ng, v3_dot(dir, ng) > 0.0f ? eps : -eps));
}

/* Whether a path with n_diffuse D vertices is within the bounce limit. */
static bool within_bounces(int n_diffuse, int max_diffuse)
{
    return max_diffuse == GK_BOUNCES_UNLIMITED || n_diffuse <= max_diffuse;
}

/* The image term (trace.h) of a path ending at a light now; 0 for volume caustics (light pass). */
static unsigned term_of(int n_medium, int n_diffuse, bool spec_after_medium)
{
    if (n_medium == 0)
        return GK_TERM_SURFACES;
    if (n_medium == 1 && n_diffuse == 0)
        return spec_after_medium ? 0u : (unsigned)GK_TERM_AIRLIGHT;
    return GK_TERM_MULTIPLE;
}

/* Is a contribution of this term (and, for surfaces, path class) wanted? */
static bool wanted(unsigned term, unsigned cls, unsigned mask, unsigned terms)
{
    return (terms & term) && (term != GK_TERM_SURFACES || (mask & cls));
}

/* Can the path still reach a wanted term? (Only then is it worth continuing.) */
static bool can_still_count(const gk_ref_scene *rs, int n_medium, int n_diffuse, unsigned mask, unsigned terms)
{
    bool surfaces = (terms & GK_TERM_SURFACES) && n_medium == 0 && !(n_diffuse >= 2 && !(mask & GK_PATH_INDIRECT));
    bool airlight = rs->medium.present && (terms & GK_TERM_AIRLIGHT) && n_diffuse == 0 && n_medium <= 1;
    bool multiple = rs->medium.present && (terms & GK_TERM_MULTIPLE);
    return surfaces || airlight || multiple;
}

static bool is_point_light(const gk_ref_scene *rs, int li)
{
    return li >= 0 && (rs->lights[li].kind == GK_REF_POINT || rs->lights[li].kind == GK_REF_SPOT);
}

/* Single scattering of point and spot lights along one eye segment o + t d, t < tmax, in the
   medium: the light picked by power (as next-event estimation picks), the scattering point by
   equi-angular sampling around it (Kulla and Fajardo 2012: pdf(t) = D / ((theta_b - theta_a)
   (D^2 + (t - t_c)^2)), which cancels the light's 1/d^2), i.e. the airlight integral of the
   segment. (Free-flight points alone leave most samples outside a narrow spot beam: measured noise
   floor 1.16 at 16 spp on caustic-ring-fog's airlight.) The free-flight vertices then skip these
   lights in their own next-event estimation, so nothing is counted twice. Draws two random numbers
   whenever the segment overlaps the medium. Returns the radiance before the path's throughput. */
static vec3 segment_point_light_scatter(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax, bool want, gk_rng *rng,
                                        gk_trace_stats *st)
{
    const gk_ref_medium *med = &rs->medium;
    float t0, t1;
    if (!gk_medium_clip(med, o, d, tmax, &t0, &t1))
        return v3(0, 0, 0);
    float u_pick = gk_rng_float(rng), u_t = gk_rng_float(rng);
    float pl;
    int li = gk_light_pick(rs, u_pick, &pl);
    if (!want || !is_point_light(rs, li) || !(pl > 0.0f))
        return v3(0, 0, 0);
    vec3 P = rs->lights[li].pos;
    float tc = v3_dot(v3_sub(P, o), d);
    float D = v3_len(v3_sub(P, v3_add(o, v3_scale(d, tc))));
    if (D < 1e-6f * (rs->radius + 1.0f))
        return v3(0, 0, 0); /* the ray runs through the light: measure zero */
    float ta = atanf((t0 - tc) / D), tb = isinf(t1) ? 0.5f * GK_PI : atanf((t1 - tc) / D);
    if (!(tb > ta))
        return v3(0, 0, 0);
    float t = tc + D * tanf(ta + u_t * (tb - ta));
    float pdf = D / ((tb - ta) * (D * D + (t - tc) * (t - tc)));
    if (!(t >= t0 && t <= t1) || !(pdf > 0.0f))
        return v3(0, 0, 0);
    vec3 x = v3_add(o, v3_scale(d, t));
    gk_light_sample ls;
    if (!gk_light_sample_one(rs, li, x, 0.5f, 0.5f, 0.5f, &ls))
        return v3(0, 0, 0);
    float tl = ls.dist * (1.0f - 1e-4f);
    st->rays++;
    if (gk_scene_occluded(rs, x, ls.wi, tl))
        return v3(0, 0, 0);
    vec3 tr = v3_mul(gk_medium_transmittance(med, o, d, t), gk_medium_transmittance(med, x, ls.wi, tl));
    float ph = gk_phase_hg(med->g, v3_dot(ls.wi, d));
    return v3_scale(v3_mul(v3_mul(ls.li, tr), med->sigma_s), ph / (pl * pdf));
}

vec3 gk_trace_eye(const gk_ref_scene *rs, vec3 o, vec3 d, unsigned mask, unsigned terms, int max_diffuse,
                  int max_depth, int rr_depth, gk_rng *rng, gk_trace_stats *st)
{
    const gk_ref_medium *med = &rs->medium;
    vec3 radiance = v3(0, 0, 0), beta = v3(1, 1, 1);
    int n_diffuse = 0, n_medium = 0;
    bool spec_after_diffuse = false, spec_before_diffuse = false, spec_after_medium = false;
    bool prev_delta = true; /* the camera ray counts as a delta step: no MIS for what it sees */
    float prev_pdf = 0.0f;
    vec3 prev_p = o;
    for (int depth = 0; depth <= max_depth; depth++) {
        gk_scene_hit h;
        st->rays++;
        /* the camera ray (depth 0) sees single-sided materials from the front only */
        bool hit = depth == 0 ? gk_scene_intersect_camera(rs, o, d, INFINITY, &h) : gk_scene_intersect(rs, o, d, INFINITY, &h);
        if (med->present && rs->has_delta_lights) {
            /* this segment's single scattering of point and spot lights: a new V vertex */
            bool want = wanted(term_of(n_medium + 1, n_diffuse, false), 0, mask, terms) &&
                        within_bounces(n_diffuse, max_diffuse) && depth < max_depth;
            vec3 l = segment_point_light_scatter(rs, o, d, hit ? h.t : INFINITY, want, rng, st);
            radiance = v3_add(radiance, v3_mul(beta, l));
        }
        if (med->present) {
            /* Free flight through the medium: a scattering event before the hit, or the hit reached
               with the transmittance's weight. */
            float ts;
            vec3 wt;
            bool scatter = gk_medium_sample_distance(med, o, d, hit ? h.t : INFINITY, rng, &ts, &wt);
            beta = v3_mul(beta, wt);
            if (scatter) {
                vec3 x = v3_add(o, v3_scale(d, ts));
                n_medium++;
                spec_after_medium = false;
                if (depth == max_depth)
                    break;
                /* Next-event estimation through the medium (drawn whatever the terms, for the
                   stream's alignment). */
                gk_light_sample ls;
                float u0 = gk_rng_float(rng), u1 = gk_rng_float(rng), u2 = gk_rng_float(rng), u3 = gk_rng_float(rng);
                float pl;
                int li = gk_light_pick(rs, u0, &pl);
                /* point and spot lights: done by segment_point_light_scatter above */
                bool got = li >= 0 && !is_point_light(rs, li) && gk_light_sample_one(rs, li, x, u1, u2, u3, &ls);
                ls.pdf *= pl;
                got = got && ls.pdf > 0.0f;
                unsigned term = term_of(n_medium, n_diffuse, false);
                if (got && wanted(term, 0, mask, terms) && within_bounces(n_diffuse, max_diffuse)) {
                    float ph = gk_phase_hg(med->g, v3_dot(ls.wi, d));
                    float tmax = isinf(ls.dist) ? INFINITY : ls.dist * (1.0f - 1e-4f);
                    vec3 tr = gk_medium_transmittance(med, x, ls.wi, tmax);
                    st->rays++;
                    if ((tr.x > 0.0f || tr.y > 0.0f || tr.z > 0.0f) && !gk_scene_occluded(rs, x, ls.wi, tmax)) {
                        float w = ls.delta ? 1.0f : gk_power_heuristic(ls.pdf, ph);
                        radiance = v3_add(radiance, v3_mul(beta, v3_scale(v3_mul(ls.li, tr), ph * w / ls.pdf)));
                    }
                }
                float v1 = gk_rng_float(rng), v2 = gk_rng_float(rng);
                vec3 wi = gk_phase_hg_sample(med->g, d, v1, v2);
                prev_delta = false;
                prev_pdf = gk_phase_hg(med->g, v3_dot(d, wi)); /* the phase function is its own pdf */
                prev_p = x;
                o = x;
                d = wi;
                if (!can_still_count(rs, n_medium, n_diffuse, mask, terms) || !within_bounces(n_diffuse, max_diffuse))
                    break;
                if (depth + 1 >= rr_depth) {
                    float q = fminf(0.95f, v3_maxc(beta));
                    if (gk_rng_float(rng) >= q)
                        break;
                    beta = v3_scale(beta, 1.0f / q);
                }
                continue;
            }
            if (beta.x <= 0.0f && beta.y <= 0.0f && beta.z <= 0.0f)
                break; /* escaped through an unbounded medium: fully extinguished */
        }
        unsigned term_here = term_of(n_medium, n_diffuse, spec_after_medium);
        unsigned cls_here = classify(n_diffuse, spec_after_diffuse, spec_before_diffuse);
        if (!hit) {
            int sun;
            vec3 le = gk_sky_emission(rs, d, &sun);
            bool count = within_bounces(n_diffuse, max_diffuse) && wanted(term_here, cls_here, mask, terms);
            if (sun >= 0 && count) {
                float w = prev_delta ? 1.0f : gk_power_heuristic(prev_pdf, gk_light_pdf(rs, sun, -1, prev_p, prev_p, d));
                radiance = v3_add(radiance, v3_mul(beta, v3_scale(le, w)));
            }
            if (rs->env_light >= 0 && count) { /* the environment map, weighted against its own sampling */
                float w = prev_delta ? 1.0f
                                     : gk_power_heuristic(prev_pdf, gk_light_pdf(rs, rs->env_light, -1, prev_p, prev_p, d));
                radiance = v3_add(radiance, v3_mul(beta, v3_scale(gk_env_radiance(rs->env.env, d), w)));
            }
            break;
        }
        vec3 x = v3_add(o, v3_scale(d, h.t));
        if (h.light >= 0) {
            vec3 le = gk_area_light_emission(rs, h.light, d);
            if (within_bounces(n_diffuse, max_diffuse) && wanted(term_here, cls_here, mask, terms)) {
                float w = prev_delta ? 1.0f : gk_power_heuristic(prev_pdf, gk_light_pdf(rs, h.light, -1, prev_p, x, d));
                radiance = v3_add(radiance, v3_mul(beta, v3_scale(le, w)));
            }
            break; /* light geometry is black apart from its emission */
        }
        const gk_ref_tri *tri = &rs->tris[h.tri];
        if (tri->emissive >= 0 && within_bounces(n_diffuse, max_diffuse) && wanted(term_here, cls_here, mask, terms)) {
            vec3 le = gk_tri_emission(rs, tri, h.b1, h.b2, d);
            float w = prev_delta ? 1.0f
                                 : gk_power_heuristic(prev_pdf, gk_light_pdf(rs, rs->mesh_light, h.tri, prev_p, x, d));
            radiance = v3_add(radiance, v3_mul(beta, v3_scale(le, w)));
        }
        if (depth == max_depth)
            break;
        gk_surface sf;
        gk_surface_init(&sf, rs, tri, h.b1, h.b2);
        vec3 wo = v3_scale(d, -1.0f);

        /* Next-event estimation: this vertex becomes a D vertex next to the light. */
        if (gk_surface_has_smooth_part(&sf) && within_bounces(n_diffuse + 1, max_diffuse) &&
            wanted(term_of(n_medium, n_diffuse + 1, false), classify(n_diffuse + 1, false, false), mask, terms)) {
            gk_light_sample ls;
            if (gk_light_sample_from(rs, x, rng, &ls)) {
                float pdf_b;
                vec3 f = gk_bsdf_eval(&sf, wo, ls.wi, &pdf_b);
                float cos_s = fabsf(v3_dot(sf.n, ls.wi));
                if (f.x > 0.0f || f.y > 0.0f || f.z > 0.0f) {
                    vec3 so = offset_point(rs, x, sf.ng, ls.wi);
                    float tmax = isinf(ls.dist) ? INFINITY : ls.dist * (1.0f - 1e-4f);
                    vec3 tr = gk_medium_transmittance(med, so, ls.wi, tmax);
                    st->rays++;
                    if ((tr.x > 0.0f || tr.y > 0.0f || tr.z > 0.0f) && !gk_scene_occluded(rs, so, ls.wi, tmax)) {
                        float w = ls.delta ? 1.0f : gk_power_heuristic(ls.pdf, pdf_b);
                        vec3 c = v3_scale(v3_mul(v3_mul(f, ls.li), tr), cos_s * w / ls.pdf);
                        radiance = v3_add(radiance, v3_mul(beta, c));
                    }
                }
            }
        } else if (gk_surface_has_smooth_part(&sf)) {
            /* Keep the random stream aligned whatever the mask, so that renders of the separate
               classes with one seed add up to the full render sample by sample. */
            gk_light_sample ls;
            gk_light_sample_from(rs, x, rng, &ls);
        }

        gk_bsdf_sample bs;
        if (!gk_bsdf_sample_dir(&sf, wo, true, rng, &bs))
            break;
        if (bs.delta) {
            if (n_diffuse >= 1)
                spec_after_diffuse = true;
            else
                spec_before_diffuse = true;
            if (n_medium >= 1)
                spec_after_medium = true;
        } else {
            n_diffuse++;
            spec_after_diffuse = false;
            spec_after_medium = false;
        }
        beta = v3_mul(beta, bs.weight);
        prev_delta = bs.delta;
        prev_pdf = bs.pdf;
        prev_p = x;
        o = offset_point(rs, x, sf.ng, bs.wi);
        d = bs.wi;
        /* Paths that can no longer reach a wanted term or class, or are past the bounce limit, end
           early (same stream use either way is not needed past this point: nothing further is
           accumulated). */
        if (!can_still_count(rs, n_medium, n_diffuse, mask, terms) || !within_bounces(n_diffuse, max_diffuse))
            break;
        if (depth + 1 >= rr_depth) {
            float q = fminf(0.95f, v3_maxc(beta));
            if (gk_rng_float(rng) >= q)
                break;
            beta = v3_scale(beta, 1.0f / q);
        }
    }
    return radiance;
}
