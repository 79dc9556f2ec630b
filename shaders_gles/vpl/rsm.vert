// Reflective shadow map (thesis §6.5 step 2): the scene seen from the light, one perspective face
// (spot; point/area lights use a cube atlas of faces). Alpha-masked materials' holes: rsm.frag.
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
    // gi.h's draw_scene promises u_model only, so the normal matrix is derived here.
    v_normal = transpose(inverse(mat3(u_model))) * a_normal;
    gl_Position = u_light_vp * w;
}
