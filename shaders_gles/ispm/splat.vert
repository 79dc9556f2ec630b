// Photon splatting (seed 000 pass 12) as instanced oriented disks: a 4-vertex strip per hit with
// per-instance attributes from the hit buffer (divisor 1), no geometry shader and no point sprites
// (research A.5). The disk lies in the receiver's tangent plane; its radius h (trace.comp) is raised
// to u_h_pixels splat pixels at its distance so every splat covers enough pixels to deposit its
// power (L15). With ispm_radius=footprint (u_footprint) the splat is the ellipse of footprint.comp
// (two axes in the tangent plane and their semi-axes, per instance), each semi-axis raised alike, in
// kernel samples (u_samples per pixel side, splat.frag) rather than pixels.
precision highp float;
layout(location = 0) in vec4 i_pos_valid;
layout(location = 1) in vec4 i_nrm_h;
layout(location = 2) in vec4 i_pow_dist;
layout(location = 3) in vec4 i_axis1;   // u_footprint: (e1, a1)
layout(location = 4) in vec4 i_axis2;   // u_footprint: (e2, a2)
uniform mat4 u_viewproj;
uniform vec3 u_cam;            // camera position
uniform float u_pixel_angle;   // 2·tan(fovy/2) / splat height: a splat pixel's size at unit distance
uniform float u_h_pixels;
uniform int u_footprint;
uniform highp int u_samples;
flat out vec3 v_c;
flat out vec3 v_n;
flat out vec4 v_e1;            // axis / semi-axis, semi-axis
flat out vec4 v_e2;
flat out vec3 v_pow;
void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
    vec3 n = i_nrm_h.xyz;
    float least = u_h_pixels / float(u_samples) * u_pixel_angle * length(i_pos_valid.xyz - u_cam);
    vec3 t = normalize(abs(n.y) < 0.999 ? cross(vec3(0.0, 1.0, 0.0), n) : cross(vec3(1.0, 0.0, 0.0), n));
    vec3 bt = cross(n, t);
    float a1 = max(i_nrm_h.w, least), a2 = a1;
    if (u_footprint == 1)
        t = i_axis1.xyz, bt = i_axis2.xyz, a1 = max(i_axis1.w, least), a2 = max(i_axis2.w, least);
    // with the kernel averaged over each pixel (u_samples > 1) a pixel whose centre lies outside the
    // splat may still overlap it: the quad grows by half a pixel's diagonal (0.75 pixels, on the
    // surface as the camera sees it, the foreshortening clamped at 5x)
    vec3 to_cam = u_cam - i_pos_valid.xyz;
    float grow = u_samples > 1 ? 0.75 * u_pixel_angle * length(to_cam) / max(abs(dot(n, normalize(to_cam))), 0.2) : 0.0;
    vec3 w = i_pos_valid.xyz + corner.x * (a1 + grow) * t + corner.y * (a2 + grow) * bt;
    gl_Position = i_pos_valid.w == 0.0 ? vec4(2.0, 2.0, 2.0, 1.0) : u_viewproj * vec4(w, 1.0);
    v_c = i_pos_valid.xyz;
    v_n = n;
    v_e1 = vec4(t / a1, a1);
    v_e2 = vec4(bt / a2, a2);
    v_pow = i_pow_dist.xyz;
}
