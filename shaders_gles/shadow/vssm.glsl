// Variance soft shadow maps, VSSM (Yang et al. 2010; dong-001.md §5, Algorithms 2 and 3), with
// the Chebyshev bound as corrected (errata §14.1: p_max = s^2 / (s^2 + (d - mu)^2), mu = E(z),
// t = d). Depths are normalised to [0, 1] over [near, far]; moments come from the exact integer
// SATs, bounds from the min-max HSM (app/render/shadow/shadow_vssm.c). Additions to the thesis, each
// with a switch whose 0 is the thesis (method vssm_thesis): VSSM_RECEIVER_PLANE, VSSM_SEARCH_BOUND.
//   VSSM_SUBDIV 1 (default): non-planar kernels (E(z) >= d) are subdivided: m x m uniform (m = 5
//                by default) for the blocker search, an adaptive quadtree of height H (3 by
//                default) with stackless traversal for the shadow kernel (m, H: u_vssm_sub); non-planar leaves use a 2x2 point-sample PCF, planar-lit ones
//                (E(z) >= d and s^2 < Threshold) count as lit. 0: SAVSM, a non-planar kernel is lit.
//   VSSM_CONTACT 1 (default): |z_occ - d| < eps (0.01 r_sc) -> 3x3 jittered bilinear PCF.
#ifndef VSSM_SUBDIV
#define VSSM_SUBDIV 1
#endif
#ifndef VSSM_CONTACT
#define VSSM_CONTACT 1
#endif
// VSSM_RECEIVER_PLANE 1 (default; an addition to the thesis, #11): every sub-kernel and point
// sample is tested against the receiver's tangent plane at its own position instead of the one
// depth d of the pixel (receiver-plane depth bias, Isidoro 2006, as pcss.glsl does). Without it a
// receiver inclined to the map finds its own nearer half "in front of" d: the subdivided kernels
// of the floor's rim under a cube-face map (the kernel half on the floor, half past its edge, so
// non-planar) counted that half as blockers, 0.78-0.90 of the light within 0.1 m of the
// shadow-planes floor edge (test_shadow_rim.c), and the Cornell walls (parallel to the downward
// cube face's axis) showed contour bands where the code path switched (test_shadow_contours.c).
// 0: the thesis's constant d (method vssm_thesis).
#ifndef VSSM_RECEIVER_PLANE
#define VSSM_RECEIVER_PLANE 1
#endif
// VSSM_SEARCH_BOUND 1 (default; an addition to the thesis, #21/#11): the blocker search kernel is
// cut from the light's footprint on the near plane to its footprint on the plane of the nearest
// depth the HSM finds over it, z_min, and the HSM is asked again over the smaller kernel; the
// penumbra kernel gets the same HSM lit test before its moments. Every blocker has z >= z_min and a
// blocker at depth z can only shadow the receiver within the footprint on its own plane, whose width
// falls with z, so no blocker is lost: what goes is the conservative search's false blockers, the
// occluders beside the light's footprint (on the Cornell walls the other walls and the boxes) that
// the thesis's near-plane kernel (up to a quarter of the map wide) averaged into z_occ. 0: the
// thesis's near-plane kernel only (method vssm_thesis).
#ifndef VSSM_SEARCH_BOUND
#define VSSM_SEARCH_BOUND 1
#endif
// How much more variance than its tangent plane's a kernel on a sloped receiver may have and still
// count as the receiver alone: the plane's depth is convex in a perspective map, so a wide kernel
// has somewhat more; a blocker adds (d - z)^2 times its share. 1.25: measured on the rim, contour
// and T1-T3 tests (test_shadow_*.c) with no change of their numbers beyond the last digit.
#ifndef VSSM_PLANAR_SLACK
#define VSSM_PLANAR_SLACK 1.25
#endif
// Subdivision depth (knob shadow_subdiv, app/render/shadow/shadow_vssm.c): u_vssm_sub = (m, H), the
// m x m uniform grid of the blocker search and the height H of the adaptive quadtree; the thesis's
// m = 5, H = 3 is the default. VSSM_M_MAX / VSSM_H_MAX bound the loops (the richest knob level).
#define VSSM_M_MAX 8
#define VSSM_H_MAX 4
uniform highp vec2 u_vssm_sub;
// Variance floor: a few fixed-point quanta (2^-17..2^-16) of E(z^2) so that flat kernels of
// blockers and rounding in E(z^2) - E(z)^2 cannot divide by zero.
#define VSSM_MIN_VAR 2e-6

