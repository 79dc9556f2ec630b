// Renders the scene into one face of a distance cube-map (lgv_maps.c): a 90-degree perspective
// looking along the face's axis W_f from the map's centre, image axes U_f, V_f (lgv/common.glsl).
precision highp float;
#include "lgv/common.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
#include "common/alpha_mask_vs.glsl"
uniform mat4 u_model;
uniform vec3 u_centre;
uniform int u_face;
uniform vec2 u_near_far;
out vec3 v_world;
out vec3 v_normal;
void main()
{
    gk_alpha_mask_pass();
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_model) * a_normal; // the tracer needs its direction only; scenes scale uniformly
    vec3 p = w.xyz - u_centre;
    float z = dot(p, lgv_face_w(u_face));
    float n = u_near_far.x, f = u_near_far.y;
    gl_Position = vec4(dot(p, lgv_face_u(u_face)), dot(p, lgv_face_v(u_face)), (z * (f + n) - 2.0 * f * n) / (f - n), z);
}
