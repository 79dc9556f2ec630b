// Multi-resolution interpolation (seed 000 Algorithm 3.2, photon-mapping-000-004.md §A.1.8), one
// level, coarse to fine: a texel keeps what the gather rendered for it; otherwise it takes the
// hasData-masked bilinear interpolation of the coarser level (weights 9/16, 3/16, 3/16, 1/16), or
// failing that the masked 3×3 neighbourhood with weight 1/16; no data stays no data (a = 0).
precision highp float;
precision highp int;
uniform highp sampler2D u_rendered;   // this level's gather (a = hasData)
uniform highp sampler2D u_coarse;     // the interpolated coarser level
uniform int u_top;                    // 1: coarsest level, nothing above
layout(location = 0) out vec4 o_s;
void main()
{
    ivec2 q = ivec2(gl_FragCoord.xy);
    vec4 r = texelFetch(u_rendered, q, 0);
    if (r.a > 0.0 || u_top != 0) {
        o_s = r;
        return;
    }
    ivec2 cs = textureSize(u_coarse, 0);
    vec2 f = (vec2(q) + 0.5) * 0.5 - 0.5;
    ivec2 b = ivec2(floor(f));
    vec2 fr = f - vec2(b);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            vec4 c = texelFetch(u_coarse, clamp(b + ivec2(i, j), ivec2(0), cs - 1), 0);
            float w = (i == 0 ? 1.0 - fr.x : fr.x) * (j == 0 ? 1.0 - fr.y : fr.y);
            if (c.a > 0.0 && w > 0.0) {
                sum += w * c.rgb;
                wsum += w;
            }
        }
    if (wsum <= 0.0) {
        ivec2 p = q / 2;
        for (int j = -1; j <= 1; j++)
            for (int i = -1; i <= 1; i++) {
                vec4 c = texelFetch(u_coarse, clamp(p + ivec2(i, j), ivec2(0), cs - 1), 0);
                if (c.a > 0.0) {
                    sum += c.rgb / 16.0;
                    wsum += 1.0 / 16.0;
                }
            }
    }
    o_s = wsum > 0.0 ? vec4(sum / wsum, 1.0) : vec4(0.0);
}
