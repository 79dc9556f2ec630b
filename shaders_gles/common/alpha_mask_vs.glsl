// The vertex half of common/alpha_mask.glsl: what its test reads, passed on from the mesh's
// attributes (locations of app/render/scene_gpu.h: 2 uv, 3 COLOR_0, 5 TEXCOORD_1). Call
// gk_alpha_mask_pass() in main.
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_color;
layout(location = 5) in vec2 a_uv1;
out vec2 v_uv;
out vec2 v_uv1;
out float v_alpha;

void gk_alpha_mask_pass()
{
    v_uv = a_uv;
    v_uv1 = a_uv1;
    v_alpha = a_color.a;
}
