// Zeroes the voxel scratch channels inside a region (GLES 3.1 has no glClearBufferData).
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0
#include "vct/common.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = 1) writeonly buffer Scratch { uint s[]; };
uniform ivec3 u_region_lo;
uniform ivec3 u_region_size;
uniform int u_channels;
void main()
{
    ivec3 g = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(g, u_region_size))) return;
    int i = vox_index(u_region_lo + g), N = vox_count();
    for (int c = 0; c < u_channels; c++) s[c * N + i] = 0u;
}
