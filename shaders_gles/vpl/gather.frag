// Indirect gather (thesis §6.5 step 9) with interleaved sampling [Segovia06]: the pixel q of the
// indirect buffer takes the VPL subset s = (q.y mod B)·B + (q.x mod B), VPLs i = s + j·B², and
// every VPL i is shadowed by the soft visibility of its VAL C(i):
//   E(x) = Σ_i Φ_i/π · max(0, n_i·(x − p_i)/d) · max(0, n_x·(p_i − x)/d) / d² · Ṽ_C(i)(x)
// The sum over the subset is multiplied by B² (each subset is an unbiased 1/B² share); the
// geometry-aware blur averages the B×B subsets back. Clamp (not in the thesis): d² ≥ u_dmin2;
// the irradiance it removes goes to alpha (luminance) so the method can report it.
// Outputs: irradiance (rgb, a = removed), the pixel's world position and normal for the blur.
// One visibility define is required (vpl_vis_define in app/gi/vpl/vpl_gather.c):
// @variant VIS_CSSM=1
// @variant VIS_VSM=1
// @variant VIS_HARD=1
// @variant VIS_NONE=1
// @variant VIS_CSSM=1 MULTIRES=1
// @variant VIS_VSM=1 MULTIRES=1
// @variant VIS_HARD=1 MULTIRES=1
// @variant VIS_NONE=1 MULTIRES=1
// @variant VIS_CSSM=1 GATHER_COUNT_FETCHES=1
// @variant VIS_VSM=1 GATHER_COUNT_FETCHES=1
// @variant VIS_HARD=1 GATHER_COUNT_FETCHES=1
// @variant VIS_NONE=1 GATHER_COUNT_FETCHES=1
// @variant VIS_CSSM=1 MULTIRES=1 GATHER_COUNT_FETCHES=1
// @variant VIS_VSM=1 MULTIRES=1 GATHER_COUNT_FETCHES=1
// @variant VIS_HARD=1 MULTIRES=1 GATHER_COUNT_FETCHES=1
// @variant VIS_NONE=1 MULTIRES=1 GATHER_COUNT_FETCHES=1
// VIS_PER_VAL=M (vpl_gather.c vpl_per_val_define; CSSM and VSM only): each VAL's visibility once per
// receiver, up to M VALs, instead of once per VPL (see main).
// @variant VIS_CSSM=1 VIS_PER_VAL=32
// @variant VIS_VSM=1 VIS_PER_VAL=32
// @variant VIS_CSSM=1 MULTIRES=1 VIS_PER_VAL=32
// @variant VIS_VSM=1 MULTIRES=1 VIS_PER_VAL=32
// @variant VIS_CSSM=1 VIS_PER_VAL=32 GATHER_COUNT_FETCHES=1
// @variant VIS_VSM=1 MULTIRES=1 VIS_PER_VAL=32 GATHER_COUNT_FETCHES=1
precision highp float;
precision highp int;
precision highp sampler2DArray;
#include "common/gbuffer.glsl"
uniform ivec2 u_ind_size;
uniform highp sampler2D u_vpl;   // N×3: pos + label, nrm + area, flux
uniform highp sampler2D u_val;   // M×4: centre + far, normal + size, t + r_near, b + map res
uniform int u_n;
uniform int u_block;
uniform float u_dmin2;
uniform vec3 u_origin;       // bounds centre: o_pos (and multires T3) store x − u_origin
uniform float u_out_max;     // 65000 on RGBA16F targets (fp16 saturates at 65504), else no cap
#ifdef VIS_PER_VAL
uniform int u_n_val;         // VALs in u_val (at most VIS_PER_VAL)
#endif
#if defined(VIS_CSSM)
uniform sampler2DArray u_bcos, u_bsin, u_bzcos, u_bzsin, u_bz;
#elif defined(VIS_VSM)
uniform sampler2DArray u_bmom;
#elif defined(VIS_HARD)
uniform sampler2DArray u_bz;
#endif
layout(location = 0) out vec4 o_ind;
layout(location = 1) out vec4 o_pos;
layout(location = 2) out vec4 o_nrm;

