// Direct light of ONE light over the G-buffer, added (blend ONE, ONE) into the RGBA16F HDR
// target. Variants: GK_LIGHT_KIND (common/lights.glsl) and the shadow method (shadow/shadow.glsl).
// Validated by tests/e2e/shaders.sh in these variants:
// @variant GK_LIGHT_KIND=0
// @variant GK_LIGHT_KIND=1 GK_LIGHT_SPOT SHADOW_HARD
// @variant GK_LIGHT_KIND=2 SHADOW_PCSS
// @variant GK_LIGHT_KIND=3 SHADOW_PCSS
// @variant GK_LIGHT_KIND=4 GK_LIGHT_SPOT SHADOW_PCSS
// @variant GK_LIGHT_KIND=5 SHADOW_HARD
// @variant GK_LIGHT_KIND=5 GK_LIGHT_SPOT SHADOW_PCSS PCSS_PCF_N=16
// @variant GK_LIGHT_KIND=2 SHADOW_PCSS PCSS_ADAPTIVE=0
// @variant GK_LIGHT_KIND=5 SHADOW_VSSM
// @variant GK_LIGHT_KIND=1 GK_LIGHT_SPOT SHADOW_VSSM VSSM_SUBDIV=0
// @variant GK_LIGHT_KIND=3 SHADOW_VSSM VSSM_RECEIVER_PLANE=0 VSSM_SEARCH_BOUND=0
// @variant GK_LIGHT_KIND=5 SHADOW_CSSM
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM CSSM_SAT=1
// @variant GK_LIGHT_KIND=3 SHADOW_CSSM CSSM_SLOPE=0
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM CSSM_SLOPE_MAX=0.05
// @variant GK_LIGHT_KIND=5 SHADOW_MASK
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM CSSM_PLANE=1
// @variant GK_LIGHT_KIND=5 SHADOW_PCSS SHADOW_COUNT_FETCHES
// @variant GK_LIGHT_KIND=5 SHADOW_VSSM SHADOW_COUNT_FETCHES
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM SHADOW_COUNT_FETCHES
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM CSSM_SAT=1 SHADOW_COUNT_FETCHES
precision highp float;
precision highp int;
#define GB_GEOM_NORMAL 1
#include "common/brdf.glsl"
#include "common/gbuffer.glsl"
#include "common/lights.glsl"
#include "shadow/shadow.glsl"

out vec4 o_color;
#ifdef SHADOW_COUNT_FETCHES
// the bench's count of the shadow lookups' fetches (shadow/common.glsl; fragment-stage storage
// buffers are capability-checked by the renderer before it asks for this variant)
// (app/render/render_work.c reads the five counts in this order)
layout(std430, binding = 6) buffer ShadowFetches {
    highp uint depth, r32f, r32ui, rgba32ui, rgba16f;
} shadow_counted;
#endif

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    gk_surface s = gk_read_surface(px);
    if (s.unlit)
        discard;
    vec3 radiance = gk_light_radiance(s);
    if (max(radiance.r, max(radiance.g, radiance.b)) <= 0.0)
        discard;
    // The receiver offset and plane are the surface's own (the geometric normal): along a normal
    // map's tilted normal the receiver sinks behind its own depth in the map and shadows itself.
    radiance *= shadow_visibility(s.p, gb_geom_normal(px));
#ifdef SHADOW_COUNT_FETCHES
    atomicAdd(shadow_counted.depth, gk_shadow_fetches.depth);
    atomicAdd(shadow_counted.r32f, gk_shadow_fetches.r32f);
    atomicAdd(shadow_counted.r32ui, gk_shadow_fetches.r32ui);
    atomicAdd(shadow_counted.rgba32ui, gk_shadow_fetches.rgba32ui);
    atomicAdd(shadow_counted.rgba16f, gk_shadow_fetches.rgba16f);
#endif
    o_color = vec4(radiance, 1.0);
}
