// Final-gather view (app/gi/lightmap/lm_gather.h): the radiance a surface sends towards the
// gathering texel -- diffuse ρ/π times the AIM's full irradiance (the seed's "scene textured with
// the AIMs"), plus the emission the renderer's direct pass does not turn into light (emissive
// meshes; light proxies are 0 here: their area light is direct light) -- as fp32 bits.
precision highp float;
precision highp int;
uniform highp sampler2D u_aim_full;
uniform float u_scale;      // u_aim_full holds E / u_scale
uniform vec3 u_albedo;      // ρ = base colour x (1 - metallic)
uniform vec3 u_emission;
in vec2 v_lightmap_uv;
layout(location = 0) out uvec4 o_radiance;
void main()
{
    vec3 E = v_lightmap_uv.x < 0.0 ? vec3(0.0) : texture(u_aim_full, v_lightmap_uv).rgb * u_scale;
    vec3 L = u_albedo * (1.0 / 3.14159265) * E + u_emission;
    o_radiance = uvec4(floatBitsToUint(L), 0u);
}
