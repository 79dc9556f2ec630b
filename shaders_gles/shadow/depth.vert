// Shadow-map depth: the scene from one light face. UVs and COLOR_0's alpha go to depth.frag for
// alpha-masked materials (common/alpha_mask_vs.glsl).
precision highp float;
layout(location = 0) in vec3 a_position;
#include "common/alpha_mask_vs.glsl"
uniform mat4 u_model;
uniform mat4 u_viewproj;
void main()
{
    gk_alpha_mask_pass();
    gl_Position = u_viewproj * (u_model * vec4(a_position, 1.0));
}
