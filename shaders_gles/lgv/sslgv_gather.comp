// One SSLGV gathering iteration (seed 002 §4.3: ~12 iterations over the 4-connected neighbours
// within h; the update rule is not given, research B.2.7): S'(p) = S(p) + w sum_i (S(u_i) - S(p))
// over the neighbours u_i whose surface lies within h of p's (a symmetric test), w = 1/5: a
// depth-aware diffusion that keeps the total exactly (what one pixel gives, its neighbour takes).
// Iteration 0 reads the fixed-point injection (u_from_ints = 1).
// SSLGV_COUNT_LOADS: the bench's counting variant (app/gi/lgv/lgv_work.c): the storage-buffer
// loads in vec4s (12 floats of a pixel: 3) and the G-buffer depth reads of each invocation, added to
// SslgvLoads once. Never in the kiosk's frames.
// @variant -
// @variant SSLGV_COUNT_LOADS
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 8) readonly buffer Screen { highp int grid[]; };
layout(std430, binding = 9) readonly buffer Src { highp float src[]; };
layout(std430, binding = 10) writeonly buffer Dst { highp float dst[]; };
uniform highp sampler2D u_gb_depth;
uniform mat4 u_inv_viewproj;
uniform ivec2 u_size;
uniform float u_h;
uniform float u_fixed;
uniform int u_from_ints;
#ifdef SSLGV_COUNT_LOADS
layout(std430, binding = 11) buffer SslgvLoads { highp uint vec4_loads; highp uint depth_fetches; } sslgv_counted;
highp uint g_vec4_loads = 0u, g_depth_fetches = 0u;
#endif

float value(int i) { return u_from_ints == 1 ? float(grid[i]) / u_fixed : src[i]; }

bool surface(ivec2 px, out vec3 x)
{
    vec2 uv = (vec2(px) + 0.5) / vec2(u_size);
    float depth = texture(u_gb_depth, uv).r;
#ifdef SSLGV_COUNT_LOADS
    g_depth_fetches++;
#endif
    vec4 w = u_inv_viewproj * vec4(vec3(uv, depth) * 2.0 - 1.0, 1.0);
    x = w.xyz / w.w;
    return depth < 1.0;
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y)
        return;
    int b = 12 * (p.y * u_size.x + p.x);
    float s[12];
    for (int k = 0; k < 12; k++)
        s[k] = value(b + k);
#ifdef SSLGV_COUNT_LOADS
    g_vec4_loads += 3u;
#endif
    float o[12];
    for (int k = 0; k < 12; k++)
        o[k] = s[k];
    vec3 xp;
    if (surface(p, xp)) {
        const ivec2 nb[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
        for (int i = 0; i < 4; i++) {
            ivec2 q = p + nb[i];
            vec3 xq;
            if (q.x < 0 || q.y < 0 || q.x >= u_size.x || q.y >= u_size.y || !surface(q, xq) || distance(xp, xq) >= u_h)
                continue;
            int bq = 12 * (q.y * u_size.x + q.x);
            for (int k = 0; k < 12; k++)
                o[k] += 0.2 * (value(bq + k) - s[k]);
#ifdef SSLGV_COUNT_LOADS
            g_vec4_loads += 3u;
#endif
        }
    }
    for (int k = 0; k < 12; k++)
        dst[b + k] = o[k];
#ifdef SSLGV_COUNT_LOADS
    atomicAdd(sslgv_counted.vec4_loads, g_vec4_loads);
    atomicAdd(sslgv_counted.depth_fetches, g_depth_fetches);
#endif
}
