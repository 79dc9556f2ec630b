// RSM texel for photon emission: the normal facing the light and the specular-mask bit (RGB10_A2:
// a = 1 on specular texels, the mask of pass 2), the specular albedo s and roughness (RGBA8), the
// diffuse albedo d (RGBA8; Russian roulette needs both). Position comes from the depth texture and
// the incident flux I·ΔΩ from the texel's direction (emit.comp), so nothing here needs a float
// target (GLES 3.1 has none without extensions).
// Specular as the scene features define it (app/scene/features.c): metallic > 0.5, roughness < 0.2.
// RSM_COUNT_FRAGMENTS: the bench's counting variant (#21, app/gi/ispm/ispm_work.c), one atomic add
// per fragment before any discard (with the atomic the depth test runs after the shader: hidden
// fragments count too), in the bench's untimed frame only.
// @variant -
// @variant RSM_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#ifdef RSM_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer RsmFragments { highp uint fragments; } rsm_counted;
#endif
#include "ispm/common.glsl"
in vec3 v_world;
in vec3 v_normal;
uniform vec4 u_base_color;
uniform vec2 u_metallic_roughness;
uniform vec4 u_specular;       // rgb ((ior-1)/(ior+1))^2 specularColorFactor, a specularFactor (KHR_materials_specular)
uniform vec3 u_emissive;
uniform int u_mat_flags;
#include "common/alpha_mask.glsl"
uniform mat4 u_model;          // declared for draw_scene (gi.h); used by rsm.vert
uniform vec3 u_light_pos;
layout(location = 0) out vec4 o_nrm;
layout(location = 1) out vec4 o_spec;
layout(location = 2) out vec4 o_diff;

const int MAT_LIGHT_PROXY = 4;

void main()
{
#ifdef RSM_COUNT_FRAGMENTS
    atomicAdd(rsm_counted.fragments, 1u);
#endif
    if ((u_mat_flags & MAT_LIGHT_PROXY) != 0)
        discard;
    // glTF alphaMode MASK: a hole emits no photon, the light passes to what is behind it
    if (gk_alpha_cut())
        discard;
    vec3 n = normalize(v_normal);
    if (dot(n, u_light_pos - v_world) < 0.0)
        n = -n;
    float metallic = clamp(u_metallic_roughness.x, 0.0, 1.0), rough = clamp(u_metallic_roughness.y, 0.0, 1.0);
    bool specular = ispm_is_specular(metallic, rough);
    // the specular albedo (common.glsl); the diffuse share is what the dielectric's Fresnel term
    // leaves, (1 - w max(F0)) of the base colour
    float w = clamp(u_specular.a, 0.0, 1.0);
    vec3 c0 = min(u_specular.rgb, vec3(1.0));
    vec3 s = ispm_specular_albedo(u_base_color.rgb, metallic, u_specular);
    vec3 d = (1.0 - metallic) * (1.0 - w * max(c0.r, max(c0.g, c0.b))) * u_base_color.rgb;
    o_nrm = vec4(n * 0.5 + 0.5, specular ? 1.0 : 0.0);
    o_spec = vec4(s, rough);
    o_diff = vec4(d, 0.0);
}
