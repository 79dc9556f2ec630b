// Final-gather reduction (app/gi/lightmap/lm_gather.h): one work group per tile sums p F_h and
// F_h over the tile's res x res pixels in fp32 and writes E = π Σ p F_h / Σ F_h (the discrete
// coverage, errata B.7 #1; Σ p F_h / coverage is E/π, errata #2) into the IIM texel and its gutter
// copies. 64 invocations: the GLES 3.1 minimum is 128 a group.
// REDUCE_COUNT_FETCHES: the bench's counting variant (#21, app/gi/lightmap/lm_work.c), one atomic add
// per invocation of the tile texels it read. Never in the kiosk's frames.
// @variant -
// @variant REDUCE_COUNT_FETCHES
precision highp float;
precision highp int;
#ifdef REDUCE_COUNT_FETCHES
layout(std430, binding = 6) buffer ReduceFetches { highp uint texels; } reduce_counted;
#endif
layout(local_size_x = 8, local_size_y = 8) in;
uniform highp usampler2D u_tiles;            // RGBA32UI: radiance's fp32 bits
layout(rgba16f, binding = 0) uniform writeonly highp image2D u_iim;
uniform int u_res;
uniform float u_half_width;
struct Job { ivec4 meta; ivec4 target[9]; }; // meta.x: targets used
layout(std430, binding = 0) readonly buffer Jobs { Job jobs[]; };
shared vec4 s_sum[64];

void main()
{
    int tile = int(gl_WorkGroupID.x);
    int lid = int(gl_LocalInvocationIndex);
    float da = 2.0 * u_half_width / float(u_res);
    vec4 acc = vec4(0.0);                     // rgb: Σ p F_h, a: Σ F_h
#ifdef REDUCE_COUNT_FETCHES
    uint fetched = 0u;
#endif
    for (int y = int(gl_LocalInvocationID.y); y < u_res; y += 8)
        for (int x = int(gl_LocalInvocationID.x); x < u_res; x += 8) {
            vec2 q = -vec2(u_half_width) + (vec2(x, y) + 0.5) * da;
            float r = dot(q, q) + 1.0;
            float fh = da * da / (3.14159265 * r * r);
            vec3 p = uintBitsToFloat(texelFetch(u_tiles, ivec2(tile * u_res + x, y), 0).rgb);
            acc += vec4(p * fh, fh);
#ifdef REDUCE_COUNT_FETCHES
            fetched++;
#endif
        }
#ifdef REDUCE_COUNT_FETCHES
    atomicAdd(reduce_counted.texels, fetched);
#endif
    s_sum[lid] = acc;
    barrier();
    for (int s = 32; s > 0; s >>= 1) {
        if (lid < s)
            s_sum[lid] += s_sum[lid + s];
        barrier();
    }
    if (lid == 0) {
        vec3 E = 3.14159265 * s_sum[0].rgb / s_sum[0].a;
        Job j = jobs[tile];
        for (int k = 0; k < j.meta.x; k++)
            imageStore(u_iim, j.target[k].xy, vec4(E, 1.0));
    }
}