uniform highp usampler2DArray u_vssm_sat_z;
uniform highp usampler2DArray u_vssm_sat_z2;
uniform highp sampler2DArray u_vssm_zmin;
uniform highp sampler2DArray u_vssm_zmax;
uniform highp vec4 u_vssm; // 1/q (SAT dequantisation), top HSM level, contact eps, planar-lit variance threshold

// The receiver plane around the pixel (set by vssm_receiver_plane), to first order as pcss.glsl
// takes it: linear depth k0 + g.(tc - tc0) in texel coordinates tc. In a perspective map a plane's
// depth is convex in tc (1 / depth is affine), so the tangent lies in front of the plane and the
// receiver's own samples never count as blockers.
highp vec2 vssm_rp_tc0, vssm_rp_g;
highp float vssm_rp_k0, vssm_rp_n0;

void vssm_receiver_plane(gk_shadow_coord c, highp vec3 p, highp vec3 n)
{
    vssm_rp_tc0 = c.uv * u_shadow_light.w;
    vssm_rp_n0 = gk_soft_norm(c.d);
    vssm_rp_k0 = c.d;
    vssm_rp_g = vec2(0.0);
#if VSSM_RECEIVER_PLANE
    int f = int(c.layer);
    highp vec3 axis = u_shadow_proj.w > 1.5 ? gk_cube_axis(f) : u_shadow_axis;
    highp float e = 1.0 / u_shadow_light.w; // one texel
    highp float du = gk_shadow_plane_depth(c.uv + vec2(e, 0.0), f, p, n, axis, c.d);
    highp float dv = gk_shadow_plane_depth(c.uv + vec2(0.0, e), f, p, n, axis, c.d);
    // per texel, bounded as gk_shadow_receiver_gradient bounds it (near-grazing planes)
    vssm_rp_g = clamp(vec2(du, dv) - c.d, vec2(-100.0 * c.d * e), vec2(100.0 * c.d * e));
#endif
}

// The shift of the test depth d for a sub-kernel centred (or a sample) at tc: the receiver plane's
// normalised depth there minus the pixel's own, where that is negative, else 0. Nothing at or
// behind the receiver's depth d can block it (every segment from the receiver to the light lies
// in front of d), so a sample must be in front of both d and the plane to count: the plane removes
// the receiver's own nearer half, d the surfaces behind the plane's extension at concave corners
// (the floor under a Cornell wall, which darkened the walls' lower rims with the plane alone).
highp float vssm_plane(highp vec2 tc)
{
#if VSSM_RECEIVER_PLANE
    return min(gk_soft_norm(vssm_rp_k0 + dot(vssm_rp_g, tc - vssm_rp_tc0)) - vssm_rp_n0, 0.0);
#else
    return 0.0;
#endif
}

// Variance of the receiver's tangent plane over a box of w texels (normalised depth^2): a box that
// holds only the receiver has this much variance from its slope alone. The planar-lit test
// (sigma^2 < Threshold) allows for it, and a kernel whose own slope variance passes Threshold is
// a sloped receiver: its whole-kernel Chebyshev would count the receiver's nearer half as
// blockers, so it is subdivided (each sub-kernel shifted by its own plane offset) instead.
highp float vssm_plane_var(highp vec2 w)
{
#if VSSM_RECEIVER_PLANE
    highp vec2 g = vssm_rp_g * w / (u_shadow_proj.y - u_shadow_proj.x);
    return dot(g, g) / 12.0;
#else
    return 0.0;
#endif
}

highp vec3 vssm_moments(ivec2 lo, ivec2 hi, int layer)
{
    return gk_sat_moments(u_vssm_sat_z, u_vssm_sat_z2, lo, hi, layer, u_vssm.x);
}

