/* Light tracing of caustics seen directly, L S+ D E, and of volume caustics, L S+ V E (see trace.h).
 *
 * Measurement: a pixel's value is the mean radiance over its footprint on the image plane at
 * distance 1 from the pinhole, I = (1/A_pix) \int L(x -> eye) dA_plane. With dA_plane =
 * cos_x dA_x / (d^2 cos_cam^3) for a surface point x at distance d, seen at angle cam from the
 * optical axis, a photon of flux Phi arriving at x from wi adds
 *     Phi f(wo_eye, wi) cos_x / (d^2 cos_cam^3 A_pix)
 * to the pixel it projects into (the pinhole's importance We), divided by the number of photons.
 * A point x inside a medium has no surface: with dV = d^2 dt dA_plane cos_cam^3, a photon of flux Phi
 * travelling along a segment adds, per unit length t of the segment,
 *     Phi T(p1, x) sigma_s p_HG(cos) T(x, eye) / (d^2 cos_cam^3 A_pix),
 * estimated with one point per segment (equi-angular sampling, below). */
#include <math.h>

#include "caustic_emit.h"
#include "lights.h"
#include "materials.h"
#include "medium.h"
#include "trace.h"

static vec3 offset_point(const gk_ref_scene *rs, vec3 p, vec3 ng, vec3 dir)
{
    float eps = 1e-5f * (rs->radius + fmaxf(fabsf(p.x), fmaxf(fabsf(p.y), fabsf(p.z))));
    return v3_add(p, v3_scale(ng, v3_dot(dir, ng) > 0.0f ? eps : -eps));
}

/* The pixel x projects into, the unit direction wo from x to the eye, the distance d and the
   pinhole's importance without the surface cosine, 1 / (d^2 cos_cam^3 A_pix). False off screen. */
static bool project(const gk_ref_scene *rs, vec3 x, int *px, int *py, vec3 *wo, float *d, float *we)
{
    vec3 to_eye = v3_sub(rs->eye, x);
    float d2 = v3_dot(to_eye, to_eye);
    if (d2 <= 0.0f)
        return false;
    *d = sqrtf(d2);
    *wo = v3_scale(to_eye, 1.0f / *d);
    vec3 dir = v3_scale(*wo, -1.0f); /* from the eye to x */
    float cos_cam = v3_dot(dir, rs->fwd);
    if (cos_cam <= 1e-6f)
        return false;
    float sx = v3_dot(dir, rs->right) / cos_cam / rs->tan_x;
    float sy = v3_dot(dir, rs->up) / cos_cam / rs->tan_y;
    if (sx <= -1.0f || sx >= 1.0f || sy <= -1.0f || sy >= 1.0f)
        return false;
    *px = (int)((sx + 1.0f) * 0.5f * (float)rs->width);
    *py = (int)((1.0f - sy) * 0.5f * (float)rs->height);
    if (*px < 0 || *py < 0 || *px >= rs->width || *py >= rs->height)
        return false;
    float a_pix = (2.0f * rs->tan_x / (float)rs->width) * (2.0f * rs->tan_y / (float)rs->height);
    *we = 1.0f / (d2 * cos_cam * cos_cam * cos_cam * a_pix);
    return true;
}

static void connect_camera(const gk_ref_scene *rs, const gk_surface *sf, vec3 x, vec3 w_in, vec3 flux,
                           gk_splat_fn splat, void *ctx, gk_trace_stats *st)
{
    int px, py;
    vec3 wo;
    float d, we;
    if (!project(rs, x, &px, &py, &wo, &d, &we))
        return;
    float pdf;
    vec3 f = gk_bsdf_eval(sf, wo, w_in, &pdf);
    if (f.x <= 0.0f && f.y <= 0.0f && f.z <= 0.0f)
        return;
    st->rays++;
    /* occluded toward the eye unless what is in the way is a single-sided back face the camera
       looks through (gk_scene_camera_sees; asked only then, so other scenes trace as before) */
    if (gk_scene_occluded(rs, offset_point(rs, x, sf->ng, wo), wo, d * (1.0f - 1e-4f)) &&
        !gk_scene_camera_sees(rs, x))
        return;
    float cos_x = fabsf(v3_dot(sf->ng, wo));
    vec3 tr = gk_medium_transmittance(&rs->medium, x, wo, d);
    splat(ctx, px, py, v3_scale(v3_mul(v3_mul(flux, f), tr), we * cos_x));
}

