/* The BRDF of app/core/brdf_spec.md for the path tracer: glTF 2.0 Appendix B, Lambert and GGX
 * (height-correlated Smith, Schlick Fresnel) mixed by fresnel_mix (the diffuse weighted by
 * 1 - w max(Fd), KHR_materials_specular's weight w and F0 colour), sampled by one-sample mixture of cosine-weighted diffuse and
 * GGX visible normals (Heitz 2018); delta mirror (metallic > 0.5, roughness < 0.05) with reflectance
 * F(F0, cos); smooth dielectric (transmission > 0, roughness < 0.05) weighted by `transmission`,
 * Fresnel-chosen reflection or refraction, refraction tinted by base colour.
 * Known simplifications: rough transmission (roughness >= 0.05) is rendered as the opaque BRDF; the
 * smooth dielectric's Fresnel ignores KHR_materials_specular (brdf_spec.md). */
#ifndef GK_REF_MATERIALS_H
#define GK_REF_MATERIALS_H

#include <stdbool.h>

#include "ref_scene.h"
#include "sample.h"

typedef struct gk_surface {
    vec3 base;             /* linear base colour (factor x texture) */
    float metallic, roughness, alpha;
    float transmission, ior;
    float spec_weight;     /* KHR_materials_specular: specularFactor x specularTexture.a */
    vec3 c0;               /* dielectric F0 colour: min(((ior-1)/(ior+1))^2 specular colour, 1) */
    float c0_max;          /* its largest component (fresnel_mix's max_value) */
    vec3 f0;               /* F0 = mix(spec_weight c0, base, metallic) */
    float f90;             /* F90 = mix(spec_weight, 1, metallic) */
    bool mirror;           /* the specular lobe is a delta mirror */
    bool diffuse_only;     /* gk_ref_scene.diffuse_only: no GGX lobe */
    float p_dielectric;    /* probability of the delta dielectric lobe (= transmission if smooth) */
    float p_mirror;        /* within the opaque part: probability of the delta mirror */
    vec3 n;                /* shading normal, unit, as stored (front face by the mesh) */
    vec3 ng;               /* geometric normal, unit, front face by winding */
} gk_surface;

typedef struct gk_bsdf_sample {
    vec3 wi;               /* unit, away from the surface */
    vec3 weight;           /* f cos / pdf, including lobe choice */
    float pdf;             /* non-delta: solid-angle pdf of the whole non-delta part (for MIS) */
    bool delta;
} gk_bsdf_sample;

/* Texture `tex` (its glTF sampler; white when -1) at barycentrics (b1, b2) of triangle t, through
 * the slot's UV set and KHR_texture_transform xf (NULL: TEXCOORD_0 as is). */
/* The BVH's any-hit test (gk_bvh.accept, ctx the gk_ref_scene): true where triangle tri of an
 * alpha-masked material is there, its alpha (base colour factor x texture x COLOR_0) at barycentrics
 * (u, v) at least the cutoff, as the G-buffer's discard and the shadow maps' decide. For an
 * alphaMode BLEND material, true with probability alpha (stochastic transparency: camera, shadow and
 * bounce rays alike pass it with probability 1 - alpha; the draw is a hash of the hit point). */
bool gk_tri_alpha_accept(const void *ctx, uint32_t tri, float u, float v);

vec3 gk_tri_texture_rgb(const gk_ref_scene *rs, const gk_ref_tri *t, int tex, const gk_tex_uv *xf, float b1, float b2);
void gk_surface_init(gk_surface *sf, const gk_ref_scene *rs, const gk_ref_tri *t, float b1, float b2);

/* True when the surface has a non-delta part (light sampling and camera connections apply). */
bool gk_surface_has_smooth_part(const gk_surface *sf);

/* Non-delta part: f(wo, wi) (without the cosine) and, in *pdf, the probability density with which
 * gk_bsdf_sample would pick wi through its non-delta lobes. Reflection only. */
vec3 gk_bsdf_eval(const gk_surface *sf, vec3 wo, vec3 wi, float *pdf);

/* Unpolarised Fresnel reflectance of a smooth dielectric interface (the mean of the s and p
 * reflectances), for cos_i > 0 on the incident side and eta = eta_t / eta_i; 1 under total internal
 * reflection (sin_t >= 1). At normal incidence it is ((eta - 1) / (eta + 1))^2. */
float gk_fresnel_dielectric(float cos_i, float eta);

/* Samples the full BSDF. radiance_mode: eye paths (radiance is scaled by (eta_t/eta_i)^2 across
 * refraction); false for light paths (flux is not). Returns false when the path ends. */
bool gk_bsdf_sample_dir(const gk_surface *sf, vec3 wo, bool radiance_mode, gk_rng *rng, gk_bsdf_sample *out);

#endif
