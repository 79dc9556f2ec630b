// The scene environment's share of direct light that its area lights do not carry (app/render/
// render_env.h), added (blend ONE, ONE) into the HDR target after the lights:
//   surfaces:   the residual map's irradiance E(n) as order-2 SH (coefficients already convolved
//               with the clamped cosine; scene/env_split.h) times the diffuse BRDF averaged over
//               the hemisphere, unshadowed but times the occlusionTexture's ao (gb_occlusion);
//   background: the map's radiance along the pixel's ray (the lat-long layout of
//               scene/environment.h, nearest pixel: the map is piecewise constant).
precision highp float;
precision highp int;
#include "common/brdf.glsl"
#include "common/gbuffer.glsl"
#include "common/env_sh.glsl"

uniform highp sampler2D u_env_map;
uniform ivec2 u_env_size;

out vec4 o_color;

highp vec3 env_radiance(highp vec3 d)
{
    highp float phi = atan(d.x, -d.z);
    if (phi < 0.0)
        phi += 2.0 * GK_PI;
    highp float u = phi / (2.0 * GK_PI);
    highp float v = acos(clamp(d.y, -1.0, 1.0)) / GK_PI;
    ivec2 texel = clamp(ivec2(vec2(u, v) * vec2(u_env_size)), ivec2(0), u_env_size - 1);
    return texelFetch(u_env_map, texel, 0).rgb;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    highp float depth = gb_depth(px);
    if (gb_background(depth)) {
        // any point along the pixel's ray gives its direction (depth 1 lies at infinity for an
        // infinite far plane)
        highp vec3 p = gb_world_at((vec2(px) + 0.5) / u_viewport, 0.5);
        o_color = vec4(env_radiance(normalize(p - u_eye)), 1.0);
        return;
    }
    gk_surface s = gk_read_surface(px);
    if (s.unlit)
        discard;
    // ambient light: the occlusionTexture darkens it (and only it: the environment's lights are direct)
    highp vec3 e = max(env_irradiance(s.n), vec3(0.0)) * gb_occlusion(px);
    o_color = vec4(gk_brdf_diffuse_gathered(s.m, dot(s.n, s.v)) * e, 1.0);
}