const float PI = 3.14159265;

// The bench's counting variant (#21, app/gi/vpl/vpl_work.c; fragment-stage storage buffers
// capability-checked by the caller): each pixel (multires: each region shaded) adds up its fetches -- x unfiltered
// RGBA32F (the VPL and VAL tables), y filtered RGBA8 (CSSM's cos/sin bases), z filtered 16-bit
// float (CSSM's z bases and depth, VSM's moments), w unfiltered R16F (exact visibility's depth) --
// and adds them to the buffer once. Never in the kiosk's frames.
#ifdef GATHER_COUNT_FETCHES
layout(std430, binding = 6) buffer GatherFetches {
    highp uint unfiltered; highp uint rgba8; highp uint half_float; highp uint depth_r16f;
} gather_counted;
highp uvec4 gather_fetches = uvec4(0u);
#define GATHER_COUNT(x, y, z, w) gather_fetches += uvec4(uint(x), uint(y), uint(z), uint(w))
#else
#define GATHER_COUNT(x, y, z, w)
#endif

#if defined(VIS_CSSM)
const vec4 C = 3.14159265 * vec4(1.0, 3.0, 5.0, 7.0);
const float ALPHA = 1.12;      // ringing suppression for K = 4 (dong-001.md §3.3, computed)
// Contact sharpening, Eq. 5.9: p = 1 + A·exp(−B·(d − z_avg)), thesis values A = 30, B = 10
// (Fig. 5.3, ch. 5, direct light). For VAL maps it turns the grazing self-occlusion of planar
// receivers (big kernels over a floor seen edge-on) into black: F11 measured rel RMSE 0.70–0.79
// against exact visibility with A = 30 (0.44–0.54 with B = 100), 0.06–0.11 with A = 0. The thesis
// does not say it sharpens VAL shadows; we do not by default (define SHARP_A to restore it).
#ifndef SHARP_A
#define SHARP_A 0.0
#endif
const float SHARP_B = 10.0;
// The receiver's own surface is in the VAL's map at depth d: the 4-term series with α = 1.12 only
// saturates to "lit" at d − z ≤ −0.064 (dong-001.md §3.3), so receivers are tested at d − 0.07
// (normalised depth; ≈ 0.13 m in the unit Cornell box). Without it every receiver shadowed itself
// (F11 measured an error above "no visibility" at every M).
const float CSM_OFFSET = 0.07;
float csm_lit(vec4 cosz, vec4 sinz, float d)
{
    return 0.5 + 2.0 * dot(cos(C * d) * sinz - sin(C * d) * cosz, 1.0 / C);
}
#endif
#if defined(VIS_VSM)
const float VSM_OFFSET = 0.01; // Chebyshev is one-tailed: a small bias suffices
#endif
#if defined(VIS_CSSM) || defined(VIS_VSM)
// Deep umbra (vpl_umbra on, plane, horizon: the default; not in the thesis). The filtered test cannot tell a
// receiver 2 cm behind a wall from the receiver's own surface: CSSM's series ramps from lit to dark
// over ±0.064 of the normalised depth and the receiver is tested CSM_OFFSET in front of itself, so
// on light-leak (far ≈ 10 m) receivers up to ~1.4 m behind the wall kept light. The VAL's chain of
// maxima (val_zmax.frag: the largest depth under a texel, and whether the map has a gap there)
// answers with exact depths. The receiver is in the whole VAL's umbra (V = 0) when it lies behind
// the surface the map holds at its own texels, and over the VAL's penumbra kernel around it every
// depth lies in front of it, or the surface has no gap a ray from the receiver could pass through
// on its way to the VAL in front of that surface (light-leak's kernels also hold the lit room's far
// walls next to the wall, behind the receiver: a closed room has no gap).
// The kernel is CSSM's own (Fig. 6.2: w = atan((r − z)Δ/(z·r))/π) with the exact blocker depth z:
// over a smaller one (the VAL centre's point visibility, or a kernel per VPL from its offset to the
// centre; both without the gap test) the leak fell to 0.020–0.039 but cornell's one-bounce error
// rose 0.0776 -> 0.079–0.082 and atrium's 0.4085 -> 0.421–0.424 whatever the margin below: a
// cluster is not its centre.
uniform highp sampler2DArray u_bzmax;
uniform highp sampler2DArray u_bplane;   // vpl_umbra plane, horizon: the surface's plane per texel (val_depth.frag)
uniform int u_umbra;   // 0 off, 1 on (a depth margin), 2 plane, 3 horizon (plane, and the map's rim and horizon below)
uniform float u_lift;  // how far each map's centre is lifted off its VAL along the normal (vpl_valmap.c)
const float UMBRA_TAN_MAX = 20.0;   // grazing receivers (φ > 87°): no test, the filtered value stands
// Maxima of the chain over the 2×2 texels of `level` around uv: (depth, level 0: slope, coarser
// levels: gap). uv lies inside the square of their centres, so over a surface whose depth is
// linear across them one of them is at least the depth at uv; at level l > 0 they cover those of
// level 0, and the kernel when 2^l texels of level 0 span it.
vec2 chain_max(int k, vec2 uv, int level, float res)
{
    int lres = max(int(res) >> level, 1);
    ivec2 t0 = clamp(ivec2(floor(uv * float(lres) - 0.5)), ivec2(0), ivec2(max(lres - 2, 0)));
    GATHER_COUNT(0, 0, 0, 4);   // RG16F texelFetch: the R16F-nearest kind
    vec2 m = vec2(0.0);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++)
            m = max(m, texelFetch(u_bzmax, ivec3(min(t0 + ivec2(i, j), ivec2(lres - 1)), k), level).rg);
    return m;
}
// Receiver at normalised depth d = r/far in direction v (unit, from the centre), normal nx. The
// receiver's own surface is in the map if the VAL sees it, and a texel's depth differs from the
// depth at uv by at most the texel's reach along that surface, d·tanφ·Δθ (φ between nx and v;
// Δθ ≤ 2.83/res rad, half the diagonal of the paraboloid's largest texel, 4/res rad at its pole),
// plus fp16's rounding of z (2^-11 relative, twice). Measured without the gap test: a margin of
// 1/res instead of 2.83/res cut light-leak's residue 0.054 -> 0.039 but cost cornell 0.0776 ->
// 0.0789 (receivers shadowed themselves); using the slope the map stores instead of tanφ left
// 0.0234 with the gap test (0.0215 with tanφ).
// vpl_umbra=plane: whether the receiver, at r·v from the centre, is hidden behind the surfaces of
// the 2×2 texels around uv (the square of their centres holds uv). Each texel holds a plane
// (val_depth.frag); the receiver's own surface holds it on its plane at any angle, so no margin
// scaled by the slope is needed (that margin, vpl_umbra=on, left light-leak's dark floor, ceiling
// and side walls lit up to 0.2-0.3 m behind the wall: 77% of the leaked light, measured). It is
// hidden when it lies behind the plane of one texel A, and every other texel either hides it too or
// holds a point in front of A's plane (the two surfaces meet in a concave corner, as the lit floor
// meets the wall's foot: of such a pair the ray meets A first). A texel holding a point behind A's
// plane (a convex edge: a box's top against its side or the floor beyond it), no plane or a grazing
// one leaves the receiver lit: the ray may pass beside A, except (vpl_umbra=horizon) where the
// texel is one the paraboloid disc's rim crosses, or one outside the disc: outside it is no
// direction at all, and on the rim the triangles are rasterised with straight edges across the
// paraboloid's bend, so their parts on the VAL's side of its plane (left out, no plane) and planes
// of triangles the texel's own direction misses cover texels there (val_zmax.frag reads rim texels
// as left out for the same reason). Vetoes by texels without a plane there let 62% of light-leak's
// last leak through with `plane` (measured: receivers within 2.2° above a VAL's horizon, on the
// dark room's surfaces next to the planes of the lit room's floor, ceiling and side walls; 59 of
// the 4800 gather pixels), false convex edges there all that stayed with `horizon` at vpl_val_map
// 128 and 256 and vpl_m=32 until rim texels stopped vetoing at all. Tolerance: fp16 planes on RGBA16F
// targets round n and the centre's distance w to 2^-11 relative, (r + w·far)·2^-10 bounds the sum;
// fp32 ones round far less. Returns the distance from the centre to A along v (the nearest such A),
// the exact blocker depth the penumbra kernel needs, or 0 where the receiver is not hidden.
float behind_planes(int k, vec2 uv, float r, vec3 v, float res, float far, mat3 frame)
{
    int ires = int(res);
    ivec2 t0 = clamp(ivec2(floor(uv * res - 0.5)), ivec2(0), ivec2(max(ires - 2, 0)));
    GATHER_COUNT(4, 0, 0, 0);   // RGBA32F (RGBA16F on the fallback) texelFetch: the unfiltered kind
    vec4 pl[4];
    bool behind[4];
    int a = -1;
    float ta = r;
    for (int q = 0; q < 4; q++) {
        pl[q] = texelFetch(u_bplane, ivec3(min(t0 + ivec2(q & 1, q >> 1), ivec2(ires - 1)), k), 0);
        float w = pl[q].w * far;
        behind[q] = r * dot(v, pl[q].xyz) < -w - (r + w) * ldexp(1.0, -10);
        float t = behind[q] ? w / -dot(v, pl[q].xyz) : r;   // behind: the ray crosses the plane before r
        a = t < ta ? q : a;
        ta = min(ta, t);
    }
    if (a < 0)
        return 0.0;
    float wa = pl[a].w * far;
    for (int q = 0; q < 4; q++) {
        if (behind[q])
            continue;
        // The point of texel q: its centre's ray (the paraboloid inverted) meets its plane.
        vec2 s = (vec2(min(t0 + ivec2(q & 1, q >> 1), ivec2(ires - 1))) + 0.5) / res * 2.0 - 1.0;
        if (u_umbra == 3 && length(s) + sqrt(2.0) / res > 1.0)
            continue;   // on the rim or outside the disc: no way around A (above)
        float lz = (1.0 - dot(s, s)) / (1.0 + dot(s, s));
        vec3 dir = frame * vec3(s * (1.0 + lz), lz);
        float facing = -dot(dir, pl[q].xyz);
        if (facing < 1e-3)
            return 0.0;   // no plane (nothing drawn, or left out) or seen edge-on
        float t = pl[q].w * far / facing;
        if (t * dot(dir, pl[a].xyz) + wa < -(t + wa) * ldexp(1.0, -10))
            return 0.0;
    }
    return ta;
}

