// Voxelization without geometry shaders (summary A.7.1 (b)): one invocation per triangle, from a
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0
// @variant CONSERVATIVE=0 AVERAGE_CAS=1 EMISSIVE=1
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 VOXELIZE_COUNT_ATOMICS=1
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 SOLID_PASS=1
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 SOLID_PASS=1 THIN_MARKS=1
// @variant CONSERVATIVE=0 AVERAGE_CAS=1 EMISSIVE=0 SOLID_PASS=1 THIN_MARKS=1
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 FACE_PASS=1
// @variant CONSERVATIVE=0 AVERAGE_CAS=1 EMISSIVE=0 FACE_PASS=1
// world-space triangle SSBO. For every voxel column along the triangle's dominant axis
// (argmax |n|, the axis the thesis's GS projects along) over the triangle's bounding box:
//   CONSERVATIVE=1: every voxel the triangle touches (Schwarz & Seidel 2010 triangle/box overlap,
//                   26-separating; "conservative by construction").
//   CONSERVATIVE=0: thin (6-separating) voxelization as the thesis's rasterizer makes it: the voxel
//                   column whose centre lies inside the projected triangle gets the one voxel at the
//                   triangle's depth there (centre sampling, no dilation).
// Averaging of all fragments that hit a voxel:
//   AVERAGE_CAS=0 (default): fixed-point sums with atomicAdd + a count; the inject pass divides.
//                 Integer addition is order-independent, so the result is bit-exact run to run.
//   AVERAGE_CAS=1 (thesis): the moving average A_{n+1} = (n A_n + x_{n+1})/(n+1) in packed RGBA8
//                 through a compare-and-swap loop with the 4-bit counter in the byte LSBs and the
//                 16-retry cap of the thesis code, defects included (counter wraps at 16).
// alphaMode MASK (glTF: alpha = base colour factor x texture x COLOR_0, below alphaCutoff no
// surface): one sample per voxel-triangle overlap, at the voxel's point on the triangle (the voxel
// centre projected on its plane, or the column's centre at the triangle's depth), its barycentrics
// clamped to the triangle; below the cutoff the triangle leaves that voxel empty. A voxel part
// covered by a hole and part by the surface is all of one or the other, as its sample says.
// SSBO atomics are core in GLES 3.1 compute (image atomics need OES_shader_image_atomic there),
// so the scratch is one SSBO rather than r32ui images.
#include "vct/common.glsl"
layout(local_size_x = 64) in;
// SOLID_PASS=1: vct_thick's second dispatch, which visits the same voxels and only marks the voxels
// behind them solid (thicken); the first writes the fragments as without vct_thick.
#ifndef SOLID_PASS
#define SOLID_PASS 0
#endif
// vct_axis_clamp=thin (vct/thin_flag.comp): FACE_PASS=1, a dispatch of its own after the fragments',
// records per voxel which ways the fragments in it face (FACE_* bits, vct/common.glsl); THIN_MARKS=1
// (with SOLID_PASS) marks THIN_MARK, in the flag volume, on the voxels up to u_thick behind the
// fragments of the voxels thin_flag.comp flagged THIN_BIT only: where the axis clamp stops too.
#ifndef FACE_PASS
#define FACE_PASS 0
#endif
#ifndef THIN_MARKS
#define THIN_MARKS 0
#endif
#if FACE_PASS || THIN_MARKS
layout(std430, binding = 4) coherent buffer ThinFlags { uint thin_flags[]; };
#endif

// p0..p2: xyz world position, w the vertex's alpha (factor x COLOR_0); uv01, uv2_mask.xy: the
// vertices' base-colour UVs (KHR_texture_transform applied); uv2_mask.z: the material's layer of
// u_alpha_tex (-1: none), .w its alphaCutoff (-1: not masked). app/gi/vct/vct_tris.c.
struct Tri { vec4 p0; vec4 p1; vec4 p2; vec4 albedo; vec4 emission; vec4 uv01; vec4 uv2_mask; };
layout(std430, binding = 0) readonly buffer Tris { Tri tris[]; };
layout(std430, binding = 1) coherent buffer Scratch { uint s[]; };
// The bench's counting variant (app/gi/vct/vct_work.c): the scratch-buffer atomics each triangle
// did, one per channel of each voxel it wrote (a compare-and-swap average counts once, its retries
// not), added to a buffer once per triangle. Never in the kiosk's frames.
#ifdef VOXELIZE_COUNT_ATOMICS
layout(std430, binding = 2) buffer VoxelizeAtomics { highp uint atomics; } voxelize_counted;
highp uint voxelize_atomics = 0u;
#endif

