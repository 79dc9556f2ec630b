// Shadow-map depth: the scene from one light face. UVs and COLOR_0's alpha go to depth.frag for
// alpha-masked materials (attribute locations of app/render/scene_gpu.c).
precision highp float;
layout(location = 0) in vec3 a_position;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_color;
layout(location = 5) in vec2 a_uv1;
uniform mat4 u_model;
uniform mat4 u_viewproj;
out vec2 v_uv;
out vec2 v_uv1;
out float v_alpha;
void main()
{
    v_uv = a_uv;
    v_uv1 = a_uv1;
    v_alpha = a_color.a;
    gl_Position = u_viewproj * (u_model * vec4(a_position, 1.0));
}
