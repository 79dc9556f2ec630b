// THE BRDF (app/core/brdf_spec.md): glTF 2.0 Appendix B with KHR_materials_specular, the same as the
// path tracer's (app/ref/materials.c): GGX + Smith height-correlated visibility + Schlick Fresnel,
// mixed by fresnel_mix, so the diffuse lobe is weighted by (1 - metallic)(1 - w max(Fd)):
//   f = (1 - metallic)(1 - w max(Fd)) base/pi + F D V,   Fd = c0 + (1 - c0)(1 - v.h)^5,
//   F = F0 + (F90 - F0)(1 - v.h)^5,  F0 = mix(w c0, base, metallic),  F90 = mix(w, 1, metallic);
// w = specular weight (0: pure Lambert), c0 = dielectric F0 colour (0.04 for ior 1.5).
// highp: n.h near 1 with alpha^2 = 6e-6 cancels catastrophically in fp16.
const highp float GK_PI = 3.14159265358979;

// The material terms the BRDF needs (G-buffer: gbuffer.glsl gk_read_surface).
struct gk_brdf_material {
    highp vec3 base;
    highp float metallic;
    highp float roughness;
    highp float spec_weight;   // KHR_materials_specular: specularFactor x specularTexture.a
    highp vec3 c0;             // min(((ior-1)/(ior+1))^2 specular colour, 1)
};

highp float gk_alpha(highp float roughness) { return max(roughness * roughness, 0.0025); }

highp float gk_schlick_weight(highp float vh) { highp float m = 1.0 - vh; return (m * m) * (m * m) * m; }

// The whole specular Fresnel F at v.h.
highp vec3 gk_fresnel(gk_brdf_material m, highp float vh)
{
    highp vec3 f0 = mix(m.spec_weight * m.c0, m.base, m.metallic);
    highp float f90 = mix(m.spec_weight, 1.0, m.metallic);
    return f0 + (f90 - f0) * gk_schlick_weight(vh);
}

highp float gk_ggx_d(highp float nh, highp float alpha)
{
    highp float a2 = alpha * alpha;
    highp float d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (GK_PI * d * d);
}

highp float gk_smith_v(highp float nl, highp float nv, highp float alpha)
{
    highp float a2 = alpha * alpha;
    return 0.5 / (nl * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nl * nl * (1.0 - a2) + a2));
}

// Diffuse part (1 - metallic)(1 - w max(Fd)) base / pi for a Schlick weight s5 = (1 - v.h)^5.
highp vec3 gk_brdf_diffuse_s5(gk_brdf_material m, highp float s5)
{
    highp float c0_max = max(m.c0.r, max(m.c0.g, m.c0.b));
    highp float fd = c0_max + (1.0 - c0_max) * s5;
    return (1.0 - m.metallic) * (1.0 - m.spec_weight * fd) * m.base / GK_PI;
}

// Diffuse part for one light direction (v.h of that light).
highp vec3 gk_brdf_diffuse(gk_brdf_material m, highp float vh)
{
    return gk_brdf_diffuse_s5(m, gk_schlick_weight(clamp(vh, 0.0, 1.0)));
}

// Diffuse part for light gathered from the whole hemisphere (the GI methods): (1 - v.h)^5 averaged
// over cosine-weighted incident directions is 0.028 (1 - n.v)^2.6 within 6e-4 (fitted to numeric
// integration; checked in tests/unit/test_brdf_albedo.c). mu = n.v at a receiver; by reciprocity
// n.l for the light a VPL reflects to everything around it.
highp vec3 gk_brdf_diffuse_gathered(gk_brdf_material m, highp float mu)
{
    return gk_brdf_diffuse_s5(m, 0.028 * pow(1.0 - clamp(mu, 0.0, 1.0), 2.6));
}

// Specular part F D V; d_scale multiplies D (representative-point energy normalisation, 1 otherwise).
highp vec3 gk_brdf_specular(highp vec3 n, highp vec3 v, highp vec3 l, gk_brdf_material m, highp float d_scale)
{
    highp float nl = dot(n, l);
    if (nl <= 0.0)
        return vec3(0.0);
    highp float nv = max(dot(n, v), 1e-4);
    highp vec3 h = normalize(v + l);
    highp float alpha = gk_alpha(m.roughness);
    highp vec3 F = gk_fresnel(m, clamp(dot(v, h), 0.0, 1.0));
    return F * (gk_ggx_d(clamp(dot(n, h), 0.0, 1.0), alpha) * d_scale) * gk_smith_v(nl, nv, alpha);
}

highp vec3 gk_brdf(highp vec3 n, highp vec3 v, highp vec3 l, gk_brdf_material m)
{
    if (dot(n, l) <= 0.0)
        return vec3(0.0);
    highp float vh = clamp(dot(v, normalize(v + l)), 0.0, 1.0);
    return gk_brdf_diffuse(m, vh) + gk_brdf_specular(n, v, l, m, 1.0);
}