highp float vssm_cheb(highp vec2 m, highp float d)
{
    highp float var = max(m.y - m.x * m.x, VSSM_MIN_VAR);
    highp float t = d - m.x;
    return t <= 0.0 ? 1.0 : var / (var + t * t);
}

highp float vssm_z(ivec2 p, int layer)
{
    p = clamp(p, ivec2(0), ivec2(int(u_shadow_light.w) - 1));
    GK_SHADOW_COUNT(r32f, 1);
    return texelFetch(u_vssm_zmin, ivec3(p, layer), 0).r;
}

// 2x2 point samples (quadrant centres) of the box [lo, hi]: (occluders, sum of their depths, each
// less its receiver-plane shift so that they compare with d).
highp vec2 vssm_pcf4(ivec2 lo, ivec2 hi, int layer, highp float d)
{
    highp vec2 a = vec2(lo), b = vec2(hi + 1);
    highp vec2 r = vec2(0.0);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            ivec2 t = ivec2(floor(mix(a, b, (vec2(float(i), float(j)) + 0.5) * 0.5)));
            highp float z = vssm_z(t, layer) - vssm_plane(vec2(t) + 0.5);
            if (z < d)
                r += vec2(1.0, z);
        }
    return r;
}

// A sub-kernel's moments shifted by its receiver-plane offset s (z -> z - s over the box).
highp vec2 vssm_shift(highp vec2 m, highp float s)
{
    return vec2(m.x - s, m.y - 2.0 * s * m.x + s * s);
}

// Sub-range k of n equal integer parts of [lo, hi] (nested: part k of n/2 = parts 2k, 2k+1 of n).
ivec2 vssm_split(int lo, int hi, int k, int n)
{
    // floor(k w / n) in float (exact: k w + 0.5 lies at least 0.5 / n from a multiple of n, far
    // more than the reciprocal's rounding): llvmpipe has no vector integer division and runs
    // one scalar division per lane, several per quadtree node and grid corner (#21).
    int w = hi - lo + 1;
    highp float inv = 1.0 / float(n);
    return ivec2(lo + int((float(k * w) + 0.5) * inv), lo + int((float((k + 1) * w) + 0.5) * inv) - 1);
}

// (min, max) depth over the box from the HSM: level ceil(log2 width), at most 2x2 texels there.
highp vec2 vssm_hsm(ivec2 lo, ivec2 hi, int layer)
{
    ivec2 top = ivec2(int(u_shadow_light.w) - 1);
    lo = clamp(lo, ivec2(0), top);
    hi = clamp(hi, lo, top);
    int w = max(hi.x - lo.x, hi.y - lo.y) + 1;
    int l = clamp(int(ceil(log2(float(w)))), 0, int(u_vssm.y));
    ivec2 a = lo >> l, b = hi >> l;
    highp vec2 r = vec2(1e30, -1e30);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            ivec2 p = min(a + ivec2(i, j), b);
            GK_SHADOW_COUNT(r32f, 2);
            r.x = min(r.x, texelFetch(u_vssm_zmin, ivec3(p, layer), l).r);
            r.y = max(r.y, texelFetch(u_vssm_zmax, ivec3(p, layer), l).r);
        }
    return r;
}

// Both SATs' sums at the prefix corner (x, y) (clamped to [-1, top]; -1: left of / below the map,
// the empty prefix 0).
highp uvec2 vssm_corner(int x, int y, int layer)
{
    bool inside = x >= 0 && y >= 0;
    GK_SHADOW_COUNT(r32ui, inside ? 2 : 0);
    ivec3 p = ivec3(x, y, layer);
    return inside ? uvec2(texelFetch(u_vssm_sat_z, p, 0).r, texelFetch(u_vssm_sat_z2, p, 0).r) : uvec2(0u);
}

