// Final-gather view (app/gi/lightmap/lm_gather.h): the radiance a surface sends towards the
// gathering texel -- diffuse ρ/π times the AIM's full irradiance (the seed's "scene textured with
// the AIMs"), plus the emission the renderer's direct pass does not turn into light (emissive
// meshes; light proxies are 0 here: their area light is direct light) -- as fp32 bits.
// GATHER_COUNT_FRAGMENTS: the bench's counting variant (#21, app/gi/lightmap/lm_work.c): per
// fragment shaded (hidden ones included: with the atomics the depth test runs after the shader) one
// add to the fragments and, where the surface is charted, one to the AIM lookups; fragment-stage
// storage buffers capability-checked by the caller. Never in the kiosk's frames.
// @variant -
// @variant GATHER_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#ifdef GATHER_COUNT_FRAGMENTS
layout(std430, binding = 5) buffer GatherFragments { highp uint fragments, lookups; } gather_counted;
#endif
uniform highp sampler2D u_aim_full;
uniform float u_scale;      // u_aim_full holds E / u_scale
uniform vec3 u_albedo;      // ρ = base colour x (1 - metallic)
uniform vec3 u_emission;
in vec2 v_lightmap_uv;
layout(location = 0) out uvec4 o_radiance;
void main()
{
    vec3 E = v_lightmap_uv.x < 0.0 ? vec3(0.0) : texture(u_aim_full, v_lightmap_uv).rgb * u_scale;
#ifdef GATHER_COUNT_FRAGMENTS
    atomicAdd(gather_counted.fragments, 1u);
    if (v_lightmap_uv.x >= 0.0)
        atomicAdd(gather_counted.lookups, 1u);
#endif
    vec3 L = u_albedo * (1.0 / 3.14159265) * E + u_emission;
    o_radiance = uvec4(floatBitsToUint(L), 0u);
}