bool deep_umbra(int k, vec2 uv, float d, float r, float delta, float res, vec3 v, vec3 nx, float far, mat3 frame)
{
    float c = abs(dot(nx, v));
    float tan_phi = sqrt(max(1.0 - c * c, 0.0)) / max(c, 1.0 / UMBRA_TAN_MAX);
    float eps = d * (ldexp(1.0, -10) + tan_phi * 2.83 / res);
    float za;   // the blocker's distance from the centre along v
    if (u_umbra >= 2) {
        za = behind_planes(k, uv, r, v, res, far, frame);
        if (za <= 0.0)
            return false;
    } else {
        float zb = chain_max(k, uv, 0, res).x;   // the blocker in front of the receiver, if any
        if (tan_phi >= UMBRA_TAN_MAX || zb >= d - eps)
            return false;
        za = zb * r / d;
    }
    float w = atan((r - za) * delta / (za * r)) / PI;
    int level = int(ceil(log2(max(w * res, 1.0))));
    if (level == 0)
        return true;
    vec2 m = chain_max(k, uv, level, res);
    return m.x < d - eps || m.y == 0.0;
}
#endif

// Soft visibility of receiver x (normal nx) from VAL k (paraboloid CSSM / VSM), or hard per-VPL
// visibility.
float visibility(int k, vec3 x, vec3 nx)
{
#if defined(VIS_NONE)
    return 1.0;
#else
    GATHER_COUNT(4, 0, 0, 0);
    vec4 c0 = texelFetch(u_val, ivec2(k, 0), 0);
    vec4 c1 = texelFetch(u_val, ivec2(k, 1), 0);
    vec4 c2 = texelFetch(u_val, ivec2(k, 2), 0);
    vec4 c3 = texelFetch(u_val, ivec2(k, 3), 0);
    vec3 v = x - c0.xyz;
    float r = length(v);
    vec3 l = vec3(dot(v, c2.xyz), dot(v, c3.xyz), dot(v, c1.xyz)) / max(r, 1e-6);
#if defined(VIS_CSSM) || defined(VIS_VSM)
    // vpl_umbra=horizon: the map's centre is lifted u_lift off the VAL, so the band of that height
    // between the VAL's surface and the map's plane is lit by the VAL's own VPLs (at grazing
    // angles) but lies in the map's negative half-space, which the thesis takes as lit. A receiver
    // in the band is looked up at the horizon of its direction instead, the map's directions
    // nearest its own (within u_lift/r); the tests keep its own position, so the deep-umbra test
    // asks whether it lies behind the planes seen along that horizon. On light-leak the band held
    // 38% of the last leak with `plane` (the dark room's surfaces within 4.7 cm of the planes of the
    // lit room's floor, ceiling and side walls; 36 of the 4800 gather pixels); taking the whole
    // negative half-space as dark instead cost cornell 0.0776 -> 0.0844 and glass 0.894 -> 0.906
    // (the VPLs of clusters with mixed normals light it).
    float h = l.z * r;   // the receiver's height over the map's plane
    if (u_umbra == 3 && h <= 0.0 && h >= -u_lift && dot(l.xy, l.xy) > 0.0)
        l = vec3(normalize(l.xy), 1e-6);
#endif
    if (l.z <= 0.0 || r <= c2.w)
        return 1.0;   // negative half-space / inside the ignored near sphere: no information
    vec2 uv = 0.5 + 0.5 * l.xy / (1.0 + l.z);
    float far = c0.w, delta = c1.w, res = c3.w;
    float d = r / far;
#if defined(VIS_CSSM) || defined(VIS_VSM)
    float d_receiver = d;   // the deep-umbra test compares exact depths: no offset
#endif
#if defined(VIS_CSSM)
    d -= CSM_OFFSET;
#elif defined(VIS_VSM)
    d -= VSM_OFFSET;
#endif
#if defined(VIS_HARD)
    GATHER_COUNT(0, 0, 0, 1);
    float z = texelFetch(u_bz, ivec3(clamp(ivec2(uv * res), ivec2(0), ivec2(int(res) - 1)), k), 0).r;
    return d <= z + 0.01 ? 1.0 : 0.0;
#else
    float layer = float(k);
    // Initial kernel from the solid angle of the VAL seen through the near sphere r_n
    // (the PCSS analogue; the thesis gives no formula): w_i = 2·atan(½Δ·(r − r_n)/(r·r_n))/π.
    float rn = max(c2.w, 1e-3 * far);
    float wi = 2.0 * atan(0.5 * delta * max(r - rn, 0.0) / (r * rn)) / PI;
    float li = log2(max(wi * res, 1.0));
    vec3 tc = vec3(uv, layer);
#if defined(VIS_CSSM)
    GATHER_COUNT(0, 2, 0, 0);
    float si = csm_lit(textureLod(u_bcos, tc, li) * 2.0 - 1.0, textureLod(u_bsin, tc, li) * 2.0 - 1.0, d);
    float occ = 1.0 - si;
    if (occ < 1e-3)
        return 1.0;   // no blockers in the search kernel
    GATHER_COUNT(0, 0, 3, 0);
    float znum = 0.5 * textureLod(u_bz, tc, li).r
               + 2.0 * dot(sin(C * d) * textureLod(u_bzcos, tc, li) - cos(C * d) * textureLod(u_bzsin, tc, li), 1.0 / C);
    float zavg = clamp(znum / occ, 1e-4, d);
#else
    GATHER_COUNT(0, 0, 1, 0);
    vec2 m = textureLod(u_bmom, tc, li).rg;
    float var = max(m.y - m.x * m.x, 1e-6);
    float md = d - m.x;
    float pl = md <= 0.0 ? 1.0 : var / (var + md * md);
    // No "lit" early-out on the search kernel's Chebyshev bound: it is an upper bound, and over
    // the wide search kernel it said "lit" for most umbra receivers (F11: rel RMSE 0.240, as bad as
    // no visibility; 0.10 without the early-out at point lookups).
    pl = min(pl, 0.99);
    float zavg = clamp((m.x - pl * d) / (1.0 - pl), 1e-4, d);   // VSSM blocker depth
#endif
    // Penumbra kernel (Fig. 6.2): p·cosθ = (d − z_avg)Δ/z_avg, w = atan(p·cosθ/d)/π.
    float za = zavg * far;
    float w = atan((r - za) * delta / (za * r)) / PI;
    float lf = log2(max(w * res, 1.0));
#if defined(VIS_CSSM)
    GATHER_COUNT(0, 2, 0, 0);
    float s = csm_lit(textureLod(u_bcos, tc, lf) * 2.0 - 1.0, textureLod(u_bsin, tc, lf) * 2.0 - 1.0, d);
    s = clamp(ALPHA * (s - 0.5) + 0.5, 0.0, 1.0);
    s = SHARP_A > 0.0 ? pow(s, 1.0 + SHARP_A * exp(-SHARP_B * (d - zavg))) : s;
#else
    GATHER_COUNT(0, 0, 1, 0);
    vec2 mf = textureLod(u_bmom, tc, lf).rg;
    float vf = max(mf.y - mf.x * mf.x, 1e-6);
    float mdf = d - mf.x;
    float s = mdf <= 0.0 ? 1.0 : vf / (vf + mdf * mdf);
#endif
    if (u_umbra != 0 && s > 0.0 && deep_umbra(k, uv, d_receiver, r, delta, res, v / r, nx, far, mat3(c2.xyz, c3.xyz, c1.xyz)))
        return 0.0;
    return s;
#endif
#endif
}

