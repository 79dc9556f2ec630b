// Multi-resolution splatting (seed 000 §3.2.2, photon-mapping-000-004.md §A.1.5): min–max mipmaps
// of linear depth and of each normal component, plus the region's mean position and geometry
// coverage. Level 0 reads the G-buffer at the indirect resolution (one texel per pixel); level l
// reduces the 2×2 children of level l − 1.
// T0 = (z_min, z_max, coverage, 0)   coverage = fraction of children with geometry
// T1 = (n_min.xyz, 0)   T2 = (n_max.xyz, 0)   T3 = (mean position.xyz − bounds centre, coverage)
// The ±1e30 sentinels become ±inf on RGBA16F targets, which min/max treat the same way.
// @variant LEVEL0=1
// @variant LEVELN=1
precision highp float;
precision highp int;
#ifdef LEVEL0
#include "common/gbuffer.glsl"
uniform ivec2 u_ind_size;
uniform vec3 u_origin;   // T3 stores x − u_origin (bounds centre): fp16 targets keep the precision
#else
uniform highp sampler2D u_t0;
uniform highp sampler2D u_t1;
uniform highp sampler2D u_t2;
uniform highp sampler2D u_t3;
#endif
layout(location = 0) out vec4 o_t0;
layout(location = 1) out vec4 o_t1;
layout(location = 2) out vec4 o_t2;
layout(location = 3) out vec4 o_t3;
void main()
{
    ivec2 q = ivec2(gl_FragCoord.xy);
#ifdef LEVEL0
    ivec2 px = min(ivec2((vec2(q) + 0.5) * u_viewport / vec2(u_ind_size)), ivec2(u_viewport) - 1);
    float depth = gb_depth(px);
    if (gb_background(depth)) {
        o_t0 = vec4(1e30, -1e30, 0.0, 0.0);
        o_t1 = vec4(1e30);
        o_t2 = vec4(-1e30);
        o_t3 = vec4(0.0);
        return;
    }
    vec3 x = gb_world_position(px);
    vec3 n = gb_normal(px);
    float z = length(x - u_eye);
    o_t0 = vec4(z, z, 1.0, 0.0);
    o_t1 = vec4(n, 0.0);
    o_t2 = vec4(n, 0.0);
    o_t3 = vec4(x - u_origin, 1.0);
#else
    ivec2 size = textureSize(u_t0, 0);
    vec4 t0 = vec4(1e30, -1e30, 0.0, 0.0), t1 = vec4(1e30), t2 = vec4(-1e30), t3 = vec4(0.0);
    float children = 0.0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            ivec2 c = 2 * q + ivec2(i, j);
            if (c.x >= size.x || c.y >= size.y)
                continue;   // odd sizes: the missing child does not count
            children += 1.0;
            vec4 a = texelFetch(u_t0, c, 0);
            vec4 p = texelFetch(u_t3, c, 0);
            t0 = vec4(min(t0.x, a.x), max(t0.y, a.y), t0.z + a.z, 0.0);
            t1 = min(t1, texelFetch(u_t1, c, 0));
            t2 = max(t2, texelFetch(u_t2, c, 0));
            t3 += vec4(p.xyz * p.w, p.w);
        }
    o_t0 = vec4(t0.xy, t0.z / max(children, 1.0), 0.0);
    o_t1 = t1;
    o_t2 = t2;
    o_t3 = vec4(t3.w > 0.0 ? t3.xyz / t3.w : vec3(0.0), t0.z / max(children, 1.0));
#endif
}
