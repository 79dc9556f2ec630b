/* The shared BRDF (brdf_spec.md: glTF 2.0 Appendix B with KHR_materials_specular) and its sampling
 * for the path tracer (see materials.h). */
#include "materials.h"

#include <math.h>
#include <string.h>

#include "core/tonemap.h"

static float lum3(vec3 c) { return gk_luminance(c.x, c.y, c.z); }
static float clamp01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

/* A texel index under a glTF wrap mode (GL's rules, ES 3.2 §8.14.2): repeat takes i mod n, clamp
 * the nearest edge texel, mirror reflects every other period (-1 -> 0, n -> n - 1). */
static int wrap_texel(int i, int n, enum gk_wrap mode)
{
    if (mode == GK_WRAP_CLAMP)
        return i < 0 ? 0 : (i >= n ? n - 1 : i);
    if (mode == GK_WRAP_MIRROR) {
        int m = (i % (2 * n) + 2 * n) % (2 * n);
        return m < n ? m : 2 * n - 1 - m;
    }
    return (i % n + n) % n;
}

/* The texture's glTF sampler as the GLES renderer's textures do it (app/render/scene_gpu.c: no
 * mipmaps, GL_NEAREST or GL_LINEAR, GL_REPEAT, GL_CLAMP_TO_EDGE or GL_MIRRORED_REPEAT), so both
 * renderers see the same colour at every point; texel centres lie at (i + 0.5) / size. RGBA into
 * out, white without a texture. */
static void tex_bilinear(const gk_ref_scene *rs, int tex, float u, float v, float out[4])
{
    if (tex < 0 || tex >= rs->n_textures || !rs->textures[tex].rgba) {
        out[0] = out[1] = out[2] = out[3] = 1.0f;
        return;
    }
    const gk_texture *t = &rs->textures[tex];
    /* far outside [0, 1] only the period matters; keeps the int conversion in range (mirror: 2) */
    if (t->wrap_s != GK_WRAP_CLAMP && fabsf(u) > 1e4f)
        u -= 2.0f * floorf(u / 2.0f);
    if (t->wrap_t != GK_WRAP_CLAMP && fabsf(v) > 1e4f)
        v -= 2.0f * floorf(v / 2.0f);
    u = fmaxf(fminf(u, 1e4f), -1e4f);
    v = fmaxf(fminf(v, 1e4f), -1e4f);
    for (int c = 0; c < 4; c++)
        out[c] = 0.0f;
    if (t->nearest) {
        int xi = wrap_texel((int)floorf(u * (float)t->width), t->width, t->wrap_s);
        int yj = wrap_texel((int)floorf(v * (float)t->height), t->height, t->wrap_t);
        const float *p = &t->rgba[4 * ((size_t)yj * (size_t)t->width + (size_t)xi)];
        for (int c = 0; c < 4; c++)
            out[c] = p[c];
        return;
    }
    float x = u * (float)t->width - 0.5f, y = v * (float)t->height - 0.5f;
    float fx = floorf(x), fy = floorf(y), wx = x - fx, wy = y - fy;
    int x0 = (int)fx, y0 = (int)fy;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int xi = wrap_texel(x0 + i, t->width, t->wrap_s);
            int yj = wrap_texel(y0 + j, t->height, t->wrap_t);
            float w = (i ? wx : 1.0f - wx) * (j ? wy : 1.0f - wy);
            const float *p = &t->rgba[4 * ((size_t)yj * (size_t)t->width + (size_t)xi)];
            for (int c = 0; c < 4; c++)
                out[c] += w * p[c];
        }
}

static vec3 tex_sample(const gk_ref_scene *rs, int tex, float u, float v)
{
    float p[4];
    tex_bilinear(rs, tex, u, v, p);
    return v3(p[0], p[1], p[2]);
}

static float tex_alpha(const gk_ref_scene *rs, int tex, float u, float v)
{
    float p[4];
    tex_bilinear(rs, tex, u, v, p);
    return p[3];
}

/* The UV a texture slot reads at barycentrics (b1, b2): its set (TEXCOORD_0 or _1), then its
 * KHR_texture_transform (gk_tex_uv); set 0 untransformed when xf is NULL. */
