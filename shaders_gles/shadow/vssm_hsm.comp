// Min-max hierarchical shadow map (dong-001.md §5.3/§5.4, [Yang10] "HSM via mipmaps"): level l
// of u_dst_* holds the min and max normalised depth over the 2x2 (3 at an odd edge) texels of
// level l-1, so a lookup at level ceil(log2 kernel) over 2x2 texels bounds every depth under a
// kernel conservatively. One level per dispatch; 4 image units (the GLES 3.1 minimum).
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, r32f) readonly uniform highp image2DArray u_src_min;
layout(binding = 1, r32f) readonly uniform highp image2DArray u_src_max;
layout(binding = 2, r32f) writeonly uniform highp image2DArray u_dst_min;
layout(binding = 3, r32f) writeonly uniform highp image2DArray u_dst_max;
uniform int u_src_size;
uniform int u_dst_size;

void main()
{
    ivec3 g = ivec3(gl_GlobalInvocationID);
    if (g.x >= u_dst_size || g.y >= u_dst_size)
        return;
    // An odd source size leaves a last row/column that the last destination texel takes too.
    int ex = (g.x == u_dst_size - 1 && u_src_size > 2 * u_dst_size) ? 3 : 2;
    int ey = (g.y == u_dst_size - 1 && u_src_size > 2 * u_dst_size) ? 3 : 2;
    highp float lo = 1e30, hi = -1e30;
    for (int j = 0; j < ey; j++)
        for (int i = 0; i < ex; i++) {
            ivec3 p = ivec3(2 * g.x + i, 2 * g.y + j, g.z);
            lo = min(lo, imageLoad(u_src_min, p).r);
            hi = max(hi, imageLoad(u_src_max, p).r);
        }
    imageStore(u_dst_min, g, vec4(lo));
    imageStore(u_dst_max, g, vec4(hi));
}
