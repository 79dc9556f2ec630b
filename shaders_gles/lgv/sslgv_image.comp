// The gathered SSLGV into three RGBA16F 2D textures (R, G, B x 4 SH) for the lookup.
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 9) readonly buffer Src { highp float src[]; };
layout(rgba16f, binding = 0) writeonly uniform highp image2D u_img_r;
layout(rgba16f, binding = 1) writeonly uniform highp image2D u_img_g;
layout(rgba16f, binding = 2) writeonly uniform highp image2D u_img_b;
uniform ivec2 u_size;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y)
        return;
    int b = 12 * (p.y * u_size.x + p.x);
    imageStore(u_img_r, p, vec4(src[b], src[b + 1], src[b + 2], src[b + 3]));
    imageStore(u_img_g, p, vec4(src[b + 4], src[b + 5], src[b + 6], src[b + 7]));
    imageStore(u_img_b, p, vec4(src[b + 8], src[b + 9], src[b + 10], src[b + 11]));
}
