// Cone tracing pass (thesis §3.3) at reduced resolution: per traced pixel the diffuse cone set
// @variant ISO_MIPS=0 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0 SPECULAR=1 CLIP_CONES=0 EMPTY_SKIP=1
// @variant ISO_MIPS=1 AXIS_WEIGHT_SQ=1 OPACITY_CORRECTION=1 SPECULAR=0 CLIP_CONES=1
// @variant ISO_MIPS=0 ANISO_LEVEL0=1 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0 SPECULAR=1 CLIP_CONES=1 EMPTY_SKIP=1
// @variant ISO_MIPS=0 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0 SPECULAR=1 CLIP_CONES=1 EMPTY_SKIP=0 AXIS_CLAMP=2
// @variant ISO_MIPS=1 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0 SPECULAR=0 CLIP_CONES=1 AXIS_CLAMP=1
// @variant ISO_MIPS=0 ANISO_LEVEL0=1 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0 SPECULAR=1 CLIP_CONES=1 AXIS_CLAMP=1
// (4, 6 or 9 cones in the tangent frame, normal = +y as in the thesis code), AO inside the diffuse
// cones, and with SPECULAR one glossy cone along reflect(V, N).
// Output u_out_diffuse: rgb = D = sum_k w_k L_k  (w_k from the C side: calibrated w_k = W_k / pi with
// W_k = cos(theta_k) pi sin^2(alpha_k) rescaled to sum 1, or the thesis code's 1 / 0.607), a = AO =
// clamp(1 - sum_k w_k ao_k, 0, 1).  u_out_spec: rgb = L_spec, the radiance seen by the glossy cone.
#define GB_GEOM_NORMAL 1
#include "vct/common.glsl"
#include "vct/cone_lib.glsl"
#include "vct/sparse.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba16f) writeonly uniform highp image2D u_out_diffuse;
layout(binding = 1, rgba16f) writeonly uniform highp image2D u_out_spec;
// The trace's work (app/gi/vct/vct_work.c): cone samples below lod 1 and from lod 1 on (they differ in
// fetches), and the pixels that traced cones (not background). One atomic add each per pixel.
layout(std430, binding = 2) buffer Counters { uint total_steps; uint fine_steps; uint traced_pixels; } counters;

#define MAX_CONES 9
uniform ivec2 u_low_size;
uniform int u_block;
uniform vec3 u_grid_origin;
uniform float u_grid_size;         // world edge of the cubic grid
uniform int u_n_cones;
uniform vec3 u_cone_dir[MAX_CONES];      // tangent frame (t, n, b)
uniform float u_cone_aperture[MAX_CONES];
uniform float u_cone_weight[MAX_CONES];
uniform float u_max_dist;          // voxel-space units (thesis code: sqrt(3))
uniform float u_apex_offset;       // voxels along the normal (thesis code 2.5, text >= sqrt(3))
uniform float u_spec_aperture;     // thesis code 0.158 (9 degrees)

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(q, u_low_size))) return;
    ivec2 px = sparse_pixel(q, u_block, ivec2(u_viewport));
    if (gb_background(gb_depth(px))) {                                   // background
        imageStore(u_out_diffuse, q, vec4(0.0, 0.0, 0.0, 1.0));
        imageStore(u_out_spec, q, vec4(0.0));
        return;
    }
    vec3 P = vct_world_position(px);
    vec3 N = gb_normal(px);
    vec3 up = abs(N.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    // The apex leaves the surface along its geometric normal and the clip plane is the surface's
    // own: along a normal map's tilted normal the apex stays inside the surface's own voxels and
    // every cone gathers them. The cones themselves are spread around the shading normal N.
    vec3 Ng = gb_geom_normal(px);
    vec3 pu = (P - u_grid_origin) / u_grid_size;      // voxel space
    vec3 apex = pu + Ng * (u_apex_offset / u_res_f);
    vec4 plane = vec4(Ng, -dot(Ng, pu));               // the receiver's tangent plane, voxel space
    vec3 D = vec3(0.0);
    float occ = 0.0;
    ivec2 total = ivec2(0);
    for (int k = 0; k < MAX_CONES; k++) {
        if (k >= u_n_cones) break;
        vec3 d = normalize(T * u_cone_dir[k].x + N * u_cone_dir[k].y + B * u_cone_dir[k].z);
        // Around a normal-mapped N a cone can point below the surface's own plane: that light is
        // blocked by the surface itself (the tracer's BSDF is zero for wi below the geometric
        // normal, app/ref/materials.c), so the cone gathers nothing and counts as occluded.
        if (dot(d, Ng) <= 0.0) {
            occ += u_cone_weight[k];
            continue;
        }
        float ao; ivec2 steps;
        vec4 c = trace_cone(apex, d, u_cone_aperture[k], u_max_dist, plane, ao, steps);
        D += u_cone_weight[k] * c.rgb;
        occ += u_cone_weight[k] * ao;
        total += steps;
    }
    vec4 spec = vec4(0.0);
#if SPECULAR
    vec2 mr = vct_metallic_roughness(px);
    if (mr.g < 0.5 || mr.r > 0.5) {                   // glossy enough to be worth a cone
        vec3 R = reflect(normalize(P - u_eye), N);
        float ao; ivec2 steps;
        spec = trace_cone(apex, R, u_spec_aperture, u_max_dist, plane, ao, steps);
        total += steps;
    }
#endif
    atomicAdd(counters.total_steps, uint(total.x + total.y));
    atomicAdd(counters.fine_steps, uint(total.x));
    atomicAdd(counters.traced_pixels, 1u);
    imageStore(u_out_diffuse, q, vec4(D, clamp(1.0 - occ, 0.0, 1.0)));
    imageStore(u_out_spec, q, vec4(spec.rgb, 1.0));
}
