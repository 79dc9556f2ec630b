// Second bounce (not in the thesis, which is one bounce; knob vct_bounces=2, as voxel-based GI
// @variant ISO_MIPS=0 AXIS_WEIGHT_SQ=1 OPACITY_CORRECTION=0 CLIP_CONES=1 CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0
// @variant ISO_MIPS=1 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=1 CLIP_CONES=0 CONSERVATIVE=0 AVERAGE_CAS=1 EMISSIVE=1
// @variant ISO_MIPS=0 ANISO_LEVEL0=1 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0 CLIP_CONES=1 CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0
// @variant ISO_MIPS=0 AXIS_WEIGHT_SQ=1 OPACITY_CORRECTION=0 CLIP_CONES=1 CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 BOUNCE_COUNT_STEPS=1
// renderers do): the indirect light of the first gather injected back into the voxels. Per occupied
// voxel, the trace pass's diffuse cone set from the voxel's mean position along its mean normal,
// through the map of direct light (level 0 + its mips as the trace pass reads them):
//   D    = sum_k w_k L_k   (w_k sum 1: the cosine-weighted mean incident radiance, E_ind / pi)
//   L_o' = L_o + rho D     (= L_o + rho / pi E_ind, the Lambertian voxel's once-bounced light)
// written to a second level-0 texture (this pass samples the first), which then replaces it; the
// mips are rebuilt from it, so the per-pixel gather sees direct + one bounce: two bounces in all.
// A voxel whose fragments' normals cancel (a wall thinner than a voxel, |mean n| < 0.25) has no
// hemisphere to gather over and keeps its direct light (a gather there would leak through the wall).
#include "vct/common.glsl"
#include "vct/cone_lib.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = 1) readonly buffer Scratch { uint s[]; };
#include "vct/voxel_read.glsl"
layout(binding = 0, rgba16f) writeonly uniform highp image3D u_out;
// BOUNCE_COUNT_STEPS: the bench's counting variant (#21, app/gi/vct/vct_work.c), in its untimed
// frame only: the cone samples below lod 1 and from lod 1 on (as trace.comp's counters), and the
// voxels that gathered.
#if defined(BOUNCE_COUNT_STEPS)
layout(std430, binding = 2) buffer BounceSteps { uint fine_steps; uint coarse_steps; uint voxels; } bounce_counted;
#endif

#define MAX_CONES 9
uniform int u_n_cones;
uniform vec3 u_cone_dir[MAX_CONES];      // tangent frame (t, n, b), as the trace pass
uniform float u_cone_aperture[MAX_CONES];
uniform float u_cone_weight[MAX_CONES];
uniform float u_max_dist;                // voxel-space units
uniform float u_apex_offset;             // voxels along the normal

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, ivec3(u_res)))) return;
    vec4 direct = texelFetch(u_vox0, c, 0);
    vec3 alb, nrm, frac, emi;
    if (!vct_voxel_read(c, alb, nrm, frac, emi) || length(nrm) < 0.25) { imageStore(u_out, c, direct); return; }
    vec3 N = normalize(nrm);
    vec3 up = abs(N.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    vec3 pu = (vec3(c) + frac) / u_res_f;              // voxel space [0, 1]^3
    vec3 apex = pu + N * (u_apex_offset / u_res_f);
    vec4 plane = vec4(N, -dot(N, pu));
    vec3 D = vec3(0.0);
    ivec2 total = ivec2(0);
    for (int k = 0; k < MAX_CONES; k++) {
        if (k >= u_n_cones) break;
        vec3 d = normalize(T * u_cone_dir[k].x + N * u_cone_dir[k].y + B * u_cone_dir[k].z);
        float ao; ivec2 steps;
        D += u_cone_weight[k] * trace_cone(apex, d, u_cone_aperture[k], u_max_dist, plane, ao, steps).rgb;
        total += steps;
    }
#if defined(BOUNCE_COUNT_STEPS)
    atomicAdd(bounce_counted.fine_steps, uint(total.x));
    atomicAdd(bounce_counted.coarse_steps, uint(total.y));
    atomicAdd(bounce_counted.voxels, 1u);
#endif
    imageStore(u_out, c, vec4(direct.rgb + alb * D, direct.a));
}
