// Convolution soft shadow maps, CSSM (Annen et al. 2008; dong-001.md §3, checklist §11.2):
//   the lit test f(d, z) = 1 - fbar, fbar ~ 1/2 + 2 sum_k sin(c_k (d - z)) / c_k, c_k = pi (2k - 1)
//   (the pi restored, errata §14.1), K = 4, expanded in the basis cos/sin(c_k z) so it can be
//   prefiltered; the average blocker depth by CSM-Z (Eq. 5.11) over the same expansion; the final
//   kernel f_w from the PCSS formula with the plane at z_avg; ringing suppression (scale about 1/2
//   by CSSM_ALPHA, clamp) and contact sharpening G(v) = v^p, p = 1 + A exp(-B (d - z_avg)).
// Depth units: z_c = u_cssm.x * z (z normalised over [near, far]); the series has period 2 in
// d - z, and u_cssm.x < 1 keeps far receivers behind near blockers on the plateau. The receiver
// depth is shifted by u_cssm.y, the point where the scaled, clamped test saturates (0.064 for
// K = 4, alpha = 1.12: dong-001.md §3.3 table), so a surface's own depth samples count as lit.
//   CSSM_SAT 0: mipmapped RGBA16F bases, textureLod at log2(kernel); 1: exact integer SATs with
//   sub-texel box position (app/render/shadow/shadow_cssm.c).
//   CSSM_ALPHA 1.12 (1: no ringing suppression), CSSM_SHARP_A 30 (0: no sharpening), CSSM_SHARP_B
//   10 per metre of d - z_avg (the thesis does not give B's unit; world metres are ours).
#ifndef CSSM_SAT
#define CSSM_SAT 0
#endif
#ifndef CSSM_ALPHA
#define CSSM_ALPHA 1.12
#endif
#ifndef CSSM_SHARP_A
#define CSSM_SHARP_A 30.0
#endif
#ifndef CSSM_SHARP_B
#define CSSM_SHARP_B 10.0
#endif
// CSSM_SLOPE 1 (default; an addition to the thesis, #11): the receiver depth of each stage is
// shifted further by half the depth its own tangent plane spans across that stage's kernel
// (slope-scaled bias). The series' transition is only 0.064 wide past the shift; on a receiver
// inclined to the map (the Cornell walls under the ceiling light's downward face) the kernel's
// own samples spread wider than that and darkened the receiver itself. 0: the thesis's one shift.
#ifndef CSSM_SLOPE
#define CSSM_SLOPE 1
#endif
// CSSM_SLOPE_MAX (metres; default: none): the slope-scaled shift is at most this far. The
// environment's lights (cssm_env, 0.05) need it: a sky patch tens of degrees across has kernels up
// to a quarter of the map, and the shift over them outgrew the objects' contact shadows (the search
// found no blocker and returned lit). Measured at env_lights 16, 160x120 (method none; env-studio
// against env-studio-direct.exr, sampler-wrap.glb's lone quad against the tracer, whose own noise is
// 0.038): no cap 0.104 / 0.029, 0.1 m 0.080 / 0.050, 0.05 m 0.076 / 0.057, 0.02 m 0.074 / 0.062,
// no shift at all 0.071 / 0.070 -- the cap trades the studio's contact shadows against the quad
// shadowing itself under grazing sky lights; 0.05 m keeps both within their tests.
#ifndef CSSM_SLOPE_MAX
#define CSSM_SLOPE_MAX 1e6
#endif
// CSSM_PLANE 1 (method cssm_plane, the environment's lights: render_env.c; default 0; an addition
// to the thesis, #11): a scale-free replacement of CSSM_SLOPE_MAX, the receiver-plane test VSSM has
// (VSSM_RECEIVER_PLANE, vssm.glsl). Stage 3's kernel, where the receiver's tangent plane spans
// more z_c over it than the series' own shift u_cssm.y (which already keeps that much of the
// receiver lit), is split into n x n sub-kernels, n the least that brings each one's span under
// u_cssm.y (at most CSSM_PLANE_N), each a lookup of its own width tested against the smaller of
// the pixel's depth d and the plane's farthest depth over the sub-kernel (its centre + half its
// span). The plane keeps the receiver's own nearer texels from counting as blockers (what the
// slope-scaled shift did, by moving d back over the whole kernel and with it past the objects'
// contact shadows); d keeps surfaces behind the plane's extension from counting. Stage 1 is the
// thesis's (one lookup at d, no slope shift). Measured at 160x120 (method none; env-studio against
// env-studio-direct.exr / sampler-wrap.glb's lone quad against the tracer, as CSSM_SLOPE_MAX
// above), env_lights 4, 8, 16, 32:
//   the 5 cm cap (cssm_env)   0.092 0.086 0.076 0.071 / 0.042 0.060 0.057 0.064
//   cssm_plane                0.089 0.082 0.070 0.064 / 0.038 0.054 0.049 0.054
// At 16 lights, other choices: both stages subdivided 0.072 / 0.048 (the direct pass 4x the cap's
// time, this one 1.65x); CSSM_PLANE_N 4 there 0.073 / 0.041 (and 4 lights 0.093, mean ratio
// 1.040); the plane at the sub-kernel's centre instead of its far edge 0.083 / 0.031 (the
// receiver's own half kept lit only by u_cssm.y, the objects' contact texels lost).
#ifndef CSSM_PLANE
#define CSSM_PLANE 0
#endif
#define CSSM_PLANE_N 3
const highp vec4 CSSM_CK = 3.14159265358979 * vec4(1.0, 3.0, 5.0, 7.0);
uniform highp vec4 u_cssm; // depth scale (z_c = x * z), receiver shift, SAT 1/q, unused
// Per layer the (min, max) of the normalised depth the map holds (cssm_range.comp): the bases were
// computed from z renormalised to it, so the receiver's depth is too ((0, 1) for cssm_thesis).
uniform highp sampler2DArray u_cssm_range;

