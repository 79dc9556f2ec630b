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
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM CSSM_PLANE=1 CSSM_TRIG_ROTATE=0
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM CSSM_PLANE=1 SHADOW_SPLIT=1
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM CSSM_PLANE=1 SHADOW_SPLIT=2
// @variant GK_LIGHT_KIND=5 SHADOW_PCSS SHADOW_COUNT_FETCHES
// @variant GK_LIGHT_KIND=5 SHADOW_VSSM SHADOW_COUNT_FETCHES
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM SHADOW_COUNT_FETCHES
// @variant GK_LIGHT_KIND=2 SHADOW_CSSM CSSM_SAT=1 SHADOW_COUNT_FETCHES
// @variant GK_LIGHT_KIND=5 SHADOW_VSSM SHADOW_SPLIT=1
// @variant GK_LIGHT_KIND=5 SHADOW_VSSM SHADOW_SPLIT=2
// @variant GK_LIGHT_KIND=1 GK_LIGHT_SPOT SHADOW_VSSM VSSM_SUBDIV=0 SHADOW_SPLIT=1 SHADOW_COUNT_FETCHES
// @variant GK_LIGHT_KIND=3 SHADOW_VSSM SHADOW_SPLIT=2 SHADOW_COUNT_FETCHES
precision highp float;
precision highp int;
// SHADOW_SPLIT (app/render/render_split.c): 0 one draw per light; 1, 2 the first and second of a
// splitting shadow method's two draws
#ifndef SHADOW_SPLIT
#define SHADOW_SPLIT 0
#endif
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

#if SHADOW_SPLIT == 2
// the second of a light's two draws (app/render/render_split.c): only the pixels the first left
// (stencil 0); tested before the shader so that a SIMD block of marked pixels runs none of it
layout(early_fragment_tests) in;
#endif

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    gk_surface s = gk_read_surface(px);
#if SHADOW_SPLIT == 1
    // The first of a light's two draws (render_split.c): every pixel not discarded here is marked
    // in the stencil and skipped by the second. Pixels with no light add nothing (alpha 0, as the
    // one-draw pass's discard); those the lookup settles early add radiance x 0 or 1 as
    // shadow_visibility would; the rest are left to the second draw.
    vec3 radiance = s.unlit ? vec3(0.0) : gk_light_radiance(s);
    if (s.unlit || max(radiance.r, max(radiance.g, radiance.b)) <= 0.0) {
        o_color = vec4(0.0);
        return;
    }
    highp float v = shadow_settle(s.p);
    if (v < 0.0)
        discard;
    radiance *= v;
#else
    if (s.unlit)
        discard;
    vec3 radiance = gk_light_radiance(s);
    if (max(radiance.r, max(radiance.g, radiance.b)) <= 0.0)
        discard;
    // The receiver offset and plane are the surface's own (the geometric normal): along a normal
    // map's tilted normal the receiver sinks behind its own depth in the map and shadows itself.
    radiance *= shadow_visibility(s.p, gb_geom_normal(px));
#endif
#ifdef SHADOW_COUNT_FETCHES
    atomicAdd(shadow_counted.depth, gk_shadow_fetches.depth);
    atomicAdd(shadow_counted.r32f, gk_shadow_fetches.r32f);
    atomicAdd(shadow_counted.r32ui, gk_shadow_fetches.r32ui);
    atomicAdd(shadow_counted.rgba32ui, gk_shadow_fetches.rgba32ui);
    atomicAdd(shadow_counted.rgba16f, gk_shadow_fetches.rgba16f);
#endif
    o_color = vec4(radiance, 1.0);
}
