// vct_axis_clamp (not in the thesis; vct/cone_lib.glsl axis_clamp): for every level-0 voxel,
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 NTH=1
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 NTH=2
// @variant CONSERVATIVE=0 AVERAGE_CAS=1 EMISSIVE=0 NTH=2
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 NTH=1 THIN_ONLY=1
// @variant CONSERVATIVE=0 AVERAGE_CAS=1 EMISSIVE=0 NTH=1 THIN_ONLY=1
// how far the NTH occupied voxel (a fragment's, or vct_thick's solid mark) lies along -x, +x, -y,
// +y, -z, +z, counting the voxel itself: 0 for NTH=1 in an occupied voxel, NONE when the row holds
// fewer that way. A cone sample whose trilinear footprint would read a texel past that voxel
// (NTH=1, vct_axis_clamp=first: no footprint reaches past the first surface) or holding it (NTH=2,
// second: past the first occupied voxel, but not as far as the next one) is read at a finer level
// instead. The next one is, for a wall thinner than a voxel, the voxel of its other face; behind a
// single-sided wall with nothing beyond it none, unless the wall fills two layers of voxels (a
// plane on a voxel boundary, voxelized conservatively) or vct_thick marked voxels behind it.
// One invocation per row of voxels along one axis: a forward sweep finds the distances back along
// -axis, a backward one those along +axis, both written into the row's own words (axis a's words at
// a * res^3, -axis in the low 16 bits).
#include "vct/common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) readonly buffer Scratch { uint s[]; };
layout(std430, binding = 3) buffer AxisDist { uint axis_dist[]; };
#define NONE 0xFFFFu
#ifndef NTH
#define NTH 1
#endif
#ifndef THIN_ONLY
#define THIN_ONLY 0
#endif
#if THIN_ONLY
// vct_axis_clamp=thin: only thin walls' voxels (THIN_BIT, thin_flag.comp) and the voxels behind them
// (THIN_MARK, voxelize.comp THIN_MARKS) stop a sample; a single-sided wall does not.
layout(std430, binding = 4) readonly buffer ThinFlags { uint thin_flags[]; };
#endif

bool occupied(ivec3 c)
{
#if THIN_ONLY
    return (thin_flags[vox_index(c)] & (THIN_BIT | THIN_MARK)) != 0u;
#elif AVERAGE_CAS
    return (s[CH_ALB * vox_count() + vox_index(c)] >> 24) != 0u;
#else
    return s[CH_COUNT * vox_count() + vox_index(c)] != 0u;   // fragments or the solid mark
#endif
}

void main()
{
    ivec2 uv = ivec2(gl_GlobalInvocationID.xy);
    int axis = int(gl_GlobalInvocationID.z);
    if (any(greaterThanEqual(uv, ivec2(u_res))) || axis > 2) return;
    // voxel t of the row: the axis is its coordinate `axis`, uv the other two
    ivec3 step_ax = ivec3(axis == 0 ? 1 : 0, axis == 1 ? 1 : 0, axis == 2 ? 1 : 0);
    ivec3 base = axis == 0 ? ivec3(0, uv) : (axis == 1 ? ivec3(uv.x, 0, uv.y) : ivec3(uv, 0));
    int off = axis * vox_count();
    // last: the nearest occupied voxel seen so far (its row position), prev: the one before it
    int last = -1, prev = -1;
    for (int t = 0; t < u_res; t++) {
        ivec3 c = base + step_ax * t;
        if (occupied(c)) { prev = last; last = t; }
        int hit = NTH == 1 ? last : prev;
        axis_dist[off + vox_index(c)] = hit < 0 ? NONE : uint(t - hit);
    }
    last = -1, prev = -1;
    for (int t = u_res - 1; t >= 0; t--) {
        ivec3 c = base + step_ax * t;
        if (occupied(c)) { prev = last; last = t; }
        int hit = NTH == 1 ? last : prev;
        int i = off + vox_index(c);
        axis_dist[i] = (axis_dist[i] & 0xFFFFu) | ((hit < 0 ? NONE : uint(hit - t)) << 16);
    }
}
