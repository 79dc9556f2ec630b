// The accumulated LGV into three RGBA16F 3D textures (R, G, B x 4 SH coefficients), which the
// lookup (lookup.frag) filters trilinearly (eq. 7's interpolated c_p).
precision highp float;
precision highp int;
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = 6) readonly buffer Acc { highp float acc[]; };
layout(rgba16f, binding = 0) writeonly uniform highp image3D u_vol_r;
layout(rgba16f, binding = 1) writeonly uniform highp image3D u_vol_g;
layout(rgba16f, binding = 2) writeonly uniform highp image3D u_vol_b;
uniform ivec3 u_dims;
void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, u_dims)))
        return;
    int b = 12 * ((c.z * u_dims.y + c.y) * u_dims.x + c.x);
    imageStore(u_vol_r, c, vec4(acc[b], acc[b + 1], acc[b + 2], acc[b + 3]));
    imageStore(u_vol_g, c, vec4(acc[b + 4], acc[b + 5], acc[b + 6], acc[b + 7]));
    imageStore(u_vol_b, c, vec4(acc[b + 8], acc[b + 9], acc[b + 10], acc[b + 11]));
}
