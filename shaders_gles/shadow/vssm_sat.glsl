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
    GK_SHADOW_COUNT(r32ui, any(lessThan(p, ivec2(0))) ? 0 : 1);
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
// The four boxes' 16 corners are four 2x2 blocks of texels (per axis i0-1, i0 and i0+W-1, i0+W), so
// each table is read with four textureGather, not sixteen texelFetch. Edges as in gk_sat_moments
// (a box's low corner left of the map reads 0, its high corner clamps to the map's last texel, its
// area is the clamped one); the start i0 is kept at most one texel before the map's last texel so
// both shifted boxes begin inside the map (gk_sat_moments clamps a box starting past it to the last
// texel; that happens only for receivers within half a texel of the map's far edges).
highp vec2 gk_sat_moments_smooth(highp usampler2DArray sz, highp usampler2DArray sz2, highp vec2 tc, highp vec2 w,
                                 int layer, highp float invq)
{
    ivec2 wi = max(ivec2(floor(w + 0.5)), ivec2(1));
    highp vec2 start = tc - 0.5 * vec2(wi);
    highp vec2 fl = floor(start);
    highp vec2 f = start - fl;
    ivec2 top = ivec2(int(u_shadow_light.w) - 1);
    ivec2 i0 = min(ivec2(fl), top - 1);
    ivec2 a = i0 - 1, h = i0 + wi - 1;     // low and high corners of the unshifted box
    // textureGather at the shared corner of texels c and c + 1 returns them as
    // (x, y, z, w) = (c.x, c.y+1), (c.x+1, c.y+1), (c.x+1, c.y), (c.x, c.y): in box order
    // (shift 00, 10, 01, 11) that is .wzxy.
    highp float inv = 1.0 / u_shadow_light.w;
    highp vec3 t_aa = vec3((vec2(a) + 1.0) * inv, float(layer)), t_hh = vec3((vec2(h) + 1.0) * inv, float(layer));
    highp vec3 t_ah = vec3(t_aa.x, t_hh.y, t_aa.z), t_ha = vec3(t_hh.x, t_aa.y, t_aa.z);
    // a low corner left of (or below) the map is the empty prefix: 0
    bvec4 ax_in = bvec4(a.x >= 0, a.x + 1 >= 0, a.x >= 0, a.x + 1 >= 0);
    bvec4 ay_in = bvec4(a.y >= 0, a.y >= 0, a.y + 1 >= 0, a.y + 1 >= 0);
    uvec4 mx = uvec4(ax_in), my = uvec4(ay_in);
    GK_SHADOW_COUNT(r32ui, 8);
    uvec4 s1 = textureGather(sz, t_hh, 0).wzxy - textureGather(sz, t_ah, 0).wzxy * mx -
               textureGather(sz, t_ha, 0).wzxy * my + textureGather(sz, t_aa, 0).wzxy * (mx * my);
    uvec4 s2 = textureGather(sz2, t_hh, 0).wzxy - textureGather(sz2, t_ah, 0).wzxy * mx -
               textureGather(sz2, t_ha, 0).wzxy * my + textureGather(sz2, t_aa, 0).wzxy * (mx * my);
    // clamped extents per axis for shift 0 and 1 (low end inside the map by the clamp of i0)
    ivec2 lo0 = max(i0, ivec2(0)), lo1 = max(i0 + 1, ivec2(0));
    ivec2 e0 = clamp(h, lo0, top) - lo0 + 1, e1 = clamp(h + 1, lo1, top) - lo1 + 1;
    highp vec4 area = vec4(float(e0.x * e0.y), float(e1.x * e0.y), float(e0.x * e1.y), float(e1.x * e1.y));
    highp vec4 mz = vec4(s1) * invq / area, mz2 = vec4(s2) * invq / area;
    highp vec2 m00 = vec2(mz.x, mz2.x), m10 = vec2(mz.y, mz2.y), m01 = vec2(mz.z, mz2.z), m11 = vec2(mz.w, mz2.w);
    return mix(mix(m00, m10, f.x), mix(m01, m11, f.x), f.y);
}
