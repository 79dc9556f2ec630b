// Bleeding: samples (bilinear) an atlas that holds every chart's id in its texels and gutters
// (id = r + 256 g) at this fragment's light-map UV and writes how far the lookup is from the
// fragment's own chart id (0 unless another chart's texels leak in).
precision highp float;
uniform highp sampler2D u_ids;
flat in float v_chart;
in vec2 v_lightmap_uv;
layout(location = 0) out vec4 o_err;
void main()
{
    vec4 s = texture(u_ids, v_lightmap_uv);
    o_err = vec4(abs(s.r + 256.0 * s.g - v_chart), 0.0, 0.0, 1.0);
}
