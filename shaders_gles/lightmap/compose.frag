// Adds the light-map indirect light to the HDR image (seed 004 eq. (5): purely additive):
// L = diffuse BRDF part * E, E the indirect irradiance of the atlas (bilinear at the pixel's
// light-map UV; each chart's gutter keeps the lookup inside the chart).
// COMPOSE_COUNT_FETCHES: the bench's counting variant (#21, app/gi/lightmap/lm_work.c), one atomic
// add per light-map lookup (fragment-stage storage buffers capability-checked by the caller). Never
// in the kiosk's frames.
// @variant -
// @variant COMPOSE_COUNT_FETCHES
precision highp float;
precision highp int;
#ifdef COMPOSE_COUNT_FETCHES
layout(std430, binding = 6) buffer ComposeFetches { highp uint lookups; } compose_counted;
#endif
uniform highp usampler2D u_lightmap_uv;
uniform highp sampler2D u_irradiance;
uniform float u_scale;     // the atlas holds E / u_scale (fits RGBA16F whatever the scene's units)
#include "common/gbuffer.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    float depth = gb_depth(px);
    if (gb_background(depth))
        discard;
    uvec2 raw = texelFetch(u_lightmap_uv, px, 0).xy;
    if (raw.x == 0xFFFFFFFFu)
        discard;           // nothing of ours drawn here
    vec2 uv = uintBitsToFloat(raw);
    if (uv.x < 0.0)
        discard;           // an uncharted surface (light proxy)
#ifdef COMPOSE_COUNT_FETCHES
    atomicAdd(compose_counted.lookups, 1u);
#endif
    vec3 E = texture(u_irradiance, uv).rgb * u_scale;
    vec3 x = gb_world_at(v_uv, depth);
    vec3 n = gb_normal(px);
    // The BRDF's diffuse part for light gathered from many directions (brdf_spec.md).
    o_color = vec4(gk_brdf_diffuse_gathered(gb_material(px), dot(n, normalize(u_eye - x))) * E, 0.0);
}
