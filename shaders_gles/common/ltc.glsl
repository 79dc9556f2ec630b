// Linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt 2016) for the GGX lobe of
// brdf.glsl over a polygonal light: the lobe D V cos (F = 1) at view angle theta_v and roughness r
// is approximated by A x (clamped cosine transformed by M), so its integral over a polygon P is
// A E(Minv P) / pi, E the clamped-cosine (Lambert) integral of the transformed polygon
// (area_lights.glsl). The tables are fitted in the repository (tools/ltc_fit.c ->
// app/render/ltc_table.c, layout in ltc_table.h) and uploaded by the renderer as one RGBA32F
// texture: rows 0..N-1 Minv (m0, m1, m2, m3), rows N..2N-1 (A, B, 0, 0); filtered here, as
// RGBA32F is not filterable in GLES 3.1 core.
#define GK_LTC_N 64
uniform highp sampler2D u_ltc;

highp vec4 gk_ltc_texel(int a, int t, int half_) { return texelFetch(u_ltc, ivec2(a, t + half_ * GK_LTC_N), 0); }

// Bilinear lookup at (roughness, sqrt(1 - cos theta_v)); half_ 0: Minv, 1: (A, B).
highp vec4 gk_ltc_lookup(highp float roughness, highp float cos_v, int half_)
{
    highp vec2 x = vec2(clamp(roughness, 0.0, 1.0), sqrt(clamp(1.0 - cos_v, 0.0, 1.0))) * float(GK_LTC_N - 1);
    ivec2 i0 = clamp(ivec2(floor(x)), ivec2(0), ivec2(GK_LTC_N - 2));
    highp vec2 f = clamp(x - vec2(i0), 0.0, 1.0);
    return mix(mix(gk_ltc_texel(i0.x, i0.y, half_), gk_ltc_texel(i0.x + 1, i0.y, half_), f.x),
               mix(gk_ltc_texel(i0.x, i0.y + 1, half_), gk_ltc_texel(i0.x + 1, i0.y + 1, half_), f.x), f.y);
}

// Integral of the lobe D V cos over the rectangle c +- hu +- hv seen from p (unit normal n, unit
// view v): returns E(Minv P) / pi and, in ab, (A, B) for F = F0 A + (F90 - F0) B.
highp float gk_ltc_rect(highp vec3 p, highp vec3 n, highp vec3 v, highp float roughness, highp vec3 c, highp vec3 hu,
                        highp vec3 hv, out highp vec2 ab)
{
    highp float cos_v = clamp(dot(n, v), 0.0, 1.0);
    highp vec4 m = gk_ltc_lookup(roughness, cos_v, 0);
    ab = gk_ltc_lookup(roughness, cos_v, 1).xy;
    // The table's frame: x = the view projected on the tangent plane, z = n.
    highp vec3 t1 = v - n * dot(v, n);
    t1 = dot(t1, t1) > 1e-8 ? normalize(t1) : normalize(abs(n.x) < 0.9 ? cross(n, vec3(1.0, 0.0, 0.0))
                                                                         : cross(n, vec3(0.0, 1.0, 0.0)));
    highp vec3 t2 = cross(n, t1);
    highp vec3 q[GK_POLY_MAX];
    highp vec3 corner[4];
    corner[0] = c - hu - hv;
    corner[1] = c + hu - hv;
    corner[2] = c + hu + hv;
    corner[3] = c - hu + hv;
    for (int i = 0; i < 4; i++) {
        highp vec3 d = corner[i] - p;
        highp vec3 l = vec3(dot(d, t1), dot(d, t2), dot(d, n));
        q[i] = vec3(m.x * l.x + m.y * l.z, l.y, m.z * l.x + m.w * l.z);
    }
    return gk_polygon_irradiance(vec3(0.0), vec3(0.0, 0.0, 1.0), q, 4) / GK_PI;
}
