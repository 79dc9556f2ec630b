// The glTF material at a fragment of a scene mesh (gbuffer.vert's outputs, the uniforms
// gk_scene_gpu_draw sets), read the same way by the G-buffer (gbuffer/gbuffer.frag) and the forward
// pass of alpha-blended surfaces (blend/forward.frag). The includer declares u_eye (the camera).
in vec3 v_world;
in vec3 v_normal;
in vec4 v_color;
in vec4 v_tangent;
uniform vec4 u_base_color;
uniform vec2 u_metallic_roughness;
uniform vec3 u_emissive;
uniform int u_mat_flags;            // GK_MAT_* in app/render/scene_gpu.h
uniform mediump sampler2D u_base_tex;
uniform mediump sampler2D u_mr_tex;
uniform vec4 u_specular;            // rgb ((ior-1)/(ior+1))^2 specularColorFactor, a specularFactor
uniform mediump sampler2D u_spec_tex;
uniform mediump sampler2D u_spec_color_tex;
uniform mediump sampler2D u_emissive_tex;
uniform mediump sampler2D u_normal_tex;
uniform float u_normal_scale;
uniform mediump sampler2D u_occlusion_tex;
uniform float u_occlusion_strength;
#include "common/tex_uv.glsl"
const int MAT_BASE_TEX = 1;
const int MAT_MR_TEX = 2;
const int MAT_LIGHT_PROXY = 4;
const int MAT_DOUBLE_SIDED = 8;
const int MAT_SPEC_TEX = 16;
const int MAT_SPEC_COLOR_TEX = 32;
const int MAT_EMISSIVE_TEX = 64;
const int MAT_NORMAL_TEX = 128;
const int MAT_ALPHA_MASK = 256;
const int MAT_OCCLUSION_TEX = 512;

struct gk_frag_material {
    vec4 base;       // base colour factor x texture x COLOR_0 (a: alpha)
    vec3 emissive;   // nits
    vec2 mr;         // metallic, roughness
    vec4 spec;       // KHR_materials_specular: rgb F0 colour, a weight
    vec3 n;          // shading normal (normal map applied), facing the viewer
    vec3 ng;         // geometric normal (the interpolated vertex normal), facing the viewer
    float ao;        // occlusionTexture: 1 + strength (R - 1); 1 without one
    bool emits;      // front face, or double-sided (emission only from the front otherwise)
};

gk_frag_material gk_eval_material()
{
    gk_frag_material f;
    // glTF: base colour = factor x texture x vertex colour (COLOR_0).
    f.base = u_base_color * v_color;
    if ((u_mat_flags & MAT_BASE_TEX) != 0)
        f.base *= texture(u_base_tex, slot_uv(SLOT_BASE));
    f.emissive = u_emissive;
    if ((u_mat_flags & MAT_EMISSIVE_TEX) != 0)
        f.emissive *= texture(u_emissive_tex, slot_uv(SLOT_EMISSIVE)).rgb;
    f.mr = u_metallic_roughness;
    if ((u_mat_flags & MAT_MR_TEX) != 0) {
        vec4 t = texture(u_mr_tex, slot_uv(SLOT_MR));
        f.mr *= vec2(t.b, t.g);
    }
    f.spec = u_specular;
    if ((u_mat_flags & MAT_SPEC_TEX) != 0)
        f.spec.a *= texture(u_spec_tex, slot_uv(SLOT_SPECULAR)).a;
    if ((u_mat_flags & MAT_SPEC_COLOR_TEX) != 0)
        f.spec.rgb *= texture(u_spec_color_tex, slot_uv(SLOT_SPECULAR_COLOR)).rgb;
    vec3 n = normalize(v_normal);
    f.ng = dot(n, u_eye - v_world) < 0.0 ? -n : n;
    if ((u_mat_flags & MAT_NORMAL_TEX) != 0) {
        // glTF normalTexture: tangent-space normal, XY scaled; B = (N x T) w. The same frame and
        // order of operations as the reference tracer (app/ref/materials.c).
        vec3 m = texture(u_normal_tex, slot_uv(SLOT_NORMAL)).rgb * 2.0 - 1.0;
        m.xy *= u_normal_scale;
        vec3 t = v_tangent.xyz - n * dot(n, v_tangent.xyz);
        if (dot(t, t) > 1e-12) {
            t = normalize(t);
            vec3 b = cross(n, t) * v_tangent.w;
            vec3 nm = t * m.x + b * m.y + n * m.z;
            if (dot(nm, nm) > 1e-12)
                n = normalize(nm);
        }
    }
    // The shading normal faces the viewer (as the path tracer's); emission only from the
    // front face unless the material is double-sided (brdf_spec.md).
    if (dot(n, u_eye - v_world) < 0.0)
        n = -n;
    f.n = n;
    f.emits = gl_FrontFacing || (u_mat_flags & MAT_DOUBLE_SIDED) != 0;
    // glTF occlusionTexture: for ambient and indirect light only
    f.ao = 1.0;
    if ((u_mat_flags & MAT_OCCLUSION_TEX) != 0)
        f.ao = clamp(1.0 + u_occlusion_strength * (texture(u_occlusion_tex, slot_uv(SLOT_OCCLUSION)).r - 1.0), 0.0, 1.0);
    return f;
}
