// ispm's reflective shadow map (seed 000 pass 2): the scene from the light, one perspective frustum
// aimed at the specular geometry (ispm_photons.c frame_light).
precision highp float;
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
#include "common/alpha_mask_vs.glsl"
uniform mat4 u_model;
uniform mat4 u_light_vp;
out vec3 v_world;
out vec3 v_normal;
void main()
{
    gk_alpha_mask_pass();
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = transpose(inverse(mat3(u_model))) * a_normal;
    gl_Position = u_light_vp * w;
}