static void slot_uv(const gk_ref_tri *t, const gk_tex_uv *xf, float b1, float b2, float *u, float *v)
{
    float b0 = 1.0f - b1 - b2;
    const float(*uv)[2] = xf && xf->texcoord == 1 ? t->uv1 : t->uv;
    float u0 = b0 * uv[0][0] + b1 * uv[1][0] + b2 * uv[2][0];
    float v0 = b0 * uv[0][1] + b1 * uv[1][1] + b2 * uv[2][1];
    if (xf)
        gk_tex_uv_apply(xf, u0, v0, u, v);
    else
        *u = u0, *v = v0;
}

vec3 gk_tri_texture_rgb(const gk_ref_scene *rs, const gk_ref_tri *t, int tex, const gk_tex_uv *xf, float b1, float b2)
{
    float u, v;
    slot_uv(t, xf, b1, b2, &u, &v);
    return tex_sample(rs, tex, u, v);
}

/* A uniform number in [0, 1) from a hit: the barycentrics' bits and the triangle, hashed
   (lowbias32, Wellons). Rays hit a surface at continuously varying points, so over a pixel's samples
   or a light's shadow rays it acts as a fresh random number, with no RNG stream to thread through
   the BVH (and the streams of every other scene stay as they were). */
static float hit_hash(uint32_t tri, float b1, float b2)
{
    uint32_t x, y;
    memcpy(&x, &b1, sizeof x);
    memcpy(&y, &b2, sizeof y);
    uint32_t h = x * 0x9e3779b9u ^ (y + 0x7f4a7c15u) * 0x85ebca6bu ^ tri * 0xc2b2ae35u;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}

bool gk_tri_alpha_accept(const void *ctx, uint32_t tri, float b1, float b2)
{
    const gk_ref_scene *rs = ctx;
    const gk_ref_tri *t = &rs->tris[tri];
    const gk_material *m = &rs->materials[t->material];
    float b0 = 1.0f - b1 - b2;
    float a = m->base_color[3] * (b0 * t->color[0][3] + b1 * t->color[1][3] + b2 * t->color[2][3]);
    if (m->base_color_tex >= 0) {
        float u, v;
        slot_uv(t, &m->tex_uv[GK_SLOT_BASE], b1, b2, &u, &v);
        a *= tex_alpha(rs, m->base_color_tex, u, v);
    }
    if (m->alpha_blend) /* stochastic transparency: there with probability alpha, for every ray */
        return hit_hash(tri, b1, b2) < a;
    return a >= m->alpha_cutoff;
}

