// Camera-frustum fragments for the per-pixel lists (seed 000 pass 10) and the depth peels (tier B):
// the scene with the camera's projection at the trace resolution.
precision highp float;
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_viewproj;
out vec3 v_normal;
out vec3 v_world;                       // world position (the shape operator's derivatives)
void main()
{
    v_normal = transpose(inverse(mat3(u_model))) * a_normal;
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    gl_Position = u_viewproj * w;
}
