// Cone tracing through the pre-integrated voxel map (thesis §3.3, Algorithm 1 with the errata of
// summary A.2.7 fixed; the loop is summary A.3). Voxel space [0,1]^3, premultiplied RGBA.
//   ISO_MIPS=1:  one texture with an isotropic mip chain (glGenerateMipmap), the cheapest level.
//   ISO_MIPS=0:  level 0 isotropic (u_vox0, thesis §4: anisotropic level 0 ripples) plus six
//                directional views +X,-X,+Y,-Y,+Z,-Z holding levels 1.., packed two per axis texture
//                (u_voxp0..2 level k = lod k+1; 3 fetches a sample above lod 1, 4 below).
//   ANISO_LEVEL0=1 (with ISO_MIPS=0; vct_level0=aniso, not in the thesis): the directional views
//                start at level 0 (u_voxp0..2 level k = lod k), every sample reads the three views
//                its direction sees (3 fetches); the cones do not sample u_vox0 (the empty-space
//                skip still reads its opacity).
//   AXIS_WEIGHT_SQ=0: thesis sample = sum |d_axis| T_face(axis)  (over-weights diagonals up to 1.73x)
//   AXIS_WEIGHT_SQ=1: weights d_axis^2 (sum 1)  -- not in the thesis, calibrated option.
//   OPACITY_CORRECTION=1: alpha' = 1 - (1 - alpha)^(step / voxel(lod)) -- not in the thesis.
//   CLIP_CONES=1: every cone stops at the volume border (thesis code: only apertures < 0.3; wide
//                 cones keep sampling clamped edge texels, the Fig. 18b banding) -- not in the thesis.
//   EMPTY_SKIP=1: Algorithm 1's empty-space skipping for cones narrower than 0.3 (vct/empty_skip.glsl).
//   AXIS_CLAMP=1, 2: vct_axis_clamp=first, second (not in the thesis): no sample reads a texel past the
//                 first occupied voxel along +-x, +-y, +-z from it, or holding the second one
//                 (axis_clamp below).
#ifndef CLIP_CONES
#define CLIP_CONES 0
#endif
#ifndef AXIS_CLAMP
#define AXIS_CLAMP 0
#endif
#ifndef ANISO_LEVEL0
#define ANISO_LEVEL0 0
#endif
// The map lod of the directional chains' first level.
#define DIR_FIRST_LOD (ANISO_LEVEL0 != 0 ? 0.0 : 1.0)
uniform highp sampler3D u_vox0;
#if !ISO_MIPS
// The six directional chains packed per axis (app/gi/vct/vct_internal.h voxp): u_voxp0 holds +X in
// z < 1/2 and -X, mirrored in z, in z >= 1/2 of every level, u_voxp1 the Y pair, u_voxp2 the Z pair. A sample picks
// its half by a coordinate offset, not by choosing a sampler: one fetch per axis, also where the
// pixels sharing a SIMD vector (or a GPU wave) trace cones whose directions differ in sign, which
// with six samplers meant both of an axis's textures were read (llvmpipe executes both sides of a
// branch under a mask, fetches included).
uniform highp sampler3D u_voxp0;
uniform highp sampler3D u_voxp1;
uniform highp sampler3D u_voxp2;
// The same textures through a sampler without mip filtering (vct.c level0_sampler): the samples
// below lod 1 read only the chains' first level, and llvmpipe then filters one level, not two.
uniform highp sampler3D u_voxp0_l0;
uniform highp sampler3D u_voxp1_l0;
uniform highp sampler3D u_voxp2_l0;
uniform float u_dir_levels; // levels in each directional chain (from lod DIR_FIRST_LOD of the map)
#endif
uniform float u_res_f;      // level-0 resolution
uniform float u_step_mul;   // step = max(diameter * u_step_mul, 1 voxel): 1 = text/Alg. 1, 0.5 = code
uniform float u_ao_lambda;  // AO distance falloff (thesis code: 725, d in voxel-space units)
// Footprint clamp (not in the thesis; gk_vct_options.footprint_clamp): a sample of diameter D is
// read at lod log2(D res), between a level whose texels are <= D and one whose texels are <= 2 D,
// and a trilinear fetch reads texels up to 1.5 texels from its centre: up to 3 D away. So a wide
// cone's coarse samples overlap the receiver's own surface once D > h / 3 (h = height above the
// receiver's tangent plane). The surface then lights itself (isotropic radiance) or shadows itself
// (its dark back), and since h starts at the apex offset, which is in voxels, this begins closer
// to the receiver on finer grids: the Cornell box's error rose with resolution. With c > 0 the
// sample diameter is capped at c h (default c = 1/3), the cone is narrower near its receiver and
// takes smaller steps there. 0: off (thesis).
uniform float u_footprint_clamp;

