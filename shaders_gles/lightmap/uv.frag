// Writes the light-map UV bit-exactly into an RG32UI target (integer targets are colour-renderable
// on the GLES 3.1 floor, float ones are not). Uncharted surfaces (light proxies) write uv < 0.
precision highp float;
precision highp int;
in vec2 v_lightmap_uv;
layout(location = 0) out uvec2 o_uv;
void main()
{
    o_uv = floatBitsToUint(v_lightmap_uv);
}
