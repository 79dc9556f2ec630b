// Test-only G-buffer: position (RGBA32F, w = window depth: what the method reconstructs from),
// normal facing the viewer (RGBA16F, w = roughness) and albedo (a = metallic) as the renderer's.
precision highp float;
in vec3 v_pos;
in vec3 v_normal;
in vec3 v_albedo;
uniform vec3 u_eye;
layout(location = 0) out vec4 o_pos;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;
layout(location = 3) out vec4 o_specular;   // KHR_materials_specular weight 0: Lambertian
void main()
{
    vec3 n = normalize(v_normal);
    if (dot(n, u_eye - v_pos) < 0.0) n = -n;   // two-sided test geometry
    o_pos = vec4(v_pos, gl_FragCoord.z);
    o_normal = vec4(n, 1.0);                    // w = roughness (renderer layout, gi.h)
    o_albedo = vec4(v_albedo, 0.0);             // a = metallic
    o_specular = vec4(0.0);
}
