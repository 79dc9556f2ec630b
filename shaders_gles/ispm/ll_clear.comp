// Empties the per-pixel lists before a build: GLES has no glClearBufferData.
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
#include "ispm/common.glsl"
layout(std430, binding = 1) writeonly buffer Pixels { Pixel px[]; };
uniform int u_pixels;
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i < u_pixels)
        px[i] = Pixel(-1, 0x7f800000u, 0u, 0u);   // head -1, zmin +inf, zmax 0, empty
}
