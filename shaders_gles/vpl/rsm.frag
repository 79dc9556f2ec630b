// RSM texel: world position (+ the surface area the texel covers), normal facing the light, and
// the reflected flux Φ = ρ_d · I(ω) · ΔΩ_texel (ρ_d = π × the BRDF's diffuse part reflected to the
// whole hemisphere, (1 − metallic)(1 − w max(Fd))·base with Fd's Schlick weight averaged as
// brdf.glsl's gk_brdf_diffuse_gathered at μ = n·l, brdf_spec.md; textures are not sampled here but
// for alphaMode MASK's holes, common/alpha_mask.glsl).
// ΔΩ_texel = (2 tanΘ / R)² / (1 + u² + v²)^{3/2} for a perspective face (photon-mapping §A.1.3).
// RSM_COUNT_FRAGMENTS: the bench's counting variant (#21, app/gi/vpl/vpl_work.c), one atomic add
// per fragment before any discard (with the atomic the depth test runs after the shader: hidden
// fragments count too), in the bench's untimed frame only.
// @variant -
// @variant RSM_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#ifdef RSM_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer RsmFragments { highp uint fragments; } rsm_counted;
#endif
in vec3 v_world;
in vec3 v_normal;
uniform vec4 u_base_color;
uniform vec2 u_metallic_roughness;
uniform vec4 u_specular;       // rgb ((ior-1)/(ior+1))^2 specularColorFactor, a specularFactor
uniform vec3 u_emissive;
uniform int u_mat_flags;
#include "common/alpha_mask.glsl"
uniform vec3 u_light_pos;
uniform vec3 u_light_dir;      // emission axis
uniform vec3 u_radiant;        // colour · intensity (cd)
uniform int u_light_kind;      // 0 spot, 1 point (uniform), 2 one-sided Lambertian (rect area),
                               // 3 directional (orthographic face; u_radiant = colour · illuminance, lux)
uniform float u_cos_inner, u_cos_outer;
uniform vec2 u_face_origin;    // pixel origin of this face in the atlas
uniform float u_face_res;
uniform float u_tan_half;      // perspective: tan of the half field of view; orthographic: half width (m)
uniform vec3 u_origin;         // bounds centre
uniform vec3 u_code;           // scales of position, area, flux (fp16-safe code, vpl_rsm.c rsm_code)
layout(location = 0) out vec4 o_pos;   // xyz, a = area covered by this texel (m²), encoded
layout(location = 1) out vec4 o_nrm;
layout(location = 2) out vec4 o_flux;  // rgb reflected flux of this texel (W), encoded

const int MAT_LIGHT_PROXY = 4;

void main()
{
#ifdef RSM_COUNT_FRAGMENTS
    atomicAdd(rsm_counted.fragments, 1u);
#endif
    // A light proxy stands where the light is: the path tracer does not see it, neither do we.
    if ((u_mat_flags & MAT_LIGHT_PROXY) != 0 || dot(u_emissive, vec3(1.0)) > 0.0)
        discard;
    // glTF alphaMode MASK: a hole reflects nothing and lets the light through to what is behind it
    if (gk_alpha_cut())
        discard;
    vec3 L = u_light_pos - v_world;
    float d2 = max(dot(L, L), 1e-8);
    vec3 l = L * inversesqrt(d2);
    if (u_light_kind == 3) { l = -u_light_dir; d2 = 1.0; }
    vec3 n = normalize(v_normal);
    if (dot(n, l) < 0.0)
        n = -n;
    vec2 ndc = (gl_FragCoord.xy - u_face_origin) / u_face_res * 2.0 - 1.0;
    vec2 uv = ndc * u_tan_half;
    float texel = 2.0 * u_tan_half / u_face_res;
    // orthographic: "d2 dOmega" is the texel's area across the beam, texel^2 (m^2), and the flux
    // rho E texel^2 (E: illuminance across the beam); the same code then serves both
    float dOmega = u_light_kind == 3 ? texel * texel : texel * texel / pow(1.0 + dot(uv, uv), 1.5);
    float c = dot(-l, u_light_dir);
    float I = 1.0;
    if (u_light_kind == 0) {
        float t = clamp((c - u_cos_outer) / max(u_cos_inner - u_cos_outer, 1e-4), 0.0, 1.0);
        I = t * t;
    } else if (u_light_kind == 2) {
        I = max(c, 0.0);
    }
    float cos_y = max(dot(n, l), 0.05);
    vec3 c0 = min(u_specular.rgb, vec3(1.0));
    float c0_max = max(c0.r, max(c0.g, c0.b));
    float fd = c0_max + (1.0 - c0_max) * 0.028 * pow(1.0 - clamp(dot(n, l), 0.0, 1.0), 2.6);
    vec3 rho = (1.0 - clamp(u_metallic_roughness.x, 0.0, 1.0)) * (1.0 - clamp(u_specular.a, 0.0, 1.0) * fd) *
               u_base_color.rgb;
    o_pos = vec4((v_world - u_origin) * u_code.x, d2 * dOmega / cos_y * u_code.y);
    o_nrm = vec4(n, 0.0);
    o_flux = vec4(rho * u_radiant * (I * dOmega * u_code.z), 1.0);
}
