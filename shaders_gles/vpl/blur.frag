// Geometry-aware blur (thesis §6.5 step 10, after [Laine07]) in two separable passes: Gaussian on
// world distance with σ = 10% of the scene extent, neighbours only where n_p·n_q > α = 0.8. It
// must span the interleave block so every pixel averages all B² VPL subsets.
// BLUR_COUNT_FETCHES: the bench's counting variant (#21, app/gi/vpl/vpl_work.c), one atomic add per
// pixel of the texels it read; fragment-stage storage buffers capability-checked by the caller.
// Never in the kiosk's frames.
// @variant -
// @variant BLUR_COUNT_FETCHES
precision highp float;
precision highp int;
#ifdef BLUR_COUNT_FETCHES
layout(std430, binding = 6) buffer BlurFetches { highp uint texels; } blur_counted;
#define BLUR_COUNT(n) atomicAdd(blur_counted.texels, uint(n))
#else
#define BLUR_COUNT(n)
#endif
uniform highp sampler2D u_ind;
uniform highp sampler2D u_pos;
uniform highp sampler2D u_nrm;
uniform ivec2 u_dir;
uniform int u_radius;
uniform float u_sigma;
uniform float u_alpha;
uniform highp sampler2D u_hist;  // last frame's displayed indirect (crossfade while M changes)
uniform float u_fade;            // 1 = no history
layout(location = 0) out vec4 o_ind;
void main()
{
    ivec2 q = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_ind, 0);
    vec4 pc = texelFetch(u_pos, q, 0);
    if (pc.w <= 0.0) {
        BLUR_COUNT(1);
        o_ind = vec4(0.0);
        return;
    }
    vec3 nc = texelFetch(u_nrm, q, 0).xyz;
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    float inv2s2 = 1.0 / (2.0 * u_sigma * u_sigma);
#ifdef BLUR_COUNT_FETCHES
    uint texels = 2u; // the centre's position and normal
#endif
    for (int k = -u_radius; k <= u_radius; k++) {
        ivec2 o = q + u_dir * k;
        if (o.x < 0 || o.y < 0 || o.x >= size.x || o.y >= size.y)
            continue;
        vec4 p = texelFetch(u_pos, o, 0);
#ifdef BLUR_COUNT_FETCHES
        texels += p.w <= 0.0 ? 1u : 2u; // its position, then its normal where it is a surface
#endif
        if (p.w <= 0.0 || dot(texelFetch(u_nrm, o, 0).xyz, nc) <= u_alpha)
            continue;
        vec3 dp = p.xyz - pc.xyz;
        float w = exp(-dot(dp, dp) * inv2s2);
        sum += w * texelFetch(u_ind, o, 0);
        wsum += w;
#ifdef BLUR_COUNT_FETCHES
        texels += 1u;
#endif
    }
    o_ind = wsum > 0.0 ? sum / wsum : vec4(0.0);
    if (u_fade < 1.0) {
        o_ind = mix(texelFetch(u_hist, q, 0), o_ind, u_fade);
        BLUR_COUNT(1);
    }
    BLUR_COUNT(texels);
}
