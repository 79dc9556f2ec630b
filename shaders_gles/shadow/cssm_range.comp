// CSSM depth range per map layer (app/render/shadow/shadow_cssm.c, #11): the Fourier test's
// transition has a fixed width in normalised depth (the scaled, clamped K = 4 test saturates 0.064
// past the shifted receiver, dong-001.md §3.3), so over [near, far] it spans metres: a blocker 1 m
// above the shadow-planes receiver was 0.09 of the range and left 0.19 of the light in the umbra.
// Renormalising each layer to the depths it actually holds makes the same transition a fraction
// of the scene's depth extent.
//   CSSM_RANGE_PASS 0: one work group per layer reduces the normalised linear depth z (R32F, from
//                      vssm_linearize.comp) to (min, max) over the texels that hold geometry (z < 1:
//                      empty texels read the far plane) into texels (0, 0) and (1, 0) of u_range;
//                      a layer without geometry gets (0, 1).
//   CSSM_RANGE_PASS 1: z rewritten in place as clamp((z - min) / (max - min), 0, 1) (empty texels
//                      stay 1: behind everything, lit).
// @variant CSSM_RANGE_PASS=0
// @variant CSSM_RANGE_PASS=1
precision highp float;
precision highp int;
uniform int u_size;
#if CSSM_RANGE_PASS == 0
layout(local_size_x = 256) in;
layout(binding = 0, r32f) readonly uniform highp image2DArray u_z;
layout(binding = 1, r32f) writeonly uniform highp image2DArray u_range;
shared highp float s_lo[256];
shared highp float s_hi[256];

void main()
{
    int layer = int(gl_WorkGroupID.z);
    int t = int(gl_LocalInvocationIndex);
    highp float lo = 2.0, hi = -1.0;
    for (int i = t; i < u_size * u_size; i += 256) {
        highp float z = imageLoad(u_z, ivec3(i % u_size, i / u_size, layer)).r;
        if (z < 1.0) {
            lo = min(lo, z);
            hi = max(hi, z);
        }
    }
    s_lo[t] = lo;
    s_hi[t] = hi;
    barrier();
    for (int n = 128; n > 0; n >>= 1) {
        if (t < n) {
            s_lo[t] = min(s_lo[t], s_lo[t + n]);
            s_hi[t] = max(s_hi[t], s_hi[t + n]);
        }
        barrier();
    }
    if (t == 0) {
        bool empty = s_hi[0] < s_lo[0];
        imageStore(u_range, ivec3(0, 0, layer), vec4(empty ? 0.0 : s_lo[0]));
        // a layer of one depth (a plane facing the light) keeps a range of at least 1e-3
        imageStore(u_range, ivec3(1, 0, layer), vec4(empty ? 1.0 : max(s_hi[0], s_lo[0] + 1e-3)));
    }
}
#else
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, r32f) uniform highp image2DArray u_z;
layout(binding = 1, r32f) readonly uniform highp image2DArray u_range;

void main()
{
    ivec3 g = ivec3(gl_GlobalInvocationID);
    if (g.x >= u_size || g.y >= u_size)
        return;
    highp float lo = imageLoad(u_range, ivec3(0, 0, g.z)).r, hi = imageLoad(u_range, ivec3(1, 0, g.z)).r;
    highp float z = imageLoad(u_z, g).r;
    imageStore(u_z, g, vec4(z >= 1.0 ? 1.0 : clamp((z - lo) / (hi - lo), 0.0, 1.0)));
}
#endif