#if !ISO_MIPS
// What a cone needs of its direction for the directional samples, computed once per cone: the
// axis weights (thesis |d|, or d^2) and where the view its direction sees lies in the packed
// texture: texture z = zoff + zmul z, (0, 1/2) for the +axis view (cones with d_a < 0), (1, -1/2)
// for the -axis view, stored mirrored.
struct cone_axes { vec3 w; vec3 zoff; vec3 zmul; };

cone_axes cone_axes_for(vec3 d)
{
    cone_axes a;
#if AXIS_WEIGHT_SQ
    a.w = d * d;
#else
    a.w = abs(d);
#endif
    a.zoff = step(0.0, d);
    a.zmul = 0.5 - a.zoff;
    return a;
}

// sum_a w_a T_view(a)(p, lodd), lodd = level in the directional chains (map lod - DIR_FIRST_LOD). At z = 0 each
// view lies at the texture's own edge (clamp-to-edge, as with separate textures). At z = 1 the two
// views of one axis meet, mirrored, so what filtering reads across the seam is the other view of
// the same edge voxels; z is clamped to the half-texel border of the finer of the two levels
// trilinear filtering reads (exact there), and the coarser level then reads at most a quarter of
// its other view's edge texel, only in the outermost half texel of the grid.
vec4 dir_sample(vec3 p, cone_axes a, float lodd)
{
    float texels = u_res_f * exp2(-DIR_FIRST_LOD - min(floor(lodd), u_dir_levels - 1.0));  // per half, in z, finer level
    float z = min(p.z, 1.0 - 0.5 / texels);
    return a.w.x * textureLod(u_voxp0, vec3(p.xy, a.zoff.x + a.zmul.x * z), lodd)
         + a.w.y * textureLod(u_voxp1, vec3(p.xy, a.zoff.y + a.zmul.y * z), lodd)
         + a.w.z * textureLod(u_voxp2, vec3(p.xy, a.zoff.z + a.zmul.z * z), lodd);
}

// dir_sample at lodd = 0 (the chains' first level only).
vec4 dir_sample_level0(vec3 p, cone_axes a)
{
    float z = min(p.z, 1.0 - 1.0 / u_res_f);
    return a.w.x * textureLod(u_voxp0_l0, vec3(p.xy, a.zoff.x + a.zmul.x * z), 0.0)
         + a.w.y * textureLod(u_voxp1_l0, vec3(p.xy, a.zoff.y + a.zmul.y * z), 0.0)
         + a.w.z * textureLod(u_voxp2_l0, vec3(p.xy, a.zoff.z + a.zmul.z * z), 0.0);
}
#endif

#include "vct/empty_skip.glsl"

#if !ISO_MIPS
// A sample below lod 1: with the isotropic level 0, mix(level 0, directional level 1, lod), as the
// thesis's quadrilinear step into the chains; with vct_level0=aniso the views' levels 0 and 1.
vec4 fine_sample(vec3 p, cone_axes ax, float lod)
{
#if ANISO_LEVEL0
    return dir_sample(p, ax, lod);
#else
    return (1.0 - lod) * textureLod(u_vox0, p, 0.0) + lod * dir_sample_level0(p, ax);
#endif
}
#endif

#if AXIS_CLAMP
// vct_axis_clamp (not in the thesis; gk_vct_options has no field for it, the knob selects it). Why:
// a trilinear fetch at level k reads the two texels whose centres bracket the sample on each axis,
// so a sample within half a level-k texel of a wall reads the texel on the wall's far side, beside
// it, whatever the directional views make of the texels in front (a lateral blend, not a front-to-
// back one). A wall thinner than a voxel on a texel boundary (light-leak's: x = 0 at every level)
// then shows its far side's radiance to every coarse sample near it. Here each sample is read at a
// level no coarser than the largest at which both texels it reads on every axis lie on its side of
// the first occupied voxel along that axis from its own voxel, that voxel included (AXIS_CLAMP=1),
// or hold no voxel from the second occupied one on (2: a wall thinner than a voxel has its other
// face in the next voxel; a single-sided wall one voxel deep with nothing behind it narrows nothing):
// axis_dist.comp's distances, 3 words per voxel. At level 0, where nothing finer exists, the sample
// moves instead (axis_clamp). The clamp narrows the samples near walls, and never widens one: the
// cone takes more, shorter steps there (their opacity integrates as before).
layout(std430, binding = 3) readonly buffer AxisDist { uint axis_dist[]; };

