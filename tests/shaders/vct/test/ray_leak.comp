// Test-only (summary A.6.1 #1 / P.3): 0-degree rays across a thin wall through the real cone loop
// @variant ISO_MIPS=1 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0
// (trace_cone with aperture 0: 1-voxel steps at level 0, trilinear). Counts rays whose accumulated
// opacity stays below 0.5 (leaked) and below 0.05 (fully leaked).
#include "vct/common.glsl"
#include "vct/cone_lib.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 3) buffer Result { uint leaked_half; uint leaked_full; } result;
uniform vec3 u_center;      // voxel space, a point on the wall
uniform vec3 u_normal;      // wall normal
uniform int u_rays;
uniform float u_march;      // voxels marched (centred on the wall)
uint hash(uint x) { x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16; return x; }
float rnd(uint i, uint k) { return float(hash(i * 4u + k) & 0xFFFFFFu) / 16777216.0; }
void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (int(i) >= u_rays) return;
    vec3 n = normalize(u_normal);
    vec3 t = normalize(cross(abs(n.y) < 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0), n));
    vec3 b = cross(n, t);
    // lateral spread over +-8 voxels on the wall; directions within 17 degrees of the normal
    float vs = 1.0 / u_res_f;
    vec3 hit = u_center + (t * (rnd(i, 0u) * 2.0 - 1.0) + b * (rnd(i, 1u) * 2.0 - 1.0)) * 8.0 * vs;
    float ang = radians(17.0) * sqrt(rnd(i, 2u)), az = 6.2831853 * rnd(i, 3u);
    vec3 d = normalize(n * cos(ang) + (t * cos(az) + b * sin(az)) * sin(ang));
    vec3 start = hit - d * (0.5 * u_march * vs);
    float ao; ivec2 steps;
    vec4 c = trace_cone(start, d, 0.0, u_march * vs, vec4(0.0), ao, steps);
    if (c.a < 0.5) atomicAdd(result.leaked_half, 1u);
    if (c.a < 0.05) atomicAdd(result.leaked_full, 1u);
}
