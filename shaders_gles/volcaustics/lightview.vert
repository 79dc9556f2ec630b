// volcaustics passes 1a/1b (research dong-001.md §6.3): the scene from the light, one perspective
// frustum fitted to the specular objects (vc_light.c).
precision highp float;
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_light_vp;
out vec3 v_world;
out vec3 v_normal;
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = transpose(inverse(mat3(u_model))) * a_normal;
    gl_Position = u_light_vp * w;
}