highp vec2 cssm_range(int layer)
{
    GK_SHADOW_COUNT(r32f, 2);
    return vec2(texelFetch(u_cssm_range, ivec3(0, 0, layer), 0).r, texelFetch(u_cssm_range, ivec3(1, 0, layer), 0).r);
}

struct cssm_basis {
    highp vec4 c, s, zc, zs;
    highp float z;
};

#if CSSM_SAT
uniform highp usampler2DArray u_cssm_cos;
uniform highp usampler2DArray u_cssm_sin;
uniform highp usampler2DArray u_cssm_zcos;
uniform highp usampler2DArray u_cssm_zsin;
uniform highp usampler2DArray u_cssm_z;
uniform highp usampler2DArray u_cssm_z2;

highp uvec4 cssm_sat4(highp usampler2DArray s, ivec2 p, int layer)
{
    GK_SHADOW_COUNT(rgba32ui, any(lessThan(p, ivec2(0))) ? 0 : 1);
    return any(lessThan(p, ivec2(0))) ? uvec4(0u) : texelFetch(s, ivec3(p, layer), 0);
}

// Mean of a basis over the texel box [lo, hi], decoded from (v + 1) / 2 fixed point to [-1, 1].
highp vec4 cssm_box4(highp usampler2DArray s, ivec2 lo, ivec2 hi, int layer)
{
    ivec2 top = ivec2(int(u_shadow_light.w) - 1);
    lo = clamp(lo, ivec2(0), top);
    hi = clamp(hi, lo, top);
    ivec2 a = lo - 1;
    highp uvec4 sum = cssm_sat4(s, hi, layer) - cssm_sat4(s, ivec2(a.x, hi.y), layer) -
                      cssm_sat4(s, ivec2(hi.x, a.y), layer) + cssm_sat4(s, a, layer);
    highp float area = float((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
    return 2.0 * vec4(sum) * (u_cssm.z / area) - 1.0;
}

// Sub-texel box position as in gk_sat_moments_smooth (vssm_sat.glsl).
highp vec4 cssm_smooth4(highp usampler2DArray s, highp vec2 tc, highp vec2 w, int layer)
{
    ivec2 wi = max(ivec2(floor(w + 0.5)), ivec2(1));
    highp vec2 start = tc - 0.5 * vec2(wi);
    highp vec2 fl = floor(start);
    highp vec2 f = start - fl;
    ivec2 i0 = ivec2(fl);
    highp vec4 m00 = cssm_box4(s, i0, i0 + wi - 1, layer);
    highp vec4 m10 = cssm_box4(s, i0 + ivec2(1, 0), i0 + wi - 1 + ivec2(1, 0), layer);
    highp vec4 m01 = cssm_box4(s, i0 + ivec2(0, 1), i0 + wi - 1 + ivec2(0, 1), layer);
    highp vec4 m11 = cssm_box4(s, i0 + ivec2(1, 1), i0 + wi, layer);
    return mix(mix(m00, m10, f.x), mix(m01, m11, f.x), f.y);
}

cssm_basis cssm_fetch(highp vec2 uv, highp vec2 w, int layer, bool with_z)
{
    highp vec2 tc = uv * u_shadow_light.w;
    cssm_basis b;
    b.c = cssm_smooth4(u_cssm_cos, tc, w, layer);
    b.s = cssm_smooth4(u_cssm_sin, tc, w, layer);
    b.zc = vec4(0.0);
    b.zs = vec4(0.0);
    b.z = 0.0;
    if (with_z) {
        b.zc = cssm_smooth4(u_cssm_zcos, tc, w, layer);
        b.zs = cssm_smooth4(u_cssm_zsin, tc, w, layer);
        b.z = u_cssm.x * gk_sat_moments_smooth(u_cssm_z, u_cssm_z2, tc, w, layer, u_cssm.z).x;
    }
    return b;
}
#else
uniform highp sampler2DArray u_cssm_cos;
uniform highp sampler2DArray u_cssm_sin;
uniform highp sampler2DArray u_cssm_zcos;
uniform highp sampler2DArray u_cssm_zsin;
uniform highp sampler2DArray u_cssm_z;

// Trilinear lookups at the level whose texel matches the kernel (geometric mean of u and v widths:
// mipmaps are square, dong-001.md §1.3).
cssm_basis cssm_fetch(highp vec2 uv, highp vec2 w, int layer, bool with_z)
{
    highp vec3 p = vec3(uv, float(layer));
    highp float lod = log2(max(sqrt(w.x * w.y), 1.0));
    cssm_basis b;
    GK_SHADOW_COUNT(rgba16f, with_z ? 5 : 2);
    b.c = textureLod(u_cssm_cos, p, lod);
    b.s = textureLod(u_cssm_sin, p, lod);
    b.zc = vec4(0.0);
    b.zs = vec4(0.0);
    b.z = 0.0;
    if (with_z) {
        b.zc = textureLod(u_cssm_zcos, p, lod);
        b.zs = textureLod(u_cssm_zsin, p, lod);
        b.z = textureLod(u_cssm_z, p, lod).r;
    }
    return b;
}
#endif

// CSSM_TRIG_ROTATE 1 (default; #21): cos(c_k d) and sin(c_k d), k = 1..4, from one cos and one sin
// of pi d, the odd multiples by rotating by 2 pi d (angle addition: a few ulps apart from the direct
// calls, the series' value the same to float precision); 0: eight cos/sin calls. llvmpipe's cos and
// sin are long polynomials: cssm_plane's direct pass on env-studio, 320x180, 3.47G -> 3.28G
// instructions (callgrind), the 160x120 image bit-identical.
#ifndef CSSM_TRIG_ROTATE
#define CSSM_TRIG_ROTATE 1
#endif
void cssm_trig(highp float d, out highp vec4 cs, out highp vec4 sn)
{
#if CSSM_TRIG_ROTATE
    highp float x = 3.14159265358979 * d;
    highp float c1 = cos(x), s1 = sin(x);
    highp float c2 = (c1 - s1) * (c1 + s1), s2 = 2.0 * s1 * c1;
    highp float c3 = c1 * c2 - s1 * s2, s3 = s1 * c2 + c1 * s2;
    highp float c5 = c3 * c2 - s3 * s2, s5 = s3 * c2 + c3 * s2;
    highp float c7 = c5 * c2 - s5 * s2, s7 = s5 * c2 + c5 * s2;
    cs = vec4(c1, c3, c5, c7);
    sn = vec4(s1, s3, s5, s7);
#else
    cs = cos(CSSM_CK * d);
    sn = sin(CSSM_CK * d);
#endif
}

// Filtered lit test s_f (Eq. 5.3 with the Fourier basis) at shifted receiver depth d.
highp float cssm_lit(cssm_basis b, highp float d)
{
    highp vec4 cs, sn;
    cssm_trig(d, cs, sn);
    return 0.5 + 2.0 * dot(cs * b.s - sn * b.c, 1.0 / CSSM_CK);
}

// Numerator of CSM-Z (Eq. 5.11): <fbar z>, the same expansion as cssm_lit.
highp float cssm_znum(cssm_basis b, highp float d)
{
    highp vec4 cs, sn;
    cssm_trig(d, cs, sn);
    return 0.5 * b.z + 2.0 * dot(sn * b.zc - cs * b.zs, 1.0 / CSSM_CK);
}

// The filtered lit test and CSM-Z's numerator over the kernel of width w (texels) at uv, for the
// shifted receiver depth d: one lookup.
highp vec2 cssm_lookup(highp vec2 uv, highp vec2 w, int layer, bool with_z, highp float d)
{
    cssm_basis b = cssm_fetch(uv, w, layer, with_z);
    return vec2(cssm_lit(b, d), with_z ? cssm_znum(b, d) : 0.0);
}

// Mean of the filtered lit test and of CSM-Z's numerator over the kernel of width w (texels) at uv,
// for the shifted receiver depth d: one lookup, the slope-scaled shift (slope: half the plane's
// z_c span per texel) at most shift_max, or (CSSM_PLANE) n x n sub-kernels against the receiver
// plane, whose z_c changes by grad per texel.
highp vec2 cssm_filtered(highp vec2 uv, highp vec2 w, int layer, bool with_z, highp float d, highp vec2 grad,
                         highp vec2 slope, highp float shift_max)
{
#if CSSM_PLANE
    int n = int(clamp(ceil(dot(slope, w) / u_cssm.y), 1.0, float(CSSM_PLANE_N)));
    highp vec2 ws = w / float(n);
    highp float half_span = dot(slope, ws);
    highp vec2 r = vec2(0.0);
    // The sub-kernels row by row in one loop of n * n steps, (i, j) stepped without a division. Two
    // nested loops, each left by a break at n, gave the same sums in the same order but cost
    // llvmpipe far more (#21: with the stage-1 change in shadow_visibility, 4.79G -> 3.47G
    // instructions for two env-studio direct passes at 320x180, callgrind; the image bit-identical).
    int i = 0, j = 0;
    for (int k = 0; k < n * n; k++) {
        highp vec2 off = ((vec2(float(i), float(j)) + 0.5) / float(n) - 0.5) * w; // texels
        // kept above u_cssm.x - 1: d - z stays within the series' period (lit, not wrapped)
        highp float di = max(d + min(dot(grad, off) + half_span, 0.0), u_cssm.x - 0.95);
        r += cssm_lookup(uv + off / u_shadow_light.w, ws, layer, with_z, di);
        bool row_done = i + 1 >= n;
        i = row_done ? 0 : i + 1;
        j = row_done ? j + 1 : j;
    }
    return r / float(n * n);
#else
    return cssm_lookup(uv, w, layer, with_z, d - min(dot(slope, w), shift_max));
#endif
}

// The lighting pass's first draw for a splitting method (SHADOW_SPLIT 1, direct/light.frag;
// cssm_plane, shadow_cssm.c): CSSM settles no pixel short of its whole lookup, so that draw only
// adds and stencil-marks the pixels with no light; the second runs shadow_visibility for the rest.
highp float shadow_settle(highp vec3 world_pos)
{
    return -1.0;
}

highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal)
{
    highp vec3 pos = gk_shadow_offset(world_pos, world_normal);
    gk_shadow_coord c = gk_shadow_project(pos);
    if (!c.inside)
        return 1.0;
    int layer = int(c.layer);
    highp vec2 range = cssm_range(layer);
    // clamped like the map's own depths: a receiver behind everything the layer holds stays on the
    // plateau (d - z < 1, inside the series' period)
    highp float dn = clamp((gk_soft_norm(c.d - 0.5 * gk_shadow_texel_world(c.d)) - range.x) / (range.y - range.x), 0.0, 1.0);
    highp float d = u_cssm.x * dn - u_cssm.y;
#if CSSM_SLOPE || CSSM_PLANE
    // half the receiver plane's depth spread per texel of kernel width, in z_c units
    highp vec2 g = gk_shadow_receiver_gradient(c, pos, world_normal);
    highp float per_texel = u_shadow_light.w * (u_shadow_proj.y - u_shadow_proj.x) * (range.y - range.x);
    highp vec2 slope = 0.5 * abs(g) * u_cssm.x / per_texel;
    highp vec2 grad = g * u_cssm.x / per_texel; // the plane's signed change per texel (CSSM_PLANE)
#else
    highp vec2 grad = vec2(0.0), slope = vec2(0.0);
#endif
    // CSSM_SLOPE_MAX in z_c units
    highp float shift_max = CSSM_SLOPE_MAX * u_cssm.x / ((u_shadow_proj.y - u_shadow_proj.x) * (range.y - range.x));
    // Stage 1: initial kernel at the near plane; filtered test and CSM-Z over it.
    highp vec2 wi = gk_soft_kernel(c.d, u_shadow_proj.x);
#if CSSM_PLANE
    // the thesis's search, one lookup at d: the receiver's own nearer texels only pull z_avg toward
    // it (a narrower f_w), and the plane in stage 3 keeps them lit. Called straight, not through
    // cssm_filtered with no slope (n = 1, the same value): the loop there, whose count the compiler
    // cannot know, cost llvmpipe 4.79G -> 3.96G instructions by itself (#21, as above).
    highp vec2 f1 = cssm_lookup(c.uv, wi, layer, true, max(d, u_cssm.x - 0.95));
#else
    highp vec2 f1 = cssm_filtered(c.uv, wi, layer, true, d, grad, slope, shift_max);
#endif
    highp float occ = 1.0 - f1.x;
    if (occ < 1e-3)
        return 1.0; // no blockers
    // Stage 2: z_avg, final kernel f_w.
    highp float zavg = clamp(f1.y / occ, 0.0, u_cssm.x * dn);
    highp float zavg_world = gk_soft_denorm(range.x + (zavg / u_cssm.x) * (range.y - range.x));
    highp vec2 wf = gk_soft_kernel(c.d, zavg_world);
    // Stage 3: filtered test over f_w, ringing suppression, contact sharpening.
    highp float s = cssm_filtered(c.uv, wf, layer, false, d, grad, slope, shift_max).x;
    s = clamp(CSSM_ALPHA * (s - 0.5) + 0.5, 0.0, 1.0);
    highp float p = 1.0 + CSSM_SHARP_A * exp(-CSSM_SHARP_B * max(c.d - zavg_world, 0.0));
    return pow(s, p);
}
