// alphaMode BLEND surfaces, shaded forward over the lit HDR image (app/render/render_blend.c), one
// mesh at a time from back to front, with the opaque G-buffer's depth test:
//   GK_FORWARD_AMBIENT 1: the first draw of a mesh, blended (ONE, ONE_MINUS_SRC_ALPHA):
//       rgb = alpha (emission + the environment's SH ambient x diffuse BRDF x ao), a = alpha,
//       so what lay behind keeps 1 - alpha of itself;
//   GK_LIGHT_KIND k: one draw per light, added (ONE, ONE): alpha x the light's direct radiance,
//       unshadowed (the light's shadow maps hold the surface itself as an opaque caster).
// @variant GK_FORWARD_AMBIENT=1
// @variant GK_LIGHT_KIND=0
// @variant GK_LIGHT_KIND=1 GK_LIGHT_SPOT
// @variant GK_LIGHT_KIND=2
// @variant GK_LIGHT_KIND=3
// @variant GK_LIGHT_KIND=4 GK_LIGHT_SPOT
// @variant GK_LIGHT_KIND=5
// @variant GK_FORWARD_AMBIENT=1 BLEND_COUNT_FRAGMENTS
// @variant GK_LIGHT_KIND=2 BLEND_COUNT_FRAGMENTS
// BLEND_COUNT_FRAGMENTS: the bench's counting variant (#21, app/render/render_work.c), one atomic add
// per fragment rasterized (with the atomic the depth test runs after the shader: fragments behind the
// opaque surfaces count too), in the bench's untimed frame only.
precision highp float;
precision highp int;
#include "common/brdf.glsl"
#include "common/gbuffer.glsl"
#include "common/material.glsl"
#ifndef GK_FORWARD_AMBIENT
#define GK_FORWARD_AMBIENT 0
#endif
#if GK_FORWARD_AMBIENT
#include "common/env_sh.glsl"
#else
#include "common/lights.glsl"
#endif

out vec4 o_color;
#ifdef BLEND_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer BlendFragments { highp uint fragments; } blend_counted;
#endif

void main()
{
#ifdef BLEND_COUNT_FRAGMENTS
    atomicAdd(blend_counted.fragments, 1u);
#endif
    gk_frag_material f = gk_eval_material();
    highp float a = clamp(f.base.a, 0.0, 1.0);
    gk_surface s;
    s.p = v_world;
    s.n = f.n;
    s.v = normalize(u_eye - v_world);
    s.m.base = f.base.rgb;
    s.m.metallic = clamp(f.mr.x, 0.0, 1.0);
    s.m.roughness = clamp(f.mr.y, 0.0, 1.0);
    s.m.spec_weight = clamp(f.spec.a, 0.0, 1.0);
    s.m.c0 = clamp(f.spec.rgb, 0.0, 1.0);
    s.unlit = false;
#if GK_FORWARD_AMBIENT
    highp vec3 e = max(env_irradiance(s.n), vec3(0.0)) * f.ao;
    highp vec3 lit = gk_brdf_diffuse_gathered(s.m, dot(s.n, s.v)) * e + (f.emits ? f.emissive : vec3(0.0));
    o_color = vec4(a * lit, a);
#else
    o_color = vec4(a * gk_light_radiance(s), 0.0);
#endif
}
