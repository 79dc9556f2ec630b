// Sparse tracing (thesis §3.4): a low-resolution pixel q traces the full-resolution pixel
// q * B + offset, B = 1 / trace_scale. The offsets follow a rotated-grid pattern over each 2x2 group
// of low-resolution pixels (explicit table instead of MSAA sample positions, summary A.7.1).
ivec2 sparse_pixel(ivec2 q, int B, ivec2 full_size)
{
    const vec2 rg[4] = vec2[4](vec2(0.375, 0.125), vec2(0.875, 0.375), vec2(0.125, 0.625), vec2(0.625, 0.875));
    int k = (q.x & 1) + 2 * (q.y & 1);
    ivec2 off = B > 1 ? ivec2(floor(rg[k] * float(B))) : ivec2(0);
    return min(q * B + off, full_size - 1);
}

vec3 gbuf_world_position(highp sampler2D depth_tex, mat4 inv_vp, ivec2 px, ivec2 size)
{
    float z = texelFetch(depth_tex, px, 0).r;
    vec2 uv = (vec2(px) + 0.5) / vec2(size);
    vec4 w = inv_vp * vec4(uv * 2.0 - 1.0, z * 2.0 - 1.0, 1.0);
    return w.xyz / w.w;
}

// Metallic and roughness from the renderer's G-buffer (albedo.a = metallic, normal.w = roughness; gi.h).
vec2 gbuf_metallic_roughness(highp sampler2D albedo_tex, highp sampler2D normal_tex, ivec2 px)
{
    return vec2(texelFetch(albedo_tex, px, 0).a, texelFetch(normal_tex, px, 0).w);
}
