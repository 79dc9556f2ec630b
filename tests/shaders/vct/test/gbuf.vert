// Test-only G-buffer: world-space triangles with per-vertex normal and albedo.
precision highp float;
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_albedo;
uniform mat4 u_view_proj;
out vec3 v_pos;
out vec3 v_normal;
out vec3 v_albedo;
void main()
{
    v_pos = a_pos;
    v_normal = a_normal;
    v_albedo = a_albedo;
    gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
