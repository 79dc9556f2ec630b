// First write into the HDR target: emitted radiance (nits) of emissive surfaces and light
// proxies; 0 for the background. Lights are then added on top.
precision highp float;
#include "common/gbuffer.glsl"
out vec4 o_color;
void main()
{
    o_color = vec4(gb_emission(ivec2(gl_FragCoord.xy)).rgb, 1.0);
}
