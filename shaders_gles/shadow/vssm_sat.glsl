// Helpers shared by the prefiltered soft-shadow lookups (vssm.glsl, cssm.glsl), included by
// shadow/shadow.glsl after shadow/common.glsl when SHADOW_VSSM or SHADOW_CSSM is defined.
// Texel coordinates: texel i covers [i, i + 1) of tc = uv * map_size. SATs are inclusive prefix
// sums with exact modular uint arithmetic (shaders_gles/shadow/vssm_sat.comp).

// Normalised linear depth over [near, far] (vssm_linearize.comp) and back.
highp float gk_soft_norm(highp float lin) { return (lin - u_shadow_proj.x) / (u_shadow_proj.y - u_shadow_proj.x); }
highp float gk_soft_denorm(highp float z) { return u_shadow_proj.x + z * (u_shadow_proj.y - u_shadow_proj.x); }

// The PCSS kernel (dong-001.md §1.2) in texels (full width along map u, v) of the light seen from
// receiver depth d through a plane at depth z: w = ((d - z) / d) S / (2 z tan(theta)) (ortho:
// (d - z) S / (2 half_extent)), clamped to [1 texel, a quarter map] (GK_SOFT_MAX_KERNEL: the
// bound the SAT fixed-point bits are chosen for).
highp vec2 gk_soft_kernel(highp float d, highp float z)
{
    highp vec2 size = u_shadow_light.xy;
    highp vec2 w = u_shadow_proj.z > 0.5 ? (d - z) * size / (2.0 * u_shadow_light.z)
                                           : ((d - z) / d) * size / (2.0 * max(z, 1e-4) * u_shadow_light.z);
    return clamp(w * u_shadow_light.w, vec2(1.0), vec2(0.25 * u_shadow_light.w));
}

// The integer texel box of a kernel of width w (texels) centred at tc: [lo, lo + W - 1].
void gk_soft_box(highp vec2 tc, highp vec2 w, out ivec2 lo, out ivec2 hi)
{
    ivec2 wi = max(ivec2(floor(w + 0.5)), ivec2(1));
    lo = ivec2(floor(tc - 0.5 * vec2(wi) + 0.5));
    hi = lo + wi - 1;
}

highp uint gk_sat1(highp usampler2DArray s, ivec2 p, int layer)
{
    return any(lessThan(p, ivec2(0))) ? 0u : texelFetch(s, ivec3(p, layer), 0).r;
}

// Mean z, mean z^2 and area (texels) over the texel box [lo, hi] (clamped to the map) of a pair
// of R32UI SATs with dequantisation factor invq.
highp vec3 gk_sat_moments(highp usampler2DArray sz, highp usampler2DArray sz2, ivec2 lo, ivec2 hi, int layer,
                          highp float invq)
{
    ivec2 top = ivec2(int(u_shadow_light.w) - 1);
    lo = clamp(lo, ivec2(0), top);
    hi = clamp(hi, lo, top);
    ivec2 a = lo - 1;
    highp uint s1 = gk_sat1(sz, hi, layer) - gk_sat1(sz, ivec2(a.x, hi.y), layer) - gk_sat1(sz, ivec2(hi.x, a.y), layer) +
                    gk_sat1(sz, a, layer);
    highp uint s2 = gk_sat1(sz2, hi, layer) - gk_sat1(sz2, ivec2(a.x, hi.y), layer) -
                    gk_sat1(sz2, ivec2(hi.x, a.y), layer) + gk_sat1(sz2, a, layer);
    highp float area = float((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
    return vec3(vec2(float(s1), float(s2)) * (invq / area), area);
}

// The same over a box of width w centred at tc with sub-texel position: the four integer boxes of
// the same integer width at the neighbouring offsets, interpolated bilinearly. For texel-constant
// depth that is exactly the box integral at the fractional position ((1-f) sum[i0, i0+W) +
// f sum[i0+1, i0+W+1) = the integral over [i0+f, i0+f+W)), so penumbrae do not step texel by texel.
highp vec2 gk_sat_moments_smooth(highp usampler2DArray sz, highp usampler2DArray sz2, highp vec2 tc, highp vec2 w,
                                 int layer, highp float invq)
{
    ivec2 wi = max(ivec2(floor(w + 0.5)), ivec2(1));
    highp vec2 start = tc - 0.5 * vec2(wi);
    highp vec2 fl = floor(start);
    highp vec2 f = start - fl;
    ivec2 i0 = ivec2(fl);
    highp vec2 m00 = gk_sat_moments(sz, sz2, i0, i0 + wi - 1, layer, invq).xy;
    highp vec2 m10 = gk_sat_moments(sz, sz2, i0 + ivec2(1, 0), i0 + wi - 1 + ivec2(1, 0), layer, invq).xy;
    highp vec2 m01 = gk_sat_moments(sz, sz2, i0 + ivec2(0, 1), i0 + wi - 1 + ivec2(0, 1), layer, invq).xy;
    highp vec2 m11 = gk_sat_moments(sz, sz2, i0 + ivec2(1, 1), i0 + wi, layer, invq).xy;
    return mix(mix(m00, m10, f.x), mix(m01, m11, f.x), f.y);
}
