precision highp float;
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_color;   // COLOR_0, constant white without one
layout(location = 4) in vec4 a_tangent; // xyz, handedness w; constant (1, 0, 0, 1) without one
layout(location = 5) in vec2 a_uv1;     // TEXCOORD_1, TEXCOORD_0 again without one
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
uniform mat4 u_viewproj;
out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
out vec2 v_uv1;
out vec4 v_color;
out vec4 v_tangent;
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_normal_matrix) * a_normal;
    v_uv = a_uv;
    v_uv1 = a_uv1;
    v_color = a_color;
    // A tangent lies in the surface: it transforms as a direction (the model matrix), not a normal.
    v_tangent = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w);
    gl_Position = u_viewproj * w;
}