void gk_surface_init(gk_surface *sf, const gk_ref_scene *rs, const gk_ref_tri *t, float b1, float b2)
{
    const gk_material *m = &rs->materials[t->material];
    float b0 = 1.0f - b1 - b2;
    sf->base = v3(m->base_color[0], m->base_color[1], m->base_color[2]);
    /* glTF: base colour = factor x texture x vertex colour (COLOR_0), as the G-buffer does. */
    for (int c = 0; c < 3; c++)
        (&sf->base.x)[c] *= b0 * t->color[0][c] + b1 * t->color[1][c] + b2 * t->color[2][c];
    sf->metallic = m->metallic;
    sf->roughness = m->roughness;
    if (m->base_color_tex >= 0)
        sf->base = v3_mul(sf->base, gk_tri_texture_rgb(rs, t, m->base_color_tex, &m->tex_uv[GK_SLOT_BASE], b1, b2));
    if (m->metallic_roughness_tex >= 0) {
        vec3 mr = gk_tri_texture_rgb(rs, t, m->metallic_roughness_tex, &m->tex_uv[GK_SLOT_MR], b1, b2);
        sf->roughness *= mr.y;
        sf->metallic *= mr.z;
    }
    sf->metallic = clamp01(sf->metallic);
    sf->roughness = clamp01(sf->roughness);
    float r = fmaxf(sf->roughness, 0.05f);
    sf->alpha = r * r; /* >= 0.0025 as the spec clamps */
    sf->transmission = clamp01(m->transmission);
    /* ior 1 is index-matched glass (no bending, no reflection); only the extension's 0 falls back. */
    sf->ior = m->ior >= 1.0f ? m->ior : 1.5f;
    /* KHR_materials_specular with KHR_materials_ior: the dielectric lobe's weight and F0 colour. */
    float su, sv;
    slot_uv(t, &m->tex_uv[GK_SLOT_SPECULAR], b1, b2, &su, &sv);
    sf->spec_weight = fmaxf(m->specular, 0.0f) * tex_alpha(rs, m->specular_tex, su, sv);
    vec3 spec_color = v3_mul(v3(m->specular_color[0], m->specular_color[1], m->specular_color[2]),
                             gk_tri_texture_rgb(rs, t, m->specular_color_tex, &m->tex_uv[GK_SLOT_SPECULAR_COLOR], b1, b2));
    float r_ior = (m->ior - 1.0f) / (m->ior + 1.0f);
    vec3 c0 = v3_scale(spec_color, r_ior * r_ior);
    sf->c0 = v3(fminf(c0.x, 1.0f), fminf(c0.y, 1.0f), fminf(c0.z, 1.0f));
    if (rs->diffuse_only) {
        sf->metallic = 0.0f;
        sf->transmission = 0.0f;
        sf->spec_weight = 0.0f;
    }
    sf->diffuse_only = rs->diffuse_only;
    sf->c0_max = fmaxf(sf->c0.x, fmaxf(sf->c0.y, sf->c0.z));
    sf->f0 = v3_lerp(v3_scale(sf->c0, sf->spec_weight), sf->base, sf->metallic);
    sf->f90 = sf->spec_weight + (1.0f - sf->spec_weight) * sf->metallic;
    sf->mirror = sf->metallic > 0.5f && sf->roughness < 0.05f;
    sf->p_dielectric = (sf->transmission > 0.0f && sf->roughness < 0.05f) ? sf->transmission : 0.0f;
    float diffuse = (1.0f - sf->metallic) * lum3(sf->base);
    sf->p_mirror = sf->mirror ? (diffuse > 0.0f ? 0.5f : 1.0f) : 0.0f;
    vec3 n = v3_add(v3_add(v3_scale(t->n[0], b0), v3_scale(t->n[1], b1)), v3_scale(t->n[2], b2));
    sf->ng = t->ng;
    sf->n = v3_len(n) > 1e-12f ? v3_norm(n) : t->ng;
    if (m->normal_tex >= 0) {
        /* glTF normalTexture, the same frame as the G-buffer (shaders_gles/gbuffer/gbuffer.frag):
           tangent-space normal, XY scaled, T made orthogonal to N, B = (N x T) w. */
        vec3 mt = v3_sub(v3_scale(gk_tri_texture_rgb(rs, t, m->normal_tex, &m->tex_uv[GK_SLOT_NORMAL], b1, b2), 2.0f), v3(1, 1, 1));
        mt.x *= m->normal_scale, mt.y *= m->normal_scale;
        vec3 tg = v3(0, 0, 0);
        float w = b0 * t->tangent[0][3] + b1 * t->tangent[1][3] + b2 * t->tangent[2][3];
        for (int k = 0; k < 3; k++)
            tg = v3_add(tg, v3_scale(v3(t->tangent[k][0], t->tangent[k][1], t->tangent[k][2]), k == 0 ? b0 : k == 1 ? b1 : b2));
        tg = v3_sub(tg, v3_scale(sf->n, v3_dot(sf->n, tg)));
        if (v3_len(tg) > 1e-6f) {
            tg = v3_norm(tg);
            vec3 bt = v3_scale(v3_cross(sf->n, tg), w < 0.0f ? -1.0f : 1.0f);
            vec3 nm = v3_add(v3_add(v3_scale(tg, mt.x), v3_scale(bt, mt.y)), v3_scale(sf->n, mt.z));
            if (v3_len(nm) > 1e-6f)
                sf->n = v3_norm(nm);
        }
    }
    /* Keep the shading normal on the geometric normal's side, so flipping by the geometric side
       below stays consistent. */
    if (v3_dot(sf->n, sf->ng) < 0.0f)
        sf->n = v3_scale(sf->n, -1.0f);
}

bool gk_surface_has_smooth_part(const gk_surface *sf) { return sf->p_dielectric < 1.0f && sf->p_mirror < 1.0f; }

/* The whole specular Fresnel term F = F0 + (F90 - F0) (1 - cos)^5 (brdf_spec.md). */
static vec3 schlick(const gk_surface *sf, float cos_t)
{
    float m = powf(clamp01(1.0f - cos_t), 5.0f);
    return v3_add(sf->f0, v3_scale(v3_sub(v3(sf->f90, sf->f90, sf->f90), sf->f0), m));
}