#ifdef MULTIRES
// Multi-resolution gather (seed 000 §3.2.2, Algorithm 3.1): shade a region of this level only when
// it is continuous and its parent is not (level 0: a pixel is always continuous; the top level's
// parent counts as discontinuous). Regions mixing geometry and background are discontinuous.
uniform highp sampler2D u_mr_t0, u_mr_t1, u_mr_t2, u_mr_t3;
uniform highp sampler2D u_mr_p0, u_mr_p1, u_mr_p2;
uniform int u_mr_level, u_mr_top;
uniform float u_tau_z, u_tau_n;
bool mr_disc(vec4 t0, vec4 t1, vec4 t2)
{
    if (t0.z > 0.0 && t0.z < 1.0)
        return true;
    if (t0.y - t0.x > u_tau_z * t0.x)
        return true;
    vec3 dn = t2.xyz - t1.xyz;
    return max(dn.x, max(dn.y, dn.z)) > u_tau_n;
}
#endif

void main()
{
    ivec2 q = ivec2(gl_FragCoord.xy);
    vec3 x, nx;
#ifdef MULTIRES
    vec4 t0 = texelFetch(u_mr_t0, q, 0);
    if (t0.z <= 0.0)
        discard;
    vec4 t1 = texelFetch(u_mr_t1, q, 0), t2 = texelFetch(u_mr_t2, q, 0);
    if (u_mr_level > 0 && mr_disc(t0, t1, t2))
        discard;
    if (u_mr_top == 0) {
        ivec2 p = q / 2;
        if (!mr_disc(texelFetch(u_mr_p0, p, 0), texelFetch(u_mr_p1, p, 0), texelFetch(u_mr_p2, p, 0)))
            discard;
    }
    x = texelFetch(u_mr_t3, q, 0).xyz + u_origin;
    nx = normalize(t1.xyz + t2.xyz);
    int bb = 1, s = 0;   // every region takes every VPL
#else
    ivec2 full_size = ivec2(u_viewport);
    ivec2 px = min(ivec2((vec2(q) + 0.5) * u_viewport / vec2(u_ind_size)), full_size - 1);
    float depth = gb_depth(px);
    if (gb_background(depth)) {
        o_ind = vec4(0.0);
        o_pos = vec4(0.0);
        o_nrm = vec4(0.0);
        return;
    }
    x = gb_world_position(px);
    nx = gb_normal(px);
    int bb = u_block * u_block;
    int s = (q.y % u_block) * u_block + (q.x % u_block);
#endif
#ifdef VIS_PER_VAL
    // Ṽ_C(i)(x) depends on the VPL's VAL alone, so each VAL's is evaluated once here and looked up
    // per VPL: the same function of the same arguments, the same values. llvmpipe runs every branch
    // of a fragment's SIMD lanes on both sides, so the per-VPL call cost its whole lookup (and the
    // deep-umbra test) for every VPL of the subset, skipped or not; vpl_gather.c picks this variant
    // when the VALs are fewer than the VPLs a receiver takes (u_n / B², or all N with MULTIRES).
    float val_vis[VIS_PER_VAL];
    for (int k = 0; k < u_n_val; k++)
        val_vis[k] = visibility(k, x, nx);
#endif
    vec3 E = vec3(0.0);
    float removed = 0.0;
    for (int i = s; i < u_n; i += bb) {
        GATHER_COUNT(2, 0, 0, 0);
        vec4 p = texelFetch(u_vpl, ivec2(i, 0), 0);
        vec3 flux = texelFetch(u_vpl, ivec2(i, 2), 0).rgb;
        if (p.w < 0.0 || dot(flux, vec3(1.0)) <= 0.0)
            continue;
        GATHER_COUNT(1, 0, 0, 0);
        vec3 ni = texelFetch(u_vpl, ivec2(i, 1), 0).xyz;
        vec3 L = p.xyz - x;
        float d2 = dot(L, L);
        vec3 w = L * inversesqrt(max(d2, 1e-12));
        float g = max(dot(nx, w), 0.0) * max(-dot(ni, w), 0.0);
        if (g <= 0.0)
            continue;
#ifdef VIS_PER_VAL
        float V = val_vis[clamp(int(p.w), 0, VIS_PER_VAL - 1)];
#else
        float V = visibility(int(p.w), x, nx);
#endif
        vec3 e = flux * (g * V / PI);
        vec3 full = e / max(d2, 1e-8);
        vec3 clamped = e / max(d2, u_dmin2);
        E += clamped;
        removed += dot(full - clamped, vec3(0.2126, 0.7152, 0.0722));
    }
#ifdef GATHER_COUNT_FETCHES
    atomicAdd(gather_counted.unfiltered, gather_fetches.x);
    atomicAdd(gather_counted.rgba8, gather_fetches.y);
    atomicAdd(gather_counted.half_float, gather_fetches.z);
    atomicAdd(gather_counted.depth_r16f, gather_fetches.w);
#endif
#ifdef MULTIRES
    o_ind = vec4(min(E, vec3(u_out_max)), 1.0);   // a = hasData
    o_pos = vec4(min(removed, u_out_max));
    o_nrm = vec4(0.0);
#else
    float scale = float(bb);
    o_ind = min(vec4(E * scale, removed * scale), vec4(u_out_max));
    o_pos = vec4(x - u_origin, 1.0);
    o_nrm = vec4(nx, 1.0);
#endif
}
