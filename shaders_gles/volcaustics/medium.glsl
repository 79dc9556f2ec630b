// The scene's homogeneous medium for the volcaustics passes (app/ref/medium.h, binding for both):
//   T(a, b) = exp(-sigma_t * |[a, b] inside the medium's box|), an unbounded medium being a box of
//   +-1e6 m; p_HG(cos) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^1.5), cos between the direction light
//   travelled before and after scattering (the 1/4pi the seed's Eq. 2.22 loses, research §14.1).
uniform highp vec3 u_sigma_s;
uniform highp vec3 u_sigma_t;
uniform highp float u_hg_g;
uniform highp vec3 u_box_min;
uniform highp vec3 u_box_max;

// [t0, t1] of o + t d (t in [0, tmax]) inside the box; empty when t1 <= t0.
highp vec2 vc_clip(highp vec3 o, highp vec3 d, highp float tmax)
{
    highp vec3 inv = 1.0 / d;   // IEEE: +-inf for a zero component, the slab test still works
    highp vec3 ta = (u_box_min - o) * inv, tb = (u_box_max - o) * inv;
    highp vec3 lo = min(ta, tb), hi = max(ta, tb);
    highp float t0 = max(max(lo.x, lo.y), max(lo.z, 0.0));
    highp float t1 = min(min(hi.x, hi.y), min(hi.z, tmax));
    return vec2(t0, t1);
}

highp vec3 vc_transmittance(highp vec3 a, highp vec3 b)
{
    highp vec3 ab = b - a;
    highp float len = length(ab);
    if (len <= 0.0)
        return vec3(1.0);
    highp vec2 c = vc_clip(a, ab / len, len);
    return exp(-u_sigma_t * max(c.y - c.x, 0.0));
}

highp float vc_phase(highp float cos_theta)
{
    highp float g = u_hg_g, g2 = g * g;
    highp float den = max(1.0 + g2 - 2.0 * g * cos_theta, 1e-6);
    return (1.0 - g2) / (4.0 * 3.14159265358979 * den * sqrt(den));
}