/* Clips [*t0, *t1] of o + t dir to the camera's view frustum (the four side planes through the eye):
   each is a half-space f0 + f1 t <= 0. False when nothing is left. */
static bool clip_to_frustum(const gk_ref_scene *rs, vec3 o, vec3 dir, float *t0, float *t1)
{
    vec3 rel = v3_sub(o, rs->eye);
    float fw0 = v3_dot(rel, rs->fwd), fw1 = v3_dot(dir, rs->fwd);
    float r0 = v3_dot(rel, rs->right), r1 = v3_dot(dir, rs->right);
    float u0 = v3_dot(rel, rs->up), u1 = v3_dot(dir, rs->up);
    const float f0[4] = {r0 - rs->tan_x * fw0, -r0 - rs->tan_x * fw0, u0 - rs->tan_y * fw0, -u0 - rs->tan_y * fw0};
    const float f1[4] = {r1 - rs->tan_x * fw1, -r1 - rs->tan_x * fw1, u1 - rs->tan_y * fw1, -u1 - rs->tan_y * fw1};
    for (int k = 0; k < 4; k++) {
        if (f1[k] == 0.0f) {
            if (f0[k] > 0.0f)
                return false;
            continue;
        }
        float tz = -f0[k] / f1[k];
        if (f1[k] > 0.0f)
            *t1 = fminf(*t1, tz);
        else
            *t0 = fmaxf(*t0, tz);
    }
    return *t1 > *t0;
}

/* Volume caustics: one point x on the segment o + t dir, t in [0, tmax], scattered towards the
   camera. The point is drawn by equi-angular sampling around the eye (Kulla and Fajardo 2012,
   "Importance sampling techniques for path tracing in participating media"): pdf(t) =
   D / ((theta_b - theta_a) (D^2 + (t - t_c)^2)), with t_c the segment's closest approach to the eye
   at distance D, which cancels the 1/d^2 of the pinhole's importance, over the part of the segment
   inside the view frustum (every sample lands on the image). (Drawing t by transmittance
   instead leaves that 1/d^2: points next to the camera have infinite variance, measured noise
   floor 350% on a mirror in fog.) Draws one random number whenever the segment overlaps the
   medium (whatever is then splatted, for the stream's alignment). */
static void connect_camera_medium(const gk_ref_scene *rs, vec3 o, vec3 dir, float tmax, vec3 flux, bool wanted,
                                  gk_rng *rng, gk_splat_fn splat, void *ctx, gk_trace_stats *st)
{
    const gk_ref_medium *m = &rs->medium;
    float t0, t1;
    if (!gk_medium_clip(m, o, dir, tmax, &t0, &t1))
        return;
    float u = gk_rng_float(rng);
    if (!wanted || v3_maxc(m->sigma_s) <= 0.0f || !clip_to_frustum(rs, o, dir, &t0, &t1))
        return;
    float tc = v3_dot(v3_sub(rs->eye, o), dir);
    float D = v3_len(v3_sub(rs->eye, v3_add(o, v3_scale(dir, tc))));
    if (D < 1e-6f * (rs->radius + 1.0f))
        return; /* the segment runs through the pinhole: it projects onto one point, measure zero */
    float ta = atanf((t0 - tc) / D), tb = isinf(t1) ? 0.5f * GK_PI : atanf((t1 - tc) / D);
    if (!(tb > ta))
        return;
    float th = ta + u * (tb - ta);
    float t = tc + D * tanf(th);
    float pdf = D / ((tb - ta) * (D * D + (t - tc) * (t - tc)));
    if (!(t >= t0 && t <= t1) || !(pdf > 0.0f))
        return;
    vec3 x = v3_add(o, v3_scale(dir, t));
    int px, py;
    vec3 wo;
    float d, we;
    if (!project(rs, x, &px, &py, &wo, &d, &we))
        return;
    st->rays++;
    if (gk_scene_occluded(rs, x, wo, d * (1.0f - 1e-4f)) && !gk_scene_camera_sees(rs, x))
        return;
    vec3 tr_in = gk_medium_transmittance(m, o, dir, t);
    vec3 tr_out = gk_medium_transmittance(m, x, wo, d);
    float ph = gk_phase_hg(m->g, v3_dot(dir, wo));
    vec3 v = v3_mul(v3_mul(v3_mul(flux, tr_in), tr_out), m->sigma_s);
    splat(ctx, px, py, v3_scale(v, ph * we / pdf));
}

