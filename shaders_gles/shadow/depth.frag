// Shadow-map depth: only alpha-masked materials (glTF alphaMode MASK) do anything here: a hole
// (common/alpha_mask.glsl) casts no shadow.
// Compiled with GK_ALPHA_MASK 1 only for scenes that have such a material (gk_scene_gpu_depth_defines):
// elsewhere the shader stays empty, so no draw pays for a discard (it can cost early depth tests).
// @variant GK_ALPHA_MASK=0
// @variant GK_ALPHA_MASK=1
#ifndef GK_ALPHA_MASK
#define GK_ALPHA_MASK 0
#endif
precision highp float;
uniform int u_mat_flags;            // GK_MAT_* in app/render/scene_gpu.h
uniform vec4 u_base_color;
#include "common/alpha_mask.glsl"
void main()
{
#if GK_ALPHA_MASK
    if (gk_alpha_cut())
        discard;
#endif
}
