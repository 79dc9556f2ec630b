// tests/gpu/test_lightmap_gather.c: a surface of constant radiance u_radiance, as the gather's
// tiles hold it (fp32 bits).
precision highp float;
precision highp int;
uniform vec3 u_radiance;
in vec2 v_lightmap_uv;
layout(location = 0) out uvec4 o_radiance;
void main()
{
    o_radiance = uvec4(floatBitsToUint(u_radiance), 0u);
}
