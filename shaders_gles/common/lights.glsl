// One light's contribution to a G-buffer surface, in the reference's units (brdf_spec.md,
// app/scene/scene.h): cd for point/spot (E = I cos / d^2), lux for directional (E = lux cos),
// area lights emit L = I / area (nits) so their power equals the punctual light's.
// GK_LIGHT_KIND selects the light: 0 point, 1 spot, 2 directional, 3 sphere, 4 disc, 5 rect.
// GK_LIGHT_SPOT (defined for spot lights of any shape) masks by the spot cone, seen from the
// light's centre.
#include "common/area_lights.glsl"
#include "common/ltc.glsl"

uniform highp vec3 u_light_pos;
uniform highp vec3 u_light_dir;       // emitter axis (node -Z); directional: the travel direction
uniform highp vec3 u_light_u;         // node X (rect width axis)
uniform highp vec3 u_light_v;         // node Y (rect height axis)
uniform highp vec3 u_light_color;     // colour * intensity: cd or lux (can be large: highp)
uniform highp float u_light_range;    // 0 = infinite
uniform highp vec2 u_light_cone;      // cos(outer), cos(inner)
uniform highp float u_light_radius;   // sphere/disc radius (m), sun angular radius (rad)
uniform highp vec2 u_light_size;      // rect W, H (m)

highp float gk_spot_factor(highp vec3 to_p)
{
#ifdef GK_LIGHT_SPOT
    highp float c = dot(u_light_dir, normalize(to_p));
    highp float t = clamp((c - u_light_cone.x) / max(u_light_cone.y - u_light_cone.x, 1e-4), 0.0, 1.0);
    return t * t;
#else
    return 1.0;
#endif
}

// glTF's recommended range window, without the 1/d^2 (applied by the caller).
highp float gk_range_window(highp float d)
{
    if (u_light_range <= 0.0)
        return 1.0;
    highp float r = d / u_light_range;
    highp float w = clamp(1.0 - r * r * r * r, 0.0, 1.0);
    return w * w;
}

highp vec3 gk_light_radiance(gk_surface s)
{
    highp vec3 to_p = s.p - u_light_pos;
    highp float d2 = max(dot(to_p, to_p), 1e-8);
    highp float d = sqrt(d2);
#if GK_LIGHT_KIND == 2
    highp vec3 l = -u_light_dir;
    return gk_brdf(s.n, s.v, l, s.m) * u_light_color * max(dot(s.n, l), 0.0);
#elif GK_LIGHT_KIND == 0 || GK_LIGHT_KIND == 1
    highp vec3 l = -to_p / d;
    highp float e = max(dot(s.n, l), 0.0) * gk_spot_factor(to_p) * gk_range_window(d) / d2;
    return gk_brdf(s.n, s.v, l, s.m) * u_light_color * e;
#else
    highp float win = gk_spot_factor(to_p) * gk_range_window(d);
    if (win <= 0.0)
        return vec3(0.0);
    highp float e_over_l;     // irradiance / emitted radiance (a form factor times pi)
    highp vec3 l_rep;         // representative direction for the specular lobe
    highp float area_radius;  // radius of a disc of the same area (for the lobe widening)
    highp float radiance_scale;
#if GK_LIGHT_KIND == 3
    e_over_l = gk_sphere_irradiance(s.p, s.n, u_light_pos, u_light_radius);
    l_rep = gk_sphere_rep_dir(s.p, s.n, s.v, u_light_pos, u_light_radius);
    area_radius = u_light_radius;
    radiance_scale = 1.0 / (GK_PI * u_light_radius * u_light_radius);
#elif GK_LIGHT_KIND == 4
    if (dot(to_p, u_light_dir) <= 0.0)
        return vec3(0.0);  // one-sided: behind the emitter
    e_over_l = gk_disc_irradiance(s.p, s.n, u_light_pos, u_light_u, u_light_v, u_light_radius);
    l_rep = gk_planar_rep_dir(s.p, s.n, s.v, u_light_pos, u_light_dir, u_light_u, u_light_v,
                              vec2(u_light_radius), true);
    area_radius = u_light_radius;
    radiance_scale = 1.0 / (GK_PI * u_light_radius * u_light_radius);
#else
    if (dot(to_p, u_light_dir) <= 0.0)
        return vec3(0.0);
    e_over_l = gk_rect_irradiance(s.p, s.n, u_light_pos, u_light_u * (0.5 * u_light_size.x),
                                  u_light_v * (0.5 * u_light_size.y));
    radiance_scale = 1.0 / (u_light_size.x * u_light_size.y);
#endif
    highp vec3 e = u_light_color * (radiance_scale * e_over_l * win);
#if GK_LIGHT_KIND == 5
    // Rectangle: the GGX lobe by linearly transformed cosines (common/ltc.glsl), F applied as
    // F0 A + (F90 - F0) B; the diffuse lobe's fresnel_mix share (1 - w max(Fd)) taken towards the
    // light's centre (over a 0.8 x 0.5 m light at 1 m it differs from the irradiance-weighted mean
    // by 1.5e-4, tests/gpu/test_render_direct.c).
    highp vec2 ab;
    highp float lobe = gk_ltc_rect(s.p, s.n, s.v, s.m.roughness, u_light_pos, u_light_u * (0.5 * u_light_size.x),
                                   u_light_v * (0.5 * u_light_size.y), ab);
    highp vec3 f0 = mix(s.m.spec_weight * s.m.c0, s.m.base, s.m.metallic);
    highp float f90 = mix(s.m.spec_weight, 1.0, s.m.metallic);
    highp float vh_c = clamp(dot(s.v, normalize(s.v - to_p / d)), 0.0, 1.0);
    return e * gk_brdf_diffuse(s.m, vh_c) +
           u_light_color * (radiance_scale * win * lobe) * (f0 * ab.x + (f90 - f0) * ab.y);
#else
    // Sphere, disc: diffuse exact (Lambert form factor) with the fresnel_mix share towards the
    // light's centre, as for the rectangle; specular GGX at the representative point with Karis'
    // normalisation (alpha / alpha')^2, alpha' = alpha + r / (2 d) -- an approximation.
    highp float alpha = gk_alpha(s.m.roughness);
    highp float alpha_w = min(1.0, alpha + area_radius / (2.0 * d));
    highp float norm = (alpha / alpha_w) * (alpha / alpha_w);
    highp float vh_c = clamp(dot(s.v, normalize(s.v - to_p / d)), 0.0, 1.0);
    return e * (gk_brdf_diffuse(s.m, vh_c) + gk_brdf_specular(s.n, s.v, l_rep, s.m, norm));
#endif
#endif
}