// Narrows a sample at p (voxel space) of diameter ds to the coarsest map level it may read; where
// that is level 0 and even its trilinear pair crosses the limit (a sample within half a voxel of a
// wall's voxel, or inside it), moves p along that axis to the centre of the nearest voxel it may
// read, so that level 0 is read from this side alone. step_max: the longest step along d (voxel
// space) that does not carry the next sample past the limit's edge on any axis, so that some sample
// lands in the wall's first voxel (a wide sample's long step jumped over the wall before).
void axis_clamp(inout vec3 p, inout float ds, vec3 d, out float step_max)
{
    vec3 pv = p * u_res_f;
    ivec3 c = clamp(ivec3(floor(pv)), ivec3(0), ivec3(u_res - 1));
    int i = vox_index(c), n = vox_count();
    vec3 lo = vec3(-1e9), hi = vec3(1e9);
    for (int a = 0; a < 3; a++) {
        uint w = axis_dist[a * n + i];
        uint dm = w & 0xFFFFu, dp = w >> 16;
        // the lowest and highest edges a texel read may have: the first occupied voxel's far edges
        // (AXIS_CLAMP=1), the second one's near edges (2)
        if (dm != 0xFFFFu) lo[a] = float(c[a] - int(dm) + (AXIS_CLAMP - 1));
        if (dp != 0xFFFFu) hi[a] = float(c[a] + int(dp) + (2 - AXIS_CLAMP));
    }
    float level = 0.0;
    for (int k = 1; k < 16; k++) {
        float t = exp2(float(k));                                 // level k's texel, in voxels
        if (t > u_res_f) break;
        vec3 first = floor(pv / t - 0.5);                         // the lower texel of each axis's pair
        if (any(lessThan(first * t, lo)) || any(greaterThan((first + 2.0) * t, hi))) break;
        level = float(k);
    }
    ds = min(ds, exp2(level) / u_res_f);
    vec3 room = mix(pv - lo, hi - pv, step(0.0, d));          // voxels to the limit ahead, per axis
    vec3 ad = max(abs(d), vec3(1e-6));
    step_max = max(min(room.x / ad.x, min(room.y / ad.y, room.z / ad.z)), 0.0) / u_res_f;
    if (ds * u_res_f <= 1.0) {   // level 0 alone: keep its pair of voxels within [lo, hi] where there is room
        vec3 q = clamp(pv, lo + 0.5, hi - 0.5);
        p = mix(p, q / u_res_f, vec3(lessThanEqual(lo + 0.5, hi - 0.5)));
    }
}
#endif

// Early termination (not in the thesis): a cone whose accumulated opacity reaches this stops; what
// it no longer adds is at most (1 - CONE_OPAQUE) of the radiance behind, below the 16-bit targets'
// and the references' noise on the Cornell box.
#define CONE_OPAQUE 0.99

// One cone sample's place: position, and the sample diameter (footprint clamp) -> lod.
struct cone_pos { vec3 p; float ds; float lod; bool ended; float step_max; };

cone_pos cone_at(vec3 apex, vec3 d, float dst, float diam, float aperture, float max_dist, vec4 plane, float acc_a)
{
    cone_pos c;
    c.p = apex + d * dst;
    // thesis code: only cones narrower than 0.3 stop at the volume border
    c.ended = acc_a >= CONE_OPAQUE || dst > max_dist ||
              ((CLIP_CONES != 0 || aperture < 0.3) && (any(lessThan(c.p, vec3(0.0))) || any(greaterThan(c.p, vec3(1.0)))));
    c.ds = diam;
    c.step_max = 1e30;
    if (u_footprint_clamp > 0.0) c.ds = min(c.ds, u_footprint_clamp * max(dot(plane.xyz, c.p) + plane.w, 0.0));
#if AXIS_CLAMP
    if (!c.ended) axis_clamp(c.p, c.ds, d, c.step_max);
#endif
    c.lod = max(log2(c.ds * u_res_f), 0.0);
    return c;
}

