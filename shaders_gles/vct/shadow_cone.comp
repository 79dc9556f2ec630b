// The soft-shadow cone (thesis §3.3, Fig. 17; summary A.2.6): per G-buffer pixel one cone from the
// surface toward the light through the pre-integrated voxel map, accumulating opacity only;
// visibility = 1 - A, written for the direct pass to multiply in (shadow/mask.glsl).
// @variant ISO_MIPS=0 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0 CLIP_CONES=1 EMPTY_SKIP=1
// @variant ISO_MIPS=1 AXIS_WEIGHT_SQ=1 OPACITY_CORRECTION=1 CLIP_CONES=0 EMPTY_SKIP=0
// @variant ISO_MIPS=0 ANISO_LEVEL0=1 AXIS_WEIGHT_SQ=0 OPACITY_CORRECTION=0 CLIP_CONES=1 EMPTY_SKIP=1
// The cone is cone_lib.glsl's, as the thesis code's shadow shader: step max(diameter, 1 voxel)
// (u_step_mul = 1), ending short of the light (thesis code: at the distance to the light; see
// main) -- a directional light's cone runs to the volume's border, apex offset along the geometric
// normal as the GI cones'. The aperture is the thesis's fixed one (Fig. 17: 9, 6, 3, 0 degrees) or,
// with u_aperture < 0 (not in the thesis), the light's own angular diameter seen from the receiver,
// which is the width a cone needs for the penumbra of an occluder near the receiver to match the
// light's size.
#define GB_GEOM_NORMAL 1
#include "vct/common.glsl"
#include "vct/cone_lib.glsl"
#include "vct/sparse.glsl"   // the G-buffer and vct_world_position
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, r32f) writeonly uniform highp image2D u_out_visibility;
// the layout of trace.comp's Counters, the shadow cones' samples after the trace's three
layout(std430, binding = 2) buffer Counters { uint total_steps; uint fine_steps; uint traced_pixels; uint shadow_steps; } counters;

uniform vec3 u_grid_origin;
uniform float u_grid_size;       // world edge of the cubic grid
uniform float u_apex_offset;     // voxels along the normal
uniform float u_max_dist;        // voxel-space units (directional lights)
uniform int u_light_directional; // 1: a directional light along u_light_dir
uniform vec3 u_light_pos;        // world (local lights)
uniform vec3 u_light_dir;        // emission axis (directional: the direction light travels)
uniform float u_aperture;        // diameter at unit distance; < 0: from u_light_diameter
uniform float u_light_diameter;  // local: the emitter's diameter (m); directional: 2 tan(angular radius)

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, ivec2(u_viewport)))) return;
    float depth = gb_depth(px);
    if (gb_background(depth)) {
        imageStore(u_out_visibility, px, vec4(1.0));
        return;
    }
    vec3 P = vct_world_position(px);
    vec3 Ng = gb_geom_normal(px);
    vec3 pu = (P - u_grid_origin) / u_grid_size;
    vec3 to_light;
    float dist, aperture;
    if (u_light_directional != 0) {
        to_light = -normalize(u_light_dir);
        dist = u_max_dist;
        aperture = u_aperture >= 0.0 ? u_aperture : u_light_diameter;
    } else {
        vec3 lu = (u_light_pos - u_grid_origin) / u_grid_size;
        to_light = lu - pu;
        dist = max(length(to_light), 1e-6);
        to_light /= dist;
        aperture = u_aperture >= 0.0 ? u_aperture : u_light_diameter / (dist * u_grid_size);
    }
    float vis = 1.0;
    ivec2 steps = ivec2(0); // below lod 1, from lod 1 on (trace_cone)
    if (dot(to_light, Ng) > 0.0) {   // a light behind the surface lights nothing: no cone
        vec3 apex = pu + Ng * (u_apex_offset / u_res_f);
        vec4 plane = vec4(Ng, -dot(Ng, pu));   // the receiver's tangent plane (footprint clamp)
        float ao;
        // The cone ends before its samples reach the light's own surroundings (not in the thesis,
        // whose spot light hangs free; a ceiling light's ceiling is in the voxels): a sample of
        // diameter D reads texels up to 1.5 D from its centre (cone_lib.glsl, footprint clamp), so
        // the last one is 1.5 a t short of the light, and at least 2 voxels (the light's plane
        // voxelized conservatively). Measured on cornell at 64^3: ending at the light itself
        // shadowed the whole room in rings, the ceiling's voxels read by the last samples.
        float end = min(dist / (1.0 + 1.5 * aperture), dist - 2.0 / u_res_f);
        vec4 c = trace_cone(apex, to_light, aperture, end, plane, ao, steps);
        vis = clamp(1.0 - c.a, 0.0, 1.0);
    }
    atomicAdd(counters.shadow_steps, uint(steps.x + steps.y));
    imageStore(u_out_visibility, px, vec4(vis));
}