// One box of a subdivision, between corners p0 (exclusive) and p1 (inclusive) clamped as
// vssm_corner takes them, from the SAT sums s00, s10, s01, s11 at its corners (x0 y0, x1 y0, x0 y1,
// x1 y1): m = its moments shifted by the receiver plane at its centre, and its area (texels).
// Returns 0 for an empty box (wholly outside the map, or a part of a kernel narrower than the
// subdivision), 1 planar and lit (the §5.2 acceleration: E(z) >= d and a variance within
// Threshold plus the receiver plane's own), 2 in front of d (Chebyshev), 3 non-planar (subdivide
// or point-sample).
int vssm_box(highp uvec2 s00, highp uvec2 s10, highp uvec2 s01, highp uvec2 s11, ivec2 p0, ivec2 p1,
             highp float d, out highp vec3 m)
{
    ivec2 e = p1 - p0;
    m.z = float(e.x * e.y);
    highp uvec2 s = s11 - s01 - s10 + s00;
    m.xy = vssm_shift(vec2(s) * (u_vssm.x / max(m.z, 1.0)), vssm_plane(0.5 * vec2(p0 + p1 + 2)));
    if (m.z <= 0.0)
        return 0;
    if (m.x >= d && m.y - m.x * m.x < u_vssm.w + vssm_plane_var(vec2(e)))
        return 1;
    return m.x < d ? 2 : 3;
}

// Average blocker depth (Eq. 7.4, z_unocc = d) over the search kernel, and the blocker fraction
// (0: no blocker, lit).
highp vec2 vssm_blocker(highp vec2 tc, highp vec2 w, int layer, highp float d)
{
    highp vec2 m = gk_sat_moments_smooth(u_vssm_sat_z, u_vssm_sat_z2, tc, w, layer, u_vssm.x);
    if (m.x < d && vssm_plane_var(w) < u_vssm.w) {
        highp float p = vssm_cheb(m, d);
        if (p >= 0.9999)
            return vec2(d, 0.0);
        return vec2((m.x - p * d) / (1.0 - p), 1.0 - p);
    }
#if VSSM_SUBDIV
    // The §5.2 planar-lit acceleration on the whole kernel, before subdividing it: E(z) >= d and a
    // variance no more than the receiver plane's own (VSSM_PLANAR_SLACK x) plus Threshold: the
    // kernel holds only the (sloped) receiver, no blocker. Without it every pixel of a receiver
    // inclined to the map paid the m x m grid (2 m (m + 1) corners x 2 tables + a 2 x 2 PCF per
    // sub-kernel) for nothing: the shadow-planes floor's outer metre on the cube's side faces.
    if (m.x >= d && m.y - m.x * m.x < u_vssm.w + VSSM_PLANAR_SLACK * vssm_plane_var(w))
        return vec2(d, 0.0);
    ivec2 lo, hi;
    gk_soft_box(tc, w, lo, hi);
    highp float a_all = 0.0, a_vsm = 0.0, ex = 0.0, ex2 = 0.0, a_pcf = 0.0, z_pcf = 0.0;
    int m_sub = clamp(int(u_vssm_sub.x + 0.5), 1, VSSM_M_MAX);
    ivec2 top = ivec2(int(u_shadow_light.w) - 1);
    // The m x m sub-boxes tile [lo, hi] (vssm_split), a row at a time; each cell reads the two
    // corners on its right and takes those on its left from the cell before (the row's first from
    // before the loop). Corners are clamped to the map as gk_sat_moments clamps a box (a corner left
    // of the map reads 0, past it the last texel); a sub-box wholly outside the map has area 0 and
    // is left out (gk_sat_moments would count the map's edge texel for it). No arrays of the
    // previous row's corners: llvmpipe reads and writes an array at a varying index lane by lane;
    // two more corner fetches per cell measured cheaper (#21, README), images bit-identical.
    for (int j = 0; j < VSSM_M_MAX; j++) {
        if (j >= m_sub)
            break;
        ivec2 sy = vssm_split(lo.y, hi.y, j, m_sub);
        ivec4 q = clamp(ivec4(lo.x - 1, sy.x - 1, lo.x - 1, sy.y), ivec4(-1), top.xyxy);
        highp uvec2 sb = vssm_corner(q.x, q.y, layer), st = vssm_corner(q.x, q.w, layer);
        for (int i = 0; i < VSSM_M_MAX; i++) {
            if (i >= m_sub)
                break;
            ivec2 sx = vssm_split(lo.x, hi.x, i, m_sub);
            int x1 = clamp(sx.y, -1, top.x);
            highp uvec2 rb = vssm_corner(x1, q.y, layer), rt = vssm_corner(x1, q.w, layer);
            highp vec3 mc;
            int cls = vssm_box(sb, rb, st, rt, q.xy, ivec2(x1, q.w), d, mc);
            if (cls > 0)
                a_all += mc.z;
            if (cls == 2) {
                a_vsm += mc.z;
                ex += mc.x * mc.z;
                ex2 += mc.y * mc.z;
            } else if (cls == 3) {
                highp vec2 pc = vssm_pcf4(ivec2(sx.x, sy.x), ivec2(sx.y, sy.y), layer, d);
                a_pcf += 0.25 * mc.z * pc.x;
                z_pcf += 0.25 * mc.z * pc.y;
            }
            q.x = x1;
            sb = rb;
            st = rt;
        }
    }
    highp float a1 = 0.0, d1 = 0.0;
    if (a_vsm > 0.0) {
        highp vec2 mv = vec2(ex, ex2) / a_vsm;
        highp float p = vssm_cheb(mv, d);
        if (p < 0.9999) {
            a1 = (1.0 - p) * a_vsm;
            d1 = (mv.x - p * d) / (1.0 - p);
        }
    }
    highp float ab = a1 + a_pcf;
    if (ab <= 0.0 || a_all <= 0.0)
        return vec2(d, 0.0);
    return vec2((d1 * a1 + z_pcf) / ab, ab / a_all);
#else
    return vec2(d, 0.0); // SAVSM: a non-planar kernel is taken as lit
#endif
}

