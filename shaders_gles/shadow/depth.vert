// Shadow-map depth: the scene from one light face.
precision highp float;
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_viewproj;
void main() { gl_Position = u_viewproj * (u_model * vec4(a_position, 1.0)); }
