// Photon splatting (seed 000 pass 12) as instanced oriented disks: a 4-vertex strip per hit with
// per-instance attributes from the hit buffer (divisor 1), no geometry shader and no point sprites
// (research A.5). The disk lies in the receiver's tangent plane; its radius h (trace.comp) is raised
// to u_h_pixels splat pixels at its distance so every splat covers enough pixels to deposit its
// power (L15).
precision highp float;
layout(location = 0) in vec4 i_pos_valid;
layout(location = 1) in vec4 i_nrm_h;
layout(location = 2) in vec4 i_pow_dist;
uniform mat4 u_viewproj;
uniform vec3 u_cam;            // camera position
uniform float u_pixel_angle;   // 2·tan(fovy/2) / splat height: a splat pixel's size at unit distance
uniform float u_h_pixels;
flat out vec3 v_c;
flat out vec3 v_n;
flat out float v_h;
flat out vec3 v_pow;
void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
    vec3 n = i_nrm_h.xyz;
    float h = max(i_nrm_h.w, u_h_pixels * u_pixel_angle * length(i_pos_valid.xyz - u_cam));
    vec3 t = normalize(abs(n.y) < 0.999 ? cross(vec3(0.0, 1.0, 0.0), n) : cross(vec3(1.0, 0.0, 0.0), n));
    vec3 bt = cross(n, t);
    vec3 w = i_pos_valid.xyz + h * (corner.x * t + corner.y * bt);
    gl_Position = i_pos_valid.w == 0.0 ? vec4(2.0, 2.0, 2.0, 1.0) : u_viewproj * vec4(w, 1.0);
    v_c = i_pos_valid.xyz;
    v_n = n;
    v_h = h;
    v_pow = i_pow_dist.xyz;
}
