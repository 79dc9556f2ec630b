// vct_axis_clamp=thin (not in the thesis; README "The axis clamp at thin walls"): flags the voxels of
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0
// @variant CONSERVATIVE=0 AVERAGE_CAS=1 EMISSIVE=0
// thin walls, where a voxel grid cannot keep a wall's two sides apart: a voxel holding a fragment that
// faces +a (bit FACE_BIT(a, true), written by voxelize.comp FACE_PASS) whose own voxel or one of the
// next two behind it (-a) holds a fragment facing -a, i.e. the wall's other face within THIN_REACH
// voxels, and the same for -a. A single-sided wall (Cornell's, every floor) faces one way alone, and
// a gap between two surfaces facing each other is not a wall: neither is flagged. Only flagged voxels
// (and vct_thick's marks behind them, voxelize.comp THIN_ONLY) then stop the axis clamp
// (axis_dist.comp THIN_ONLY); a scene without thin walls (thin_count 0) is traced without the clamp.
// One invocation per voxel; it reads its neighbours' face bits and sets its own THIN_BIT (another
// bit of the word: the face bits it reads never change here).
#include "vct/common.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = 4) coherent buffer ThinFlags { uint thin_flags[]; };
// How many voxels were flagged: with none the C side traces without the clamp (vct_pass_trace).
layout(std430, binding = 5) buffer ThinCount { uint thin_count; };
// The other face may lie in the voxel itself or in the next two: a wall up to ~2 voxels thick, for
// a face on either side of a voxel boundary (light-leak's wall: 0.1 voxels at 64^3, on a boundary,
// so its faces are in the same or adjacent voxels with conservative voxelization).
#define THIN_REACH 2

uint faces_at(ivec3 c)
{
    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(u_res)))) return 0u;
    return thin_flags[vox_index(c)] & 0x3Fu;
}

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, ivec3(u_res)))) return;
    uint f = faces_at(c);
    if (f == 0u) return;
    bool thin = false;
    for (int a = 0; a < 3; a++) {
        ivec3 e = ivec3(a == 0 ? 1 : 0, a == 1 ? 1 : 0, a == 2 ? 1 : 0);
        for (int d = 0; d <= THIN_REACH; d++) {
            // facing +a: behind it lies -a, where the other face faces -a (and the other way round)
            if ((f & FACE_BIT(a, true)) != 0u && (faces_at(c - e * d) & FACE_BIT(a, false)) != 0u) thin = true;
            if ((f & FACE_BIT(a, false)) != 0u && (faces_at(c + e * d) & FACE_BIT(a, true)) != 0u) thin = true;
        }
    }
    if (thin) {
        atomicOr(thin_flags[vox_index(c)], THIN_BIT);
        atomicAdd(thin_count, 1u);
    }
}
