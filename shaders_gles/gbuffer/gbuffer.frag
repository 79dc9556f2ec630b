// G-buffer: RT0 RGBA8 (base colour, metallic), RT1 RGBA16F (world normal facing the viewer,
// roughness), RT2 RGBA16F (emitted radiance in nits, a = 1 for unlit light proxies, else the
// occlusionTexture's (1 - ao) / 2, in [0, 0.5]: common/gbuffer.glsl gb_occlusion), RT3 RGBA8
// (KHR_materials_specular: rgb = sqrt(c0), a = weight; sqrt so the usual c0 = 0.04 keeps 8-bit
// precision, 51/255, within 2%); RT4 RGBA16F (the geometric normal: the interpolated vertex normal
// before the normal map, facing the viewer; only with GK_GEOM_NORMAL_TARGET 1, which the renderer
// defines when the driver has 5 draw buffers: an output location past GL_MAX_DRAW_BUFFERS fails to
// link); depth 32F. The material itself: common/material.glsl.
// GBUFFER_COUNT_FRAGMENTS: the bench's counting variant (#21, app/render/render_work.c), one atomic
// add per fragment the draws rasterize (before the alpha mask's discard; with the atomic the depth
// test runs after the shader, so occluded fragments count too); fragment-stage storage buffers
// capability-checked by the caller. Never in the kiosk's frames.
// @variant GK_GEOM_NORMAL_TARGET=0
// @variant GK_GEOM_NORMAL_TARGET=1
// @variant GK_GEOM_NORMAL_TARGET=1 GBUFFER_COUNT_FRAGMENTS
precision highp float;
#ifdef GBUFFER_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer GBufferFragments { highp uint fragments; } gbuffer_counted;
#endif
uniform vec3 u_eye;
#include "common/material.glsl"
layout(location = 0) out mediump vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_emission;
layout(location = 3) out mediump vec4 o_specular;
#ifndef GK_GEOM_NORMAL_TARGET
#define GK_GEOM_NORMAL_TARGET 0
#endif
#if GK_GEOM_NORMAL_TARGET
layout(location = 4) out vec4 o_geom_normal;
#endif

uniform float u_alpha_cutoff;

void main()
{
#ifdef GBUFFER_COUNT_FRAGMENTS
    atomicAdd(gbuffer_counted.fragments, 1u);
#endif
    gk_frag_material f = gk_eval_material();
    // glTF alphaMode MASK: below the cutoff the surface is not there (shadow/depth.frag cuts the
    // same holes in the shadow maps, the tracer's any-hit test in its rays).
    if ((u_mat_flags & MAT_ALPHA_MASK) != 0 && f.base.a < u_alpha_cutoff)
        discard;
    bool proxy = (u_mat_flags & MAT_LIGHT_PROXY) != 0;
    o_albedo = vec4(proxy ? vec3(0.0) : f.base.rgb, clamp(f.mr.x, 0.0, 1.0));
    o_normal = vec4(f.n, clamp(f.mr.y, 0.0, 1.0));
    o_emission = vec4(f.emits ? f.emissive : vec3(0.0), proxy ? 1.0 : 0.5 * (1.0 - f.ao));
    o_specular = vec4(sqrt(clamp(f.spec.rgb, 0.0, 1.0)), clamp(f.spec.a, 0.0, 1.0));
#if GK_GEOM_NORMAL_TARGET
    o_geom_normal = vec4(f.ng, 0.0);
#endif
}