#if VSSM_SUBDIV
// Algorithm 3: adaptive subdivision of the shadow kernel, a quadtree of height H = u_vssm_sub.y
// traversed in preorder without a stack (node = level l + Morton index c; Child = (l+1, 4c); Next
// climbs while the node is a last sibling). At most 1 + 4 + ... + 4^H_MAX = 341 nodes.
highp float vssm_adaptive(ivec2 lo, ivec2 hi, int layer, highp float d)
{
    highp float a_vsm = 0.0, ex = 0.0, ex2 = 0.0, a_lit = 0.0, a_pcf = 0.0, b_pcf = 0.0;
    int h_sub = clamp(int(u_vssm_sub.y + 0.5), 0, VSSM_H_MAX);
    ivec2 top = ivec2(int(u_shadow_light.w) - 1);
    int l = 0;
    highp uint c = 0u;
    for (int it = 0; it < 341; it++) {
        int n = 1 << l;
        int ix = 0, iy = 0;
        for (int b = 0; b < VSSM_H_MAX; b++)
            if (b < l) {
                ix |= int((c >> uint(2 * b)) & 1u) << b;
                iy |= int((c >> uint(2 * b + 1)) & 1u) << b;
            }
        ivec2 sx = vssm_split(lo.x, hi.x, ix, n), sy = vssm_split(lo.y, hi.y, iy, n);
        bool descend = false;
        if (sx.y >= sx.x && sy.y >= sy.x) {
            ivec2 slo = ivec2(sx.x, sy.x), shi = ivec2(sx.y, sy.y);
            highp vec3 mc = vssm_moments(slo, shi, layer);
            ivec2 clo = clamp(slo, ivec2(0), top), chi = clamp(shi, clo, top); // the box vssm_moments read
            mc.xy = vssm_shift(mc.xy, vssm_plane(0.5 * vec2(clo + chi + 1)));
            highp float var = mc.y - mc.x * mc.x;
            if (mc.x >= d && var < u_vssm.w + vssm_plane_var(vec2(chi - clo + 1))) {
                a_lit += mc.z;
            } else if (mc.x < d) {
                a_vsm += mc.z;
                ex += mc.x * mc.z;
                ex2 += mc.y * mc.z;
            } else if (l < h_sub) {
                descend = true;
            } else {
                highp vec2 pc = vssm_pcf4(slo, shi, layer, d);
                a_pcf += mc.z;
                b_pcf += 0.25 * mc.z * pc.x;
            }
        }
        if (descend) {
            l++;
            c <<= 2u;
            continue;
        }
        while (l > 0 && (c & 3u) == 3u) {
            c >>= 2u;
            l--;
        }
        if (l == 0)
            break;
        c += 1u;
    }
    highp float total = a_vsm + a_lit + a_pcf;
    if (total <= 0.0)
        return 1.0;
    highp float L = a_vsm > 0.0 ? vssm_cheb(vec2(ex, ex2) / a_vsm, d) : 1.0;
    highp float L1 = a_pcf > 0.0 ? 1.0 - b_pcf / a_pcf : 1.0;
    return (L * a_vsm + a_lit + L1 * a_pcf) / total;
}
#endif

