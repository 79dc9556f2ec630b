// Shadow-map depth: only alpha-masked materials (glTF alphaMode MASK) do anything here: a hole
// (common/alpha_mask.glsl) casts no shadow.
// Compiled with GK_ALPHA_MASK 1 only for scenes that have such a material (gk_scene_gpu_depth_defines):
// elsewhere the shader stays empty, so no draw pays for a discard (it can cost early depth tests).
// DEPTH_COUNT_FRAGMENTS: the bench's counting variant (#21, app/render/render_work.c), one atomic
// add per fragment the draws rasterize, before the alpha mask's discard (with the atomic the depth
// test runs after the shader, so occluded fragments count too); fragment-stage storage buffers
// capability-checked by the caller. Never in the kiosk's frames.
// @variant GK_ALPHA_MASK=0
// @variant GK_ALPHA_MASK=1
// @variant GK_ALPHA_MASK=0 DEPTH_COUNT_FRAGMENTS
// @variant GK_ALPHA_MASK=1 DEPTH_COUNT_FRAGMENTS
#ifndef GK_ALPHA_MASK
#define GK_ALPHA_MASK 0
#endif
precision highp float;
#ifdef DEPTH_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer DepthFragments { highp uint fragments; } depth_counted;
#endif
uniform int u_mat_flags;            // GK_MAT_* in app/render/scene_gpu.h
uniform vec4 u_base_color;
#include "common/alpha_mask.glsl"
void main()
{
#ifdef DEPTH_COUNT_FRAGMENTS
    atomicAdd(depth_counted.fragments, 1u);
#endif
#if GK_ALPHA_MASK
    if (gk_alpha_cut())
        discard;
#endif
}