uniform vec3 u_grid_origin;
uniform float u_voxel_size;
uniform int u_tri_first;
uniform int u_tri_count;
uniform ivec3 u_region_lo;    // voxels outside [lo, hi] are not written (dirty-region update)
uniform ivec3 u_region_hi;
uniform float u_emission_scale;  // 1 / max emission of the scene
uniform mediump sampler2DArray u_alpha_tex;  // masked materials' base-colour alpha (vct_alpha.c)
#if SOLID_PASS
uniform float u_thick;           // vct_thick: voxels marked solid behind each fragment (see thicken)
#endif

// true where the masked triangle T (vertices v0..v2, voxel units) has a hole at its point p
bool alpha_cut(Tri T, vec3 v0, vec3 v1, vec3 v2, vec3 p)
{
    if (T.uv2_mask.w < 0.0)
        return false;
    vec3 d0 = v1 - v0, d1 = v2 - v0, d2 = p - v0;
    float d00 = dot(d0, d0), d01 = dot(d0, d1), d11 = dot(d1, d1), d20 = dot(d2, d0), d21 = dot(d2, d1);
    float den = d00 * d11 - d01 * d01;
    vec2 b12 = vec2(d11 * d20 - d01 * d21, d00 * d21 - d01 * d20) / den;
    vec3 b = clamp(vec3(1.0 - b12.x - b12.y, b12), 0.0, 1.0);
    b /= max(b.x + b.y + b.z, 1e-6);
    float a = dot(b, vec3(T.p0.w, T.p1.w, T.p2.w));
    if (T.uv2_mask.z >= 0.0) {
        vec2 uv = b.x * T.uv01.xy + b.y * T.uv01.zw + b.z * T.uv2_mask.xy;
        a *= textureLod(u_alpha_tex, vec3(uv, T.uv2_mask.z), 0.0).r;
    }
    return a < T.uv2_mask.w;
}

uint pack8(vec4 v) { uvec4 u = uvec4(clamp(v, 0.0, 255.0)); return (u.w << 24) | (u.z << 16) | (u.y << 8) | u.x; }
vec4 vct_unpack8(uint v) { return vec4(float(v & 0xFFu), float((v >> 8) & 0xFFu), float((v >> 16) & 0xFFu), float(v >> 24)); }
uint encN(uint m, uint n) { return (m & 0xFEFEFEFEu) | (n & 1u) | ((n & 2u) << 7) | ((n & 4u) << 14) | ((n & 8u) << 21); }
uint decN(uint m) { return (m & 1u) | ((m & 0x100u) >> 7) | ((m & 0x10000u) >> 14) | ((m & 0x1000000u) >> 21); }

// Thesis moving average (A.2.1 / S.2), val in [0,1].
void cas_average(int idx, vec4 val)
{
    val *= 255.0;
    uint newV = encN(pack8(val), 1u);
    uint prev = 0u;
    for (int it = 0; it < 16; ++it) {           // thesis code: retry cap 16
        uint cur = atomicCompSwap(s[idx], prev, newV);
        if (cur == prev) break;
        vec4 r = vct_unpack8(cur & 0xFEFEFEFEu);
        uint n = decN(cur);
        r = (r * float(n) + val) / float(n + 1u);
        r = round(r * 0.5) * 2.0;                // keep the LSBs free for the counter
        newV = encN(pack8(r), n + 1u);           // n + 1 == 16 wraps to 0 (thesis behaviour)
        prev = cur;
    }
}

