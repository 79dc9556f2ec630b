// One texel of a distance cube-map (lgv/common.glsl): distance from the centre, normal, base colour
// and material code. u_glass = (ior, transmission) per material and u_node_mesh = (node, mesh) per
// draw (render_gi.c's draw_scene sets both when the program declares them); u_refractor_draws: the
// (node, mesh) of each refractor map's glass (lgv_maps.c), so a glass texel names the refractor map
// of the instance drawn. Glass beyond LGV_MAX_REFRACTORS has none and is coded as what it is without
// its transmission (diffuse, or a mirror).
// u_leave_glass = 1: an exit map (lgv_maps.c), which leaves glass out.
// MAPS_COUNT_FRAGMENTS: the bench's counting variant (app/gi/lgv/lgv_work.c), one atomic add per
// fragment shaded, discarded or not (fragment-stage storage buffers capability-checked by the
// caller). Never in the kiosk's frames.
// @variant -
// @variant MAPS_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#ifdef MAPS_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer MapFragments { highp uint fragments; } map_counted;
#endif
in vec3 v_world;
in vec3 v_normal;
uniform vec3 u_centre;
uniform vec4 u_base_color;
uniform vec2 u_metallic_roughness;
uniform vec3 u_emissive;
uniform int u_mat_flags;
#include "common/alpha_mask.glsl"
uniform vec4 u_specular;
uniform vec2 u_glass;
uniform ivec2 u_node_mesh;
uniform int u_n_refractors;
uniform ivec2 u_refractor_draws[4]; // LGV_MAX_REFRACTORS
uniform int u_leave_glass;
layout(location = 0) out highp uint o_dist;
layout(location = 1) out mediump vec4 o_normal;
layout(location = 2) out mediump vec4 o_albedo;
void main()
{
#ifdef MAPS_COUNT_FRAGMENTS
    atomicAdd(map_counted.fragments, 1u);
#endif
    // glTF alphaMode MASK: through a hole the map sees what is behind it
    if (gk_alpha_cut())
        discard;
    if (u_leave_glass == 1 && u_glass.y > 0.0)
        discard;
    o_dist = floatBitsToUint(length(v_world - u_centre));
    vec3 n = normalize(v_normal);
    o_normal = vec4(n * 0.5 + 0.5, 1.0);
    int refractor = -1;
    for (int r = 0; r < u_n_refractors; r++)
        if (u_refractor_draws[r] == u_node_mesh)
            refractor = r;
    float code = 0.0;
    if (u_glass.y > 0.0 && refractor >= 0) {
        float q = clamp(floor((u_glass.x - 1.0) / 0.05 + 0.5), 0.0, 31.0);
        code = 128.0 + 32.0 * float(refractor) + q;
    } else if (u_metallic_roughness.x > 0.5 && u_metallic_roughness.y < 0.2) {
        code = 1.0;
    }
    // u_emissive, u_specular: declared for draw_scene (gi.h), not used here
    o_albedo = vec4(u_base_color.rgb, code / 255.0);
}
