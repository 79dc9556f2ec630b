/* Light tracing of caustics seen directly, L S+ D E (see trace.h).
 *
 * Measurement: a pixel's value is the mean radiance over its footprint on the image plane at
 * distance 1 from the pinhole, I = (1/A_pix) \int L(x -> eye) dA_plane. With dA_plane =
 * cos_x dA_x / (d^2 cos_cam^3) for a surface point x at distance d, seen at angle cam from the
 * optical axis, a photon of flux Phi arriving at x from wi adds
 *     Phi f(wo_eye, wi) cos_x / (d^2 cos_cam^3 A_pix)
 * to the pixel it projects into (the pinhole's importance We), divided by the number of photons. */
#include <math.h>

#include "caustic_emit.h"
#include "lights.h"
#include "materials.h"
#include "trace.h"

static vec3 offset_point(const gk_ref_scene *rs, vec3 p, vec3 ng, vec3 dir)
{
    float eps = 1e-5f * (rs->radius + fmaxf(fabsf(p.x), fmaxf(fabsf(p.y), fabsf(p.z))));
    return v3_add(p, v3_scale(ng, v3_dot(dir, ng) > 0.0f ? eps : -eps));
}

static void connect_camera(const gk_ref_scene *rs, const gk_surface *sf, vec3 x, vec3 w_in, vec3 flux,
                           gk_splat_fn splat, void *ctx, gk_trace_stats *st)
{
    vec3 to_eye = v3_sub(rs->eye, x);
    float d2 = v3_dot(to_eye, to_eye);
    if (d2 <= 0.0f)
        return;
    float d = sqrtf(d2);
    vec3 wo = v3_scale(to_eye, 1.0f / d);
    vec3 dir = v3_scale(wo, -1.0f); /* from the eye to x */
    float cos_cam = v3_dot(dir, rs->fwd);
    if (cos_cam <= 1e-6f)
        return;
    float sx = v3_dot(dir, rs->right) / cos_cam / rs->tan_x;
    float sy = v3_dot(dir, rs->up) / cos_cam / rs->tan_y;
    if (sx <= -1.0f || sx >= 1.0f || sy <= -1.0f || sy >= 1.0f)
        return;
    int px = (int)((sx + 1.0f) * 0.5f * (float)rs->width);
    int py = (int)((1.0f - sy) * 0.5f * (float)rs->height);
    if (px < 0 || py < 0 || px >= rs->width || py >= rs->height)
        return;
    float pdf;
    vec3 f = gk_bsdf_eval(sf, wo, w_in, &pdf);
    if (f.x <= 0.0f && f.y <= 0.0f && f.z <= 0.0f)
        return;
    st->rays++;
    if (gk_scene_occluded(rs, offset_point(rs, x, sf->ng, wo), wo, d * (1.0f - 1e-4f)))
        return;
    float a_pix = (2.0f * rs->tan_x / (float)rs->width) * (2.0f * rs->tan_y / (float)rs->height);
    float cos_x = fabsf(v3_dot(sf->ng, wo));
    float we = cos_x / (d2 * cos_cam * cos_cam * cos_cam * a_pix);
    splat(ctx, px, py, v3_scale(v3_mul(flux, f), we));
}

void gk_trace_light(const gk_ref_scene *rs, const gk_caustic_emitter *em, int max_depth, int max_specular, gk_rng *rng,
                    gk_splat_fn splat, void *ctx, gk_trace_stats *st)
{
    vec3 o, d, flux;
    int li;
    if (em ? !gk_caustic_photon(rs, em, rng, &o, &d, &flux, &li) : !gk_light_photon(rs, rng, &o, &d, &flux, &li))
        return;
    int n_specular = 0;
    for (int depth = 0; depth < max_depth; depth++) {
        gk_scene_hit h;
        st->rays++;
        if (!gk_scene_intersect(rs, o, d, INFINITY, &h) || h.light >= 0)
            return;
        if (depth == 0 && (rs->lights[li].kind == GK_REF_POINT || rs->lights[li].kind == GK_REF_SPOT))
            flux = v3_scale(flux, gk_light_window(&rs->lights[li], h.t));
        vec3 x = v3_add(o, v3_scale(d, h.t));
        gk_surface sf;
        gk_surface_init(&sf, rs, &rs->tris[h.tri], h.b1, h.b2);
        vec3 w_in = v3_scale(d, -1.0f);
        /* First diffuse vertex after a specular chain: connect it to the eye (L S+ D E). */
        if (n_specular > 0 && gk_surface_has_smooth_part(&sf) &&
            (max_specular == GK_BOUNCES_UNLIMITED || n_specular <= max_specular))
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