// plane: the receiver's tangent plane (xyz normal, w offset) in voxel space, for the footprint clamp.
// Front-to-back accumulation C += (1 - A) C_s, A += (1 - A) a_s; AO ao += (1 - ao) a_s / (1 + d lambda).
// Returns the premultiplied radiance seen along the cone; ao = accumulated occlusion (0 = open);
// steps = the samples taken, x below lod 1 (ISO_MIPS=0: 4 fetches each), y from lod 1 on (3 each; with
// ISO_MIPS every sample is one fetch and counts in x): the trace's work (app/gi/vct/vct_work.c).
vec4 trace_cone(vec3 apex, vec3 d, float aperture, float max_dist, vec4 plane, out float ao, out ivec2 steps)
{
    float vs = 1.0 / u_res_f, dst = 0.0, diam = 0.0, ao_acc = 0.0;
    vec4 acc = vec4(0.0);
    steps = ivec2(0);
#if !ISO_MIPS
    cone_axes ax = cone_axes_for(d);
#endif
    // The sample diameter never shrinks along a cone (the cone widens, and its height above the
    // receiver's plane grows: every cone leaves the hemisphere's base), so the samples below lod 1,
    // which blend the isotropic level 0 with the directional level 1 (4 fetches), all come first:
    // phase 0 takes them, phase 1 the rest with 3 fetches and no blend. Two loops, not a branch in
    // one, since a SIMD machine pays for both sides of a branch its lanes disagree on. (AXIS_CLAMP
    // narrows samples near walls again, so there phase 1 takes samples below lod 1 too.)
    bool ended = false;
    for (int it = 0; it < 4096; it++) {
        cone_pos c = cone_at(apex, d, dst, diam, aperture, max_dist, plane, acc.a);
        if (c.ended) { ended = true; break; }
#if !ISO_MIPS
        if (c.lod >= 1.0) break;
        vec4 s = fine_sample(c.p, ax, c.lod);
#else
        vec4 s = textureLod(u_vox0, c.p, c.lod);
#endif
        float step_len = max(min(c.ds * u_step_mul, c.step_max), vs);
#if OPACITY_CORRECTION
        float a_c = 1.0 - pow(max(1.0 - s.a, 0.0), step_len / (exp2(c.lod) * vs));
        s = s.a > 1e-6 ? s * (a_c / s.a) : vec4(0.0);
#endif
        acc += (1.0 - acc.a) * s;
        ao_acc += (1.0 - ao_acc) * s.a / (1.0 + dst * u_ao_lambda);
#if EMPTY_SKIP
        if (aperture < SKIP_MAX_APERTURE && s.a < SKIP_EPS) step_len = max(step_len, empty_skip(c.p, d));
#endif
        dst += step_len;
        diam = dst * aperture;
        steps.x++;
    }
#if !ISO_MIPS
    for (int it = 0; it < 4096; it++) {
        if (ended) break;
        cone_pos c = cone_at(apex, d, dst, diam, aperture, max_dist, plane, acc.a);
        if (c.ended) break;
#if AXIS_CLAMP
        // near a wall the axis clamp narrows a sample again, below lod 1 too
        bool fine = c.lod < 1.0;
        vec4 s = fine ? fine_sample(c.p, ax, c.lod) : dir_sample(c.p, ax, c.lod - DIR_FIRST_LOD);
#else
        vec4 s = dir_sample(c.p, ax, c.lod - DIR_FIRST_LOD);
#endif
        float step_len = max(min(c.ds * u_step_mul, c.step_max), vs);
#if OPACITY_CORRECTION
        float a_c = 1.0 - pow(max(1.0 - s.a, 0.0), step_len / (exp2(c.lod) * vs));
        s = s.a > 1e-6 ? s * (a_c / s.a) : vec4(0.0);
#endif
        acc += (1.0 - acc.a) * s;
        ao_acc += (1.0 - ao_acc) * s.a / (1.0 + dst * u_ao_lambda);
#if EMPTY_SKIP
        if (aperture < SKIP_MAX_APERTURE && s.a < SKIP_EPS) step_len = max(step_len, empty_skip(c.p, d));
#endif
        dst += step_len;
        diam = dst * aperture;
#if AXIS_CLAMP
        if (fine) steps.x++; else steps.y++;
#else
        steps.y++;
#endif
    }
#endif
    ao = ao_acc;
    return acc;
}