void gk_trace_light(const gk_ref_scene *rs, const gk_caustic_emitter *em, unsigned terms, int max_depth,
                    int max_specular, gk_rng *rng, gk_splat_fn splat, void *ctx, gk_trace_stats *st)
{
    vec3 o, d, flux;
    int li;
    if (em ? !gk_caustic_photon(rs, em, rng, &o, &d, &flux, &li) : !gk_light_photon(rs, rng, &o, &d, &flux, &li))
        return;
    int n_specular = 0;
    for (int depth = 0; depth < max_depth; depth++) {
        gk_scene_hit h;
        st->rays++;
        bool hit = gk_scene_intersect(rs, o, d, INFINITY, &h);
        bool within_specular = max_specular == GK_BOUNCES_UNLIMITED || n_specular <= max_specular;
        /* A specular segment through the medium: its volume caustic (L S+ V E). */
        if (n_specular > 0 && rs->medium.present)
            connect_camera_medium(rs, o, d, hit ? h.t : INFINITY, flux,
                                  (terms & GK_TERM_VCAUSTICS) && within_specular, rng, splat, ctx, st);
        if (!hit || h.light >= 0)
            return;
        if (depth == 0 && (rs->lights[li].kind == GK_REF_POINT || rs->lights[li].kind == GK_REF_SPOT))
            flux = v3_scale(flux, gk_light_window(&rs->lights[li], h.t));
        /* The photon reaches the surface unscattered (scattered photons belong to the terms the
           eye pass renders). */
        flux = v3_mul(flux, gk_medium_transmittance(&rs->medium, o, d, h.t));
        vec3 x = v3_add(o, v3_scale(d, h.t));
        gk_surface sf;
        gk_surface_init(&sf, rs, &rs->tris[h.tri], h.b1, h.b2);
        vec3 w_in = v3_scale(d, -1.0f);
        /* First diffuse vertex after a specular chain: connect it to the eye (L S+ D E). */
        if (n_specular > 0 && gk_surface_has_smooth_part(&sf) && within_specular && (terms & GK_TERM_SURFACES))
            connect_camera(rs, &sf, x, w_in, flux, splat, ctx, st);
        /* Continue only through delta lobes; a non-delta bounce would make a second D vertex,
           which the eye pass already counts (indirect). */
        gk_bsdf_sample bs;
        if (!gk_bsdf_sample_dir(&sf, w_in, false, rng, &bs) || !bs.delta)
            return;
        n_specular++;
        flux = v3_mul(flux, bs.weight);
        o = offset_point(rs, x, sf.ng, bs.wi);
        d = bs.wi;
        if (depth >= 3) {
            /* Russian roulette by the last bounce's reflectance (flux is absolute, so its own size
               says nothing about how much the path still matters). */
            float qw = fminf(0.95f, v3_maxc(bs.weight));
            if (gk_rng_float(rng) >= qw)
                return;
            flux = v3_scale(flux, 1.0f / qw);
        }
    }
}
