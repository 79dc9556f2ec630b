// glTF alphaMode MASK in a pass that draws the scene without its full material (shadow depth, vpl's
// RSMs, lgv's cube maps): where the base colour's alpha (factor x texture x COLOR_0) is below the
// cutoff the surface is not there, as the G-buffer (gbuffer/gbuffer.frag) and the tracer's any-hit
// test see it. The includer declares u_mat_flags (int) and u_base_color (vec4), as for the draw
// (app/render/scene_gpu.h GK_ALPHA_MASK_FIELDS), and its vertex shader writes v_uv, v_uv1 (the
// attributes at locations 2 and 5) and v_alpha (COLOR_0's alpha, location 3).
#include "common/tex_uv.glsl"
in float v_alpha;
uniform mediump sampler2D u_base_tex;
uniform float u_alpha_cutoff;

// true where an alpha-masked material has a hole (GK_MAT_BASE_TEX 1, GK_MAT_ALPHA_MASK 256)
bool gk_alpha_cut()
{
    if ((u_mat_flags & 256) == 0)
        return false;
    float a = u_base_color.a * v_alpha;
    if ((u_mat_flags & 1) != 0)
        a *= texture(u_base_tex, slot_uv(SLOT_BASE)).a;
    return a < u_alpha_cutoff;
}