/* The diffuse lobe's weight: (1 - metallic) (1 - w max(Fd)), fresnel_mix's share left to the base
   layer, with Fd = c0 + (1 - c0)(1 - v.h)^5 the dielectric Fresnel before the weight. */
static float diffuse_weight(const gk_surface *sf, float vh)
{
    float fd = sf->c0_max + (1.0f - sf->c0_max) * powf(clamp01(1.0f - vh), 5.0f);
    return (1.0f - sf->metallic) * (1.0f - sf->spec_weight * fd);
}

/* Whether F can be non-zero: a glossy lobe to evaluate and sample. */
static bool has_glossy_lobe(const gk_surface *sf)
{
    return !sf->mirror && !sf->diffuse_only && (sf->spec_weight > 0.0f || sf->metallic > 0.0f);
}

static float ggx_d(float nh, float a2)
{
    float d = nh * nh * (a2 - 1.0f) + 1.0f;
    return a2 / (GK_PI * d * d);
}

static float smith_v(float nl, float nv, float a2)
{
    float gv = nl * sqrtf(nv * nv * (1.0f - a2) + a2);
    float gl = nv * sqrtf(nl * nl * (1.0f - a2) + a2);
    return 0.5f / (gv + gl);
}

static float smith_g1(float nv, float a2) { return 2.0f * nv / (nv + sqrtf(a2 + (1.0f - a2) * nv * nv)); }

/* Probability of the GGX lobe (vs diffuse) among the non-delta lobes, from the lobes' albedos. */
static float p_specular(const gk_surface *sf, float nv)
{
    if (!has_glossy_lobe(sf))
        return 0.0f;
    float spec = lum3(schlick(sf, nv));
    float diff = diffuse_weight(sf, nv) * lum3(sf->base);
    if (diff <= 0.0f)
        return 1.0f;
    float p = spec / (spec + diff);
    return p < 0.1f ? 0.1f : (p > 0.9f ? 0.9f : p);
}

/* Normal on wo's side: surfaces scatter on both faces (no back-face culling in the tracer). */
static vec3 side_normal(const gk_surface *sf, vec3 wo, vec3 *ng)
{
    bool back = v3_dot(wo, sf->ng) < 0.0f;
    *ng = back ? v3_scale(sf->ng, -1.0f) : sf->ng;
    return back ? v3_scale(sf->n, -1.0f) : sf->n;
}

vec3 gk_bsdf_eval(const gk_surface *sf, vec3 wo, vec3 wi, float *pdf)
{
    *pdf = 0.0f;
    vec3 ng;
    vec3 n = side_normal(sf, wo, &ng);
    float nl = v3_dot(n, wi), nv = v3_dot(n, wo);
    if (nl <= 0.0f || nv <= 0.0f || v3_dot(ng, wi) <= 0.0f)
        return v3(0, 0, 0);
    float opaque = 1.0f - sf->p_dielectric;
    float smooth_sel = opaque * (1.0f - sf->p_mirror);
    if (smooth_sel <= 0.0f)
        return v3(0, 0, 0);
    vec3 h = v3_norm(v3_add(wo, wi));
    float vh = fmaxf(v3_dot(wo, h), 0.0f);
    vec3 f = v3_scale(sf->base, diffuse_weight(sf, vh) / GK_PI);
    float ps = p_specular(sf, nv);
    float pdf_spec = 0.0f;
    if (has_glossy_lobe(sf)) {
        float nh = fmaxf(v3_dot(n, h), 0.0f);
        float a2 = sf->alpha * sf->alpha;
        float d = ggx_d(nh, a2);
        vec3 F = schlick(sf, vh);
        f = v3_add(f, v3_scale(F, d * smith_v(nl, nv, a2)));
        pdf_spec = smith_g1(nv, a2) * d / (4.0f * nv);
    }
    *pdf = smooth_sel * ((1.0f - ps) * nl / GK_PI + ps * pdf_spec);
    return v3_scale(f, opaque);
}