// Depth test of texel t against d shifted by the receiver plane at the texel's centre.
highp float vssm_lit_texel(ivec2 t, int layer, highp float d)
{
    return vssm_z(t, layer) - vssm_plane(vec2(t) + 0.5) >= d ? 1.0 : 0.0;
}

// Bilinear-weighted depth test of the 2x2 texels around tc.
highp float vssm_pcf_bilinear(highp vec2 tc, int layer, highp float d)
{
    highp vec2 t = tc - 0.5;
    ivec2 i = ivec2(floor(t));
    highp vec2 f = t - floor(t);
    highp float v00 = vssm_lit_texel(i, layer, d);
    highp float v10 = vssm_lit_texel(i + ivec2(1, 0), layer, d);
    highp float v01 = vssm_lit_texel(i + ivec2(0, 1), layer, d);
    highp float v11 = vssm_lit_texel(i + ivec2(1, 1), layer, d);
    return mix(mix(v00, v10, f.x), mix(v01, v11, f.x), f.y);
}

// Contact fallback (§7.5.4, after [Bavoil08]): 3x3 jittered bilinear PCF over the penumbra kernel.
highp float vssm_contact(highp vec2 tc, highp vec2 w, int layer, highp float d)
{
    highp float jit = gk_shadow_noise();
    highp float sum = 0.0;
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            highp vec2 g = (vec2(float(i), float(j)) + fract(jit + vec2(0.0, 0.5))) / 3.0 - 0.5;
            sum += vssm_pcf_bilinear(tc + g * w, layer, d);
        }
    return sum / 9.0;
}

// The lookup's state between its early-outs (shadow_settle) and the rest (shadow_visibility_rest).
gk_shadow_coord vssm_c;
int vssm_layer;
highp vec2 vssm_tc, vssm_wi, vssm_mm;
highp float vssm_d;

