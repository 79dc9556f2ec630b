// THE BRDF (app/core/brdf_spec.md): glTF metallic-roughness, GGX + Smith height-correlated
// visibility + Schlick Fresnel, diffuse (1 - metallic) base / pi without a (1 - F) factor.
// highp: n.h near 1 with alpha^2 = 6e-6 cancels catastrophically in fp16.
const highp float GK_PI = 3.14159265358979;

highp float gk_alpha(highp float roughness) { return max(roughness * roughness, 0.0025); }

highp vec3 gk_fresnel(highp vec3 f0, highp float vh) { return f0 + (1.0 - f0) * pow(1.0 - vh, 5.0); }

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

highp vec3 gk_brdf_diffuse(highp vec3 base, highp float metallic) { return (1.0 - metallic) * base / GK_PI; }

// Specular part F D V; d_scale multiplies D (representative-point energy normalisation, 1 otherwise).
highp vec3 gk_brdf_specular(highp vec3 n, highp vec3 v, highp vec3 l, highp vec3 base, highp float metallic,
                            highp float roughness, highp float d_scale)
{
    highp float nl = dot(n, l);
    if (nl <= 0.0)
        return vec3(0.0);
    highp float nv = max(dot(n, v), 1e-4);
    highp vec3 h = normalize(v + l);
    highp float alpha = gk_alpha(roughness);
    highp vec3 f0 = mix(vec3(0.04), base, metallic);
    highp vec3 F = gk_fresnel(f0, clamp(dot(v, h), 0.0, 1.0));
    return F * (gk_ggx_d(clamp(dot(n, h), 0.0, 1.0), alpha) * d_scale) * gk_smith_v(nl, nv, alpha);
}

highp vec3 gk_brdf(highp vec3 n, highp vec3 v, highp vec3 l, highp vec3 base, highp float metallic, highp float roughness)
{
    if (dot(n, l) <= 0.0)
        return vec3(0.0);
    return gk_brdf_diffuse(base, metallic) + gk_brdf_specular(n, v, l, base, metallic, roughness, 1.0);
}
