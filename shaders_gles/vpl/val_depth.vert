// Paraboloid depth map of one VAL (or one VPL in the exact-visibility reference), [Brabec02]:
// ℓ = local unit direction around the cluster frame, uv = ½ + ½·ℓ.xy/(1 + ℓ.z). The projection is
// per-vertex non-linear, so it is drawn on the method's own tessellated copy of the scene.
precision highp float;
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform vec3 u_c, u_t, u_b, u_n;
uniform float u_far;
out vec3 v_world;
void main()
{
    vec3 w = (u_model * vec4(a_position, 1.0)).xyz;
    v_world = w;
    vec3 v = w - u_c;
    float r = max(length(v), 1e-6);
    vec3 l = vec3(dot(v, u_t), dot(v, u_b), dot(v, u_n)) / r;
    gl_Position = vec4(l.xy / max(1.0 + l.z, 1e-3), r / u_far * 2.0 - 1.0, 1.0);
}