// The lookup up to the HSM's early-outs: 1 (no texel in front of the receiver over the blocker
// search kernel: lit), 0 (every texel in front: umbra), or -1 (not settled: shadow_visibility_rest
// goes on from here). The lighting pass's first draw (SHADOW_SPLIT 1, direct/light.frag) adds and
// stencil-marks the pixels this settles; llvmpipe runs the whole lookup for a SIMD block unless
// the early stencil test rejects every lane of it (a discard or a return skips nothing), so the
// second draw runs it only in blocks with a pixel left (#21, app/render/render_split.c).
highp float shadow_settle(highp vec3 world_pos)
{
    // No receiver offset: Chebyshev's test is t <= mu (a surface's own samples at t count as
    // lit), and any offset puts the receiver's own samples behind t and biases p_max upward
    // (measured +0.065 in the T1 penumbra with the 1.5 + 0.5 texel offset of the other methods).
    gk_shadow_coord c = gk_shadow_project(world_pos);
    vssm_c = c;
    if (!c.inside)
        return 1.0;
    int layer = int(c.layer);
    highp vec2 tc = c.uv * u_shadow_light.w;
    highp float d = gk_soft_norm(c.d);
    // 1. Blocker search kernel from the near plane; HSM early-out over it (1 texel margin for the
    //    interpolated box).
    highp vec2 wi = gk_soft_kernel(c.d, u_shadow_proj.x);
    ivec2 lo, hi;
    gk_soft_box(tc, wi, lo, hi);
    highp vec2 mm = vssm_hsm(lo - 1, hi + 1, layer);
    // Point-sample tests (HSM, PCF leaves, contact PCF) compare with d - tol: a surface's own
    // samples differ from d by rounding (linearisation, 2^-17 fixed point) and, on slopes, by up
    // to about a texel of depth; without it lit receivers self-shadow in PCF leaves (measured:
    // lit-mask max error 1.0 on T1).
    highp float tol = 1e-4 + gk_shadow_texel_world(c.d) / (u_shadow_proj.y - u_shadow_proj.x);
    d -= tol;
    if (d <= mm.x)
        return 1.0;
    if (d > mm.y)
        return 0.0;
#if VSSM_SEARCH_BOUND
    wi = min(wi, gk_soft_kernel(c.d, gk_soft_denorm(mm.x)));
    gk_soft_box(tc, wi, lo, hi);
    mm = vssm_hsm(lo - 1, hi + 1, layer);
    if (d <= mm.x)
        return 1.0;
    if (d > mm.y)
        return 0.0;
#endif
    vssm_layer = layer;
    vssm_tc = tc;
    vssm_wi = wi;
    vssm_mm = mm;
    vssm_d = d;
    return -1.0;
}

// The rest of the lookup for a pixel shadow_settle left unsettled (-1), from its state.
highp float shadow_visibility_rest(highp vec3 world_pos, highp vec3 world_normal)
{
    gk_shadow_coord c = vssm_c;
    int layer = vssm_layer;
    highp vec2 tc = vssm_tc, wi = vssm_wi, mm = vssm_mm;
    highp float d = vssm_d;
    ivec2 lo, hi;
    // the receiver plane only after the HSM's early-outs, which do not use it (two unprojections)
    vssm_receiver_plane(c, world_pos, world_normal);
    // 2. Average blocker depth.
    highp vec2 b = vssm_blocker(tc, wi, layer, d);
    if (b.y <= 0.0)
        return 1.0;
#if VSSM_SEARCH_BOUND
    // No blocker is nearer than the HSM's z_min over the kernel: the bound keeps Eq. 7.4 in range
    // where the kernel holds a sliver of blocker (the footprint's edge at the penumbra's outer
    // rim), 1 - p is within the SATs' rounding, and z_occ = mu - s^2 / (d - mu) came out near the
    // light: a wide penumbra kernel darkened a thin ring there (T1: penumbra error 0.043 without
    // the bound, 0.016 with it).
    highp float zocc = clamp(b.x, mm.x, d);
#else
    highp float zocc = min(b.x, d);
#endif
    // 3. Penumbra kernel from the blocker plane.
    highp vec2 wp = gk_soft_kernel(c.d, gk_soft_denorm(zocc));
#if VSSM_SEARCH_BOUND
    // Nothing in front of d within the penumbra kernel (1 texel margin: the sub-texel boxes and the
    // contact PCF's bilinear taps reach one texel past it): every path below would return 1.
    gk_soft_box(tc, wp, lo, hi);
    if (d <= vssm_hsm(lo - 1, hi + 1, layer).x)
        return 1.0;
#endif
#if VSSM_CONTACT
    if (abs(zocc - d) < u_vssm.z)
        return vssm_contact(tc, wp, layer, d);
#endif
    highp vec2 m = gk_sat_moments_smooth(u_vssm_sat_z, u_vssm_sat_z2, tc, wp, layer, u_vssm.x);
    if (m.x < d && vssm_plane_var(wp) < u_vssm.w)
        return vssm_cheb(m, d);
#if VSSM_SUBDIV
    gk_soft_box(tc, wp, lo, hi);
    return vssm_adaptive(lo, hi, layer, d);
#else
    return 1.0;
#endif
}

highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal)
{
    highp float v = shadow_settle(world_pos);
    return v >= 0.0 ? v : shadow_visibility_rest(world_pos, world_normal);
}
