// Min-reduction of the distance mips (research B.1.2: never average distances across silhouettes):
// texel (x, y) of level l + 1 is the minimum of its four texels of level l, every layer at once.
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32ui, binding = 0) readonly uniform highp uimage2DArray u_src;
layout(r32ui, binding = 1) writeonly uniform highp uimage2DArray u_dst;
uniform int u_dst_res;
void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (p.x >= u_dst_res || p.y >= u_dst_res)
        return;
    ivec3 s = ivec3(p.xy * 2, p.z);
    // distances are >= 0, so their float bits order as unsigned integers
    uint m = min(min(imageLoad(u_src, s).r, imageLoad(u_src, s + ivec3(1, 0, 0)).r),
                 min(imageLoad(u_src, s + ivec3(0, 1, 0)).r, imageLoad(u_src, s + ivec3(1, 1, 0)).r));
    imageStore(u_dst, p, uvec4(m));
}
