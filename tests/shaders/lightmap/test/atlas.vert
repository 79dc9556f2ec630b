// tests/gpu/test_lightmap_atlas.c: a chart's triangles drawn in atlas space (the viewport is the
// atlas, possibly supersampled), carrying the chart's id.
precision highp float;
layout(location = 0) in vec2 a_lightmap_uv;
layout(location = 1) in float a_chart;
out vec2 v_lightmap_uv;
flat out float v_chart;
void main()
{
    v_lightmap_uv = a_lightmap_uv;
    v_chart = a_chart;
    gl_Position = vec4(a_lightmap_uv * 2.0 - 1.0, 0.0, 1.0);
}
