// G-buffer: RT0 RGBA8 (base colour, metallic), RT1 RGBA16F (world normal facing the viewer,
// roughness), RT2 RGBA16F (emitted radiance in nits, a = 1 for unlit light proxies), RT3 RGBA8
// (KHR_materials_specular: rgb = sqrt(c0), a = weight; sqrt so the usual c0 = 0.04 keeps 8-bit
// precision, 51/255, within 2%); RT4 RGBA16F (the geometric normal: the interpolated vertex normal
// before the normal map, facing the viewer; only with GK_GEOM_NORMAL_TARGET 1, which the renderer
// defines when the driver has 5 draw buffers: an output location past GL_MAX_DRAW_BUFFERS fails to
// link); depth 32F.
// @variant GK_GEOM_NORMAL_TARGET=0
// @variant GK_GEOM_NORMAL_TARGET=1
precision highp float;
in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;
in vec2 v_uv1;
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
uniform vec3 u_eye;
// Each texture slot's UVs (app/scene/scene.h gk_tex_uv): rows of its KHR_texture_transform 2x3
// matrix, and bit k of u_tex_uv1 when slot k reads TEXCOORD_1.
const int SLOT_BASE = 0, SLOT_MR = 1, SLOT_EMISSIVE = 2, SLOT_NORMAL = 3, SLOT_SPECULAR = 4, SLOT_SPECULAR_COLOR = 5,
          SLOT_OCCLUSION = 6;
uniform vec3 u_tex_xf[14];
uniform int u_tex_uv1;

vec2 slot_uv(int slot)
{
    vec3 uv = vec3((u_tex_uv1 & (1 << slot)) != 0 ? v_uv1 : v_uv, 1.0);
    return vec2(dot(u_tex_xf[2 * slot], uv), dot(u_tex_xf[2 * slot + 1], uv));
}
layout(location = 0) out mediump vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_emission;
layout(location = 3) out mediump vec4 o_specular;
#ifndef GK_GEOM_NORMAL_TARGET
#define GK_GEOM_NORMAL_TARGET 0
#endif
#if GK_GEOM_NORMAL_TARGET
layout(location = 4) out vec4 o_geom_normal;
#endif

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
uniform float u_alpha_cutoff;

void main()
{
    // glTF: base colour = factor x texture x vertex colour (COLOR_0).
    vec4 base = u_base_color * v_color;
    if ((u_mat_flags & MAT_BASE_TEX) != 0)
        base *= texture(u_base_tex, slot_uv(SLOT_BASE));
    // glTF alphaMode MASK: below the cutoff the surface is not there (shadow/depth.frag cuts the
    // same holes in the shadow maps, the tracer's any-hit test in its rays).
    if ((u_mat_flags & MAT_ALPHA_MASK) != 0 && base.a < u_alpha_cutoff)
        discard;
    vec3 emissive = u_emissive;
    if ((u_mat_flags & MAT_EMISSIVE_TEX) != 0)
        emissive *= texture(u_emissive_tex, slot_uv(SLOT_EMISSIVE)).rgb;
    vec2 mr = u_metallic_roughness;
    if ((u_mat_flags & MAT_MR_TEX) != 0) {
        vec4 t = texture(u_mr_tex, slot_uv(SLOT_MR));
        mr *= vec2(t.b, t.g);
    }
    vec4 spec = u_specular;
    if ((u_mat_flags & MAT_SPEC_TEX) != 0)
        spec.a *= texture(u_spec_tex, slot_uv(SLOT_SPECULAR)).a;
    if ((u_mat_flags & MAT_SPEC_COLOR_TEX) != 0)
        spec.rgb *= texture(u_spec_color_tex, slot_uv(SLOT_SPECULAR_COLOR)).rgb;
    vec3 n = normalize(v_normal);
    vec3 ng = dot(n, u_eye - v_world) < 0.0 ? -n : n;
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
    bool front = gl_FrontFacing;
    if (dot(n, u_eye - v_world) < 0.0)
        n = -n;
    bool emits = front || (u_mat_flags & MAT_DOUBLE_SIDED) != 0;
    bool proxy = (u_mat_flags & MAT_LIGHT_PROXY) != 0;
    o_albedo = vec4(proxy ? vec3(0.0) : base.rgb, clamp(mr.x, 0.0, 1.0));
    o_normal = vec4(n, clamp(mr.y, 0.0, 1.0));
    // glTF occlusionTexture: ao = 1 + strength (R - 1), for ambient and indirect light only
    float ao = 1.0;
    if ((u_mat_flags & MAT_OCCLUSION_TEX) != 0)
        ao = 1.0 + u_occlusion_strength * (texture(u_occlusion_tex, slot_uv(SLOT_OCCLUSION)).r - 1.0);
    o_emission = vec4(emits ? emissive : vec3(0.0), proxy ? 1.0 : 0.5 * (1.0 - clamp(ao, 0.0, 1.0)));
    o_specular = vec4(sqrt(clamp(spec.rgb, 0.0, 1.0)), clamp(spec.a, 0.0, 1.0));
#if GK_GEOM_NORMAL_TARGET
    o_geom_normal = vec4(ng, 0.0);
#endif
}
