// Each texture slot's UVs (app/scene/scene.h gk_tex_uv): rows of its KHR_texture_transform 2x3
// matrix, and bit k of u_tex_uv1 when slot k reads TEXCOORD_1. Shared by the full material
// (common/material.glsl) and the passes that only test alphaMode MASK (common/alpha_mask.glsl), so
// a cut-out is read through the same transform and set everywhere.
in vec2 v_uv;
in vec2 v_uv1;
const int SLOT_BASE = 0, SLOT_MR = 1, SLOT_EMISSIVE = 2, SLOT_NORMAL = 3, SLOT_SPECULAR = 4, SLOT_SPECULAR_COLOR = 5,
          SLOT_OCCLUSION = 6;
uniform vec3 u_tex_xf[14];
uniform int u_tex_uv1;

vec2 slot_uv(int slot)
{
    vec3 uv = vec3((u_tex_uv1 & (1 << slot)) != 0 ? v_uv1 : v_uv, 1.0);
    return vec2(dot(u_tex_xf[2 * slot], uv), dot(u_tex_xf[2 * slot + 1], uv));
}
