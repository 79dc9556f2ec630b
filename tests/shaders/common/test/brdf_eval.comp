// Test-only: evaluates the shaders' BRDF (common/brdf.glsl) for a list of cases, so
// tests/gpu/test_brdf_agreement.c can compare it with the path tracer's (app/ref/materials.c).
// Out: rgb = gk_brdf(n, v, l, m), a = gk_brdf_diffuse_gathered(m, n.v).r.
precision highp float;
#include "common/brdf.glsl"
layout(local_size_x = 64) in;
struct Case {
    vec4 n;               // xyz
    vec4 v;               // xyz, unit, towards the eye
    vec4 l;               // xyz, unit, towards the light
    vec4 base_metallic;   // rgb base colour, a metallic
    vec4 c0_weight;       // rgb dielectric F0 colour, a specular weight
    vec4 roughness;       // x
};
layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 result[]; };
uniform int u_count;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count)
        return;
    Case c = cases[i];
    gk_brdf_material m;
    m.base = c.base_metallic.rgb;
    m.metallic = c.base_metallic.a;
    m.roughness = c.roughness.x;
    m.spec_weight = c.c0_weight.a;
    m.c0 = c.c0_weight.rgb;
    result[i] = vec4(gk_brdf(c.n.xyz, c.v.xyz, c.l.xyz, m), gk_brdf_diffuse_gathered(m, dot(c.n.xyz, c.v.xyz)).r);
}