void write_voxel(ivec3 c, vec3 alb, vec3 n, vec3 frac, vec3 emi)
{
    if (any(lessThan(c, u_region_lo)) || any(greaterThan(c, u_region_hi))) return;
    int i = vox_index(c), N = vox_count();
#ifdef VOXELIZE_COUNT_ATOMICS
    // the channels written below: albedo, normal, position (+ emission) averages, or those three
    // sums per component and the count
    voxelize_atomics += uint(AVERAGE_CAS != 0 ? 3 + EMISSIVE : 10 + 3 * EMISSIVE);
#endif
#if AVERAGE_CAS
    cas_average(CH_ALB * N + i, vec4(alb, 1.0));
    cas_average(CH_NRM * N + i, vec4(n * 0.5 + 0.5, 1.0));
    cas_average(CH_POS * N + i, vec4(frac, 1.0));
#if EMISSIVE
    cas_average(CH_EMI * N + i, vec4(emi, 1.0));
#endif
#else
    uvec3 qa = uvec3(clamp(alb, 0.0, 1.0) * 255.0 + 0.5);
    ivec3 qn = ivec3(round(n * 127.0));
    uvec3 qp = uvec3(clamp(frac, 0.0, 1.0) * 255.0 + 0.5);
    atomicAdd(s[CH_COUNT * N + i], 1u);
    for (int k = 0; k < 3; k++) {
        atomicAdd(s[(CH_ALB + k) * N + i], qa[k]);
        atomicAdd(s[(CH_NRM + k) * N + i], uint(qn[k]));
        atomicAdd(s[(CH_POS + k) * N + i], qp[k]);
    }
#if EMISSIVE
    uvec3 qe = uvec3(clamp(emi, 0.0, 1.0) * 255.0 + 0.5);
    for (int k = 0; k < 3; k++) atomicAdd(s[(CH_EMI + k) * N + i], qe[k]);
#endif
#endif
}

// vct_thick (not in the thesis; fixed-point averaging only: the C side runs no SOLID_PASS with the
// thesis's CAS averages): solid ("thick") voxelization of thin walls. Each fragment also marks the
// voxels behind it, along -n up to u_thick voxels from its point p on the plane (points every half
// voxel), solid: opaque, with no radiance and no albedo (SOLID_BIT, vct/common.glsl). The mark is a
// bit beside the count, not a fragment, so a voxel that holds fragments keeps its radiance averaged
// over them alone (tests/gpu/test_vct_leak.c). Why: a wall thinner than a voxel on a voxel boundary
// (light-leak) has its lit face, and the lit room's floor and ceiling beside it, in the column just
// behind its dark face; a trilinear sample of a cone from the dark room between the two columns'
// centres sees part of the lit column before its opacity reaches 1. The dark face's own column is
// opaque already, so one voxel behind changes nothing (leak 0.132% -> 0.129% at 64^3); 1.5 voxels
// behind the lit face fill the dark room's column in front of the wall, and the cone is opaque
// before its samples reach the lit column. The price: the marks behind a thin shell's one face (a
// ring, a balustrade) cover its other face from that side (tests/e2e/vct_leak.sh, README).
#if SOLID_PASS
void write_solid(ivec3 c)
{
    if (any(lessThan(c, max(u_region_lo, ivec3(0)))) || any(greaterThan(c, min(u_region_hi, ivec3(u_res - 1))))) return;
#if THIN_MARKS
    atomicOr(thin_flags[vox_index(c)], THIN_MARK);
#else
    atomicOr(s[CH_COUNT * vox_count() + vox_index(c)], SOLID_BIT);
#endif
}

void thicken(ivec3 c, vec3 p, vec3 nn)
{
#if THIN_MARKS
    if ((thin_flags[vox_index(c)] & THIN_BIT) == 0u) return;   // not a thin wall's: no marks behind it
#endif
    ivec3 last = c;
    for (int k = 1; float(k) * 0.5 <= u_thick + 1e-3; k++) {
        ivec3 b = ivec3(floor(p - nn * (0.5 * float(k))));
        if (b != last && b != c) write_solid(b);
        last = b;
    }
}
#endif

#if FACE_PASS
// The ways the fragment's normal faces (face_bits, vct/common.glsl), into its voxel's flag word.
void write_faces(ivec3 c, vec3 nn)
{
    if (any(lessThan(c, u_region_lo)) || any(greaterThan(c, u_region_hi))) return;
    uint f = face_bits(nn);
    if (f != 0u) atomicOr(thin_flags[vox_index(c)], f);
}
#endif

// Component access by a runtime axis index (0, 1, 2), and the cyclic swizzle that makes `axis`
// the third coordinate (the GS swizzle of summary S.1).
vec3 to_axis(vec3 p, int axis) { return axis == 0 ? p.yzx : (axis == 1 ? p.zxy : p.xyz); }
ivec3 from_axis(ivec3 q, int axis) { return axis == 0 ? q.zxy : (axis == 1 ? q.yzx : q.xyz); }
vec3 from_axis_f(vec3 q, int axis) { return axis == 0 ? q.zxy : (axis == 1 ? q.yzx : q.xyz); }

