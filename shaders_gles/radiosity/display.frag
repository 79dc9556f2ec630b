// Adds the radiosity's indirect light to the HDR image (blended ONE, ONE): the diffuse part of the
// pixel's BRDF for light gathered from many directions times the interpolated irradiance. Only
// where the G-buffer shows this very surface: the mesh is drawn without a depth buffer of its own,
// and a fragment whose world position is not the G-buffer's (a hidden surface, a light proxy drawn
// in front) adds nothing.
// DISPLAY_COUNT_FRAGMENTS: the bench's counting variant (#21, app/gi/radiosity/rad_work.c), one
// atomic add per fragment the mesh rasterizes, before the tests that discard it (fragment-stage
// storage buffers capability-checked by the caller). Never in the kiosk's frames.
// @variant -
// @variant DISPLAY_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#ifdef DISPLAY_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer DisplayFragments { highp uint fragments; } display_counted;
#endif
#include "common/gbuffer.glsl"
in vec3 v_irradiance;
in vec3 v_world;
uniform float u_tolerance;   // relative to the distance from the eye
layout(location = 0) out vec4 o_color;

void main()
{
#ifdef DISPLAY_COUNT_FRAGMENTS
    atomicAdd(display_counted.fragments, 1u);
#endif
    ivec2 px = ivec2(gl_FragCoord.xy);
    float depth = gb_depth(px);
    if (gb_background(depth) || gb_emission(px).a > 0.5)
        discard;
    vec3 x = gb_world_position(px);
    if (distance(x, v_world) > u_tolerance * distance(u_eye, x))
        discard;
    vec3 n = gb_normal(px);
    o_color = vec4(gk_brdf_diffuse_gathered(gb_material(px), dot(n, normalize(u_eye - x))) * v_irradiance, 0.0);
}
