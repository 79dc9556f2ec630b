// First write into the HDR target: emitted radiance (nits) of emissive surfaces and light
// proxies; 0 for the background. Lights are then added on top.
precision highp float;
uniform highp sampler2D u_gb_emission;
out vec4 o_color;
void main()
{
    o_color = vec4(texelFetch(u_gb_emission, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
}
