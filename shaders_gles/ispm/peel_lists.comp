// Tier B: the K peeled layers of each pixel as a list (node = pixel·K + layer, nearest first), so
// the trace is one shader for both tiers.
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
#include "ispm/common.glsl"
layout(std430, binding = 0) writeonly buffer Nodes { Node nodes[]; };
layout(std430, binding = 1) writeonly buffer Pixels { Pixel px[]; };
uniform highp usampler2D u_layers[4];   // ISPM_PEEL_LAYERS
uniform int u_width, u_height, u_k;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_width || p.y >= u_height)
        return;
    int pix = p.y * u_width + p.x;
    int head = -1;
    uint zmin = 0x7f800000u, zmax = 0u, count = 0u;
    for (int k = u_k - 1; k >= 0; k--) {
        uvec4 v = k == 0 ? texelFetch(u_layers[0], p, 0)
                : k == 1 ? texelFetch(u_layers[1], p, 0)
                : k == 2 ? texelFetch(u_layers[2], p, 0) : texelFetch(u_layers[3], p, 0);   // constant indices (ESSL 3.10)
        if (v.x == 0u)
            continue;   // cleared: no fragment this deep
        int idx = pix * u_k + k;
        nodes[idx] = Node(uintBitsToFloat(v.x), v.y, head, v.z, v.w);
        head = idx;
        zmin = min(zmin, v.x), zmax = max(zmax, v.x), count++;
    }
    px[pix] = Pixel(head, zmin, zmax, count);
}
