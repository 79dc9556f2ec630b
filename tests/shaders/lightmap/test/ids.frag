// Texel ids: the chart id (blended with MIN in one pass and MAX in another: a texel two charts
// cover has min != max).
precision highp float;
flat in float v_chart;
in vec2 v_lightmap_uv;
layout(location = 0) out vec4 o_id;
void main()
{
    o_id = vec4(v_chart, 0.0, 0.0, 1.0);
}