void main()
{
    int t = int(gl_GlobalInvocationID.x);
    if (t >= u_tri_count) return;
    Tri T = tris[u_tri_first + t];
    vec3 v0 = (T.p0.xyz - u_grid_origin) / u_voxel_size;   // voxel units: voxel size h = 1
    vec3 v1 = (T.p1.xyz - u_grid_origin) / u_voxel_size;
    vec3 v2 = (T.p2.xyz - u_grid_origin) / u_voxel_size;
    vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
    vec3 n = cross(e0, e1);
    float nl = length(n);
    if (nl < 1e-12) return;                                   // degenerate
    vec3 nn = n / nl;
    vec3 an = abs(n);
    int axis = (an.x >= an.y && an.x >= an.z) ? 0 : (an.y >= an.z ? 1 : 2);
    vec3 emi = T.emission.rgb * u_emission_scale;

    // the voxels visited: the region's, and with vct_thick those within its reach outside it, whose
    // fragments may mark voxels inside it solid (write_voxel and write_solid keep to the region)
#if SOLID_PASS
    ivec3 reach = ivec3(int(ceil(u_thick)));
#else
    ivec3 reach = ivec3(0);
#endif
    ivec3 rlo = max(u_region_lo - reach, ivec3(0)), rhi = min(u_region_hi + reach, ivec3(u_res - 1));
    ivec3 lo = clamp(ivec3(floor(min(v0, min(v1, v2)))), rlo, rhi);
    ivec3 hi = clamp(ivec3(floor(max(v0, max(v1, v2)))), rlo, rhi);
    if (any(greaterThan(lo, hi))) return;
    vec3 lo3 = to_axis(vec3(lo), axis), hi3 = to_axis(vec3(hi), axis);
    vec3 w0 = to_axis(v0, axis), w1 = to_axis(v1, axis), w2 = to_axis(v2, axis);
    vec3 wn = to_axis(n, axis);                               // |wn.z| is the largest component
    // plane: dot(wn, w - w0) = 0 -> depth z(a, b) = w0.z - (wn.x (a - w0.x) + wn.y (b - w0.y)) / wn.z
    float dzda = -wn.x / wn.z, dzdb = -wn.y / wn.z;

#if CONSERVATIVE
    // Schwarz & Seidel 2010 overlap test with h = 1 (summary S.3).
    vec3 cpt = vec3(n.x > 0.0 ? 1.0 : 0.0, n.y > 0.0 ? 1.0 : 0.0, n.z > 0.0 ? 1.0 : 0.0);
    float d1 = dot(n, cpt - v0), d2 = dot(n, (vec3(1.0) - cpt) - v0);
    float sz = n.z >= 0.0 ? 1.0 : -1.0, sx = n.x >= 0.0 ? 1.0 : -1.0, sy = n.y >= 0.0 ? 1.0 : -1.0;
    vec2 nxy0 = vec2(-e0.y, e0.x) * sz, nxy1 = vec2(-e1.y, e1.x) * sz, nxy2 = vec2(-e2.y, e2.x) * sz;
    float dxy0 = -dot(nxy0, v0.xy) + max(0.0, nxy0.x) + max(0.0, nxy0.y);
    float dxy1 = -dot(nxy1, v1.xy) + max(0.0, nxy1.x) + max(0.0, nxy1.y);
    float dxy2 = -dot(nxy2, v2.xy) + max(0.0, nxy2.x) + max(0.0, nxy2.y);
    vec2 nyz0 = vec2(-e0.z, e0.y) * sx, nyz1 = vec2(-e1.z, e1.y) * sx, nyz2 = vec2(-e2.z, e2.y) * sx;
    float dyz0 = -dot(nyz0, v0.yz) + max(0.0, nyz0.x) + max(0.0, nyz0.y);
    float dyz1 = -dot(nyz1, v1.yz) + max(0.0, nyz1.x) + max(0.0, nyz1.y);
    float dyz2 = -dot(nyz2, v2.yz) + max(0.0, nyz2.x) + max(0.0, nyz2.y);
    vec2 nzx0 = vec2(-e0.x, e0.z) * sy, nzx1 = vec2(-e1.x, e1.z) * sy, nzx2 = vec2(-e2.x, e2.z) * sy;
    float dzx0 = -dot(nzx0, v0.zx) + max(0.0, nzx0.x) + max(0.0, nzx0.y);
    float dzx1 = -dot(nzx1, v1.zx) + max(0.0, nzx1.x) + max(0.0, nzx1.y);
    float dzx2 = -dot(nzx2, v2.zx) + max(0.0, nzx2.x) + max(0.0, nzx2.y);
    for (int b = int(lo3.y); b <= int(hi3.y); b++)
        for (int a = int(lo3.x); a <= int(hi3.x); a++) {
            // depth range of the plane over the column's square, +-1 voxel of slack
            float zc = w0.z + dzda * (float(a) + 0.5 - w0.x) + dzdb * (float(b) + 0.5 - w0.y);
            float zr = 0.5 * (abs(dzda) + abs(dzdb));
            int z0 = max(int(lo3.z), int(floor(zc - zr)) - 1), z1 = min(int(hi3.z), int(floor(zc + zr)) + 1);
            for (int z = z0; z <= z1; z++) {
                ivec3 c = from_axis(ivec3(a, b, z), axis);
                vec3 p = vec3(c);
                float np = dot(n, p);
                if ((np + d1) * (np + d2) > 0.0) continue;
                if (dot(nxy0, p.xy) + dxy0 < 0.0 || dot(nxy1, p.xy) + dxy1 < 0.0 || dot(nxy2, p.xy) + dxy2 < 0.0) continue;
                if (dot(nyz0, p.yz) + dyz0 < 0.0 || dot(nyz1, p.yz) + dyz1 < 0.0 || dot(nyz2, p.yz) + dyz2 < 0.0) continue;
                if (dot(nzx0, p.zx) + dzx0 < 0.0 || dot(nzx1, p.zx) + dzx1 < 0.0 || dot(nzx2, p.zx) + dzx2 < 0.0) continue;
                vec3 pc = p + 0.5;
                pc -= nn * dot(nn, pc - v0);                   // voxel centre projected on the plane
                if (alpha_cut(T, v0, v1, v2, pc)) continue;
#if SOLID_PASS
                thicken(c, pc, nn);
#elif FACE_PASS
                write_faces(c, nn);
#else
                write_voxel(c, T.albedo.rgb, nn, pc - p, emi);
#endif
            }
        }
#else
    // Edge functions of the projected triangle (counter-clockwise after orienting by wn.z).
    float o = wn.z >= 0.0 ? 1.0 : -1.0;
    for (int b = int(lo3.y); b <= int(hi3.y); b++)
        for (int a = int(lo3.x); a <= int(hi3.x); a++) {
            vec2 q = vec2(float(a) + 0.5, float(b) + 0.5);
            float E0 = o * ((w1.x - w0.x) * (q.y - w0.y) - (w1.y - w0.y) * (q.x - w0.x));
            float E1 = o * ((w2.x - w1.x) * (q.y - w1.y) - (w2.y - w1.y) * (q.x - w1.x));
            float E2 = o * ((w0.x - w2.x) * (q.y - w2.y) - (w0.y - w2.y) * (q.x - w2.x));
            if (E0 < 0.0 || E1 < 0.0 || E2 < 0.0) continue;
            float z = w0.z + dzda * (q.x - w0.x) + dzdb * (q.y - w0.y);
            int zi = int(floor(z));
            if (zi < int(lo3.z) || zi > int(hi3.z)) continue;
            ivec3 c = from_axis(ivec3(a, b, zi), axis);
            vec3 frac = from_axis_f(vec3(0.5, 0.5, z - float(zi)), axis);
            if (alpha_cut(T, v0, v1, v2, vec3(c) + frac)) continue;
#if SOLID_PASS
            thicken(c, vec3(c) + frac, nn);
#elif FACE_PASS
            write_faces(c, nn);
#else
            write_voxel(c, T.albedo.rgb, nn, frac, emi);
#endif
        }
#endif
#ifdef VOXELIZE_COUNT_ATOMICS
    if (voxelize_atomics > 0u)
        atomicAdd(voxelize_counted.atomics, voxelize_atomics);
#endif
}