/* Heitz 2018, "Sampling the GGX Distribution of Visible Normals", isotropic; local frame z = n. */
static vec3 sample_vndf(vec3 wo, float alpha, float u1, float u2)
{
    vec3 vh = v3_norm(v3(alpha * wo.x, alpha * wo.y, wo.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0f ? v3_scale(v3(-vh.y, vh.x, 0.0f), 1.0f / sqrtf(lensq)) : v3(1, 0, 0);
    vec3 t2 = v3_cross(vh, t1);
    float r = sqrtf(u1), phi = 2.0f * GK_PI * u2;
    float p1 = r * cosf(phi), p2 = r * sinf(phi);
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * sqrtf(fmaxf(0.0f, 1.0f - p1 * p1)) + s * p2;
    vec3 nh = v3_add(v3_add(v3_scale(t1, p1), v3_scale(t2, p2)), v3_scale(vh, sqrtf(fmaxf(0.0f, 1.0f - p1 * p1 - p2 * p2))));
    return v3_norm(v3(alpha * nh.x, alpha * nh.y, fmaxf(1e-6f, nh.z)));
}

float gk_fresnel_dielectric(float cos_i, float eta)
{
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f)
        return 1.0f;
    float cos_t = sqrtf(1.0f - sin2_t);
    float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

static vec3 reflect_about(vec3 wo, vec3 n) { return v3_sub(v3_scale(n, 2.0f * v3_dot(wo, n)), wo); }

bool gk_bsdf_sample_dir(const gk_surface *sf, vec3 wo, bool radiance_mode, gk_rng *rng, gk_bsdf_sample *out)
{
    float u0 = gk_rng_float(rng), u1 = gk_rng_float(rng), u2 = gk_rng_float(rng);
    vec3 ng;
    vec3 n = side_normal(sf, wo, &ng);
    float nv = v3_dot(n, wo);
    if (u0 < sf->p_dielectric) {
        /* Smooth dielectric: entering when wo is on the front face (by winding). */
        bool entering = v3_dot(wo, sf->ng) > 0.0f;
        float eta = entering ? sf->ior : 1.0f / sf->ior; /* eta_t / eta_i */
        float cos_i = fabsf(v3_dot(wo, n));
        float fr = gk_fresnel_dielectric(cos_i, eta);
        out->delta = true;
        out->pdf = 0.0f;
        if (u1 < fr) {
            out->wi = reflect_about(wo, n);
            out->weight = v3(1, 1, 1);
        } else {
            float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
            float cos_t = sqrtf(fmaxf(0.0f, 1.0f - sin2_t));
            out->wi = v3_norm(v3_sub(v3_scale(v3_scale(wo, -1.0f), 1.0f / eta), v3_scale(n, cos_t - cos_i / eta)));
            float scale = radiance_mode ? 1.0f / (eta * eta) : 1.0f;
            out->weight = v3_scale(sf->base, scale);
        }
        return true;
    }
    if (nv <= 0.0f)
        return false;
    float u_opaque = (u0 - sf->p_dielectric) / (1.0f - sf->p_dielectric); /* reuse u0, rescaled */
    if (u_opaque < sf->p_mirror) {
        out->delta = true;
        out->pdf = 0.0f;
        out->wi = reflect_about(wo, n);
        if (v3_dot(out->wi, ng) <= 0.0f)
            return false;
        out->weight = v3_scale(schlick(sf, nv), 1.0f / sf->p_mirror);
        return true;
    }
    float ps = p_specular(sf, nv);
    float u_lobe = (u_opaque - sf->p_mirror) / (1.0f - sf->p_mirror);
    vec3 t, b;
    gk_onb(n, &t, &b);
    vec3 wi;
    if (u_lobe < ps) {
        vec3 wol = gk_to_local(wo, t, b, n);
        vec3 h = gk_to_world(sample_vndf(wol, sf->alpha, u1, u2), t, b, n);
        wi = reflect_about(wo, h);
    } else {
        wi = gk_to_world(gk_sample_cosine_hemisphere(u1, u2), t, b, n);
    }
    float pdf;
    vec3 f = gk_bsdf_eval(sf, wo, wi, &pdf);
    if (pdf <= 0.0f || (f.x <= 0.0f && f.y <= 0.0f && f.z <= 0.0f))
        return false;
    out->wi = wi;
    out->delta = false;
    out->pdf = pdf;
    out->weight = v3_scale(f, v3_dot(n, wi) / pdf);
    return true;
}
