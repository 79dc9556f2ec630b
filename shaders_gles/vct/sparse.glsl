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

// The renderer's G-buffer (common/gbuffer.glsl): positions from depth, metallic in albedo.a,
// roughness in normal.w (gi.h).
#define GB_ALBEDO_PRECISION highp
#include "common/gbuffer.glsl"

highp vec3 vct_world_position(ivec2 px)
{
    return gb_world_position(px);
}

vec2 vct_metallic_roughness(ivec2 px)
{
    return vec2(gb_albedo_metallic(px).a, gb_roughness(px));
}
