// Counts a caustic photon in its pixel (additive blending into R8: 1/255 a photon, the seed's
// 8-bit pbuffer, at most 255 a pixel: M14; or into R16F: 1 a photon) where the scene does not hide it. The seed draws the
// scene black with depth first; the G-buffer already holds that depth, so a photon is hidden when
// it lies behind the visible surface's plane and farther from the eye (the plane test keeps
// photons lying on that surface itself, which a depth comparison would half lose: M19). A photon
// counted also increments the stencil (the tile culling's "stencil > 0").
// CAUSTIC_COUNT_FRAGMENTS: the bench's counting variant (#21, app/gi/lightmap/lm_work.c), one atomic
// add per point fragment, before the discards (fragment-stage storage buffers capability-checked by
// the caller). Never in the kiosk's frames.
// @variant -
// @variant CAUSTIC_COUNT_FRAGMENTS
precision highp float;
#ifdef CAUSTIC_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer PointFragments { highp uint fragments; } points_counted;
#endif
#include "common/gbuffer.glsl"
uniform float u_count_scale; // what the target holds for n photons: n / u_count_scale
in vec3 v_world;
layout(location = 0) out vec4 o_count;
void main()
{
#ifdef CAUSTIC_COUNT_FRAGMENTS
    atomicAdd(points_counted.fragments, 1u);
#endif
    ivec2 px = ivec2(gl_FragCoord.xy);
    float depth = gb_depth(px);
    if (gb_background(depth))
        discard;
    vec3 x = gb_world_at((vec2(px) + 0.5) / u_viewport, depth);
    vec3 n = gb_normal(px);
    float dist = length(x - u_eye);
    // hidden: behind the visible surface's plane by more than 1/500 of the eye distance (the
    // photon was stored on a surface; float error of both positions is far below that)
    if (dot(v_world - x, n) * sign(dot(u_eye - x, n)) < -0.002 * dist && length(v_world - u_eye) > dist)
        discard;
    o_count = vec4(1.0 / u_count_scale, 0.0, 0.0, 0.0);
}
