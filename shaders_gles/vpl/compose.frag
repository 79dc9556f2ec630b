// Adds the indirect light to the HDR image: L = ρ_d/π · E, E joint-bilaterally upsampled from the
// indirect resolution (the 2×2 nearest low-res samples, weighted by bilinear weight × normal and
// position agreement). The crossfade while M changes happens in the blur's second pass.
// VPL_COMPOSE_COUNT_FETCHES: the bench's counting variant (#21, app/gi/vpl/vpl_work.c), one atomic
// add per shaded pixel of the upsample's texels (its G-buffer reads not counted); fragment-stage
// storage buffers capability-checked by the caller. Never in the kiosk's frames.
// @variant -
// @variant VPL_COMPOSE_COUNT_FETCHES
precision highp float;
precision highp int;
#ifdef VPL_COMPOSE_COUNT_FETCHES
layout(std430, binding = 6) buffer ComposeFetches { highp uint texels; } compose_counted;
uint compose_texels = 0u;
#endif
uniform highp sampler2D u_ind;
uniform highp sampler2D u_pos;
uniform highp sampler2D u_nrm;
#include "common/gbuffer.glsl"
uniform float u_sigma;
uniform vec3 u_origin;   // u_pos holds positions relative to the bounds centre (gather.frag)
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

vec3 upsample(highp sampler2D tex, vec3 x, vec3 n)
{
    ivec2 size = textureSize(tex, 0);
    vec2 f = v_uv * vec2(size) - 0.5;
    ivec2 b = ivec2(floor(f));
    vec2 fr = f - vec2(b);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            ivec2 o = clamp(b + ivec2(i, j), ivec2(0), size - 1);
            vec4 p = texelFetch(u_pos, o, 0);
#ifdef VPL_COMPOSE_COUNT_FETCHES
            compose_texels += p.w <= 0.0 ? 1u : 3u; // its position, then its normal and irradiance
#endif
            if (p.w <= 0.0)
                continue;
            float wb = (i == 0 ? 1.0 - fr.x : fr.x) * (j == 0 ? 1.0 - fr.y : fr.y) + 1e-3;
            float wn = max(dot(texelFetch(u_nrm, o, 0).xyz, n), 0.0);
            vec3 dp = p.xyz - x;
            float w = wb * wn * wn * exp(-dot(dp, dp) / (2.0 * u_sigma * u_sigma));
            sum += w * texelFetch(tex, o, 0).rgb;
            wsum += w;
        }
    return wsum > 0.0 ? sum / wsum : vec3(0.0);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    float depth = gb_depth(px);
    if (gb_background(depth))
        discard;
    vec3 x = gb_world_at(v_uv, depth);
    vec3 n = gb_normal(px);
    vec3 E = upsample(u_ind, x - u_origin, n);
#ifdef VPL_COMPOSE_COUNT_FETCHES
    atomicAdd(compose_counted.texels, compose_texels);
#endif
    // The BRDF's diffuse part for light gathered from many directions (brdf_spec.md).
    o_color = vec4(gk_brdf_diffuse_gathered(gb_material(px), dot(n, normalize(u_eye - x))) * E, 0.0);
}
