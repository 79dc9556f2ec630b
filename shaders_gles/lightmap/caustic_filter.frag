// The seed's caustic filter, eq. (4): c = s sum_{i,j=-k..k} t(x+i, y+j) sqrt(1 + 2k^2 - (i^2+j^2)),
// k = 3 (7x7), over the photon counts t, drawn into the HDR image additively (eq. (5)). The scale s
// the seed leaves open (errata B.7 #7): 1 / (the weights' sum, 156.76) makes c the photon count
// per pixel; times the photon flux and over the pixel's footprint on the visible surface (the
// plane through the pixel's point, cut by the rays through the neighbouring pixel centres) it is
// the irradiance E, which is view-independent (M13); the diffuse BRDF turns it into radiance.
precision highp float;
precision highp int;
uniform highp sampler2D u_count;
uniform vec3 u_photon_flux;  // the mean flux of a caustic photon (one colour: the seed's assumption)
uniform float u_count_scale; // the count target holds n photons as n / u_count_scale (R8: 255, R16F: 1)
#include "common/gbuffer.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

const int K = 3;

// The point where the ray through window point uv meets the plane (p, n).
vec3 on_plane(vec2 uv, vec3 p, vec3 n)
{
    vec3 a = gb_world_at(uv, 0.0), b = gb_world_at(uv, 1.0);
    vec3 d = b - a;
    float dn = dot(d, n);
    float t = abs(dn) > 1e-20 ? dot(p - a, n) / dn : 0.0;
    return a + d * t;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_count, 0);
    float sum = 0.0, wsum = 0.0;
    for (int j = -K; j <= K; j++)
        for (int i = -K; i <= K; i++) {
            float w = sqrt(float(1 + 2 * K * K - (i * i + j * j)));
            wsum += w;
            ivec2 q = px + ivec2(i, j);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            sum += w * floor(texelFetch(u_count, q, 0).r * u_count_scale + 0.5);
        }
    if (sum == 0.0)
        discard;  // no photon within reach: add nothing (bit-identical to adding 0)
    float depth = gb_depth(px);
    if (gb_background(depth))
        discard;
    vec2 c = (vec2(px) + 0.5) / u_viewport;
    vec3 x = gb_world_at(c, depth);
    vec3 n = gb_normal(px);
    vec3 dx = on_plane(c + vec2(1.0, 0.0) / u_viewport, x, n) - x;
    vec3 dy = on_plane(c + vec2(0.0, 1.0) / u_viewport, x, n) - x;
    float area = length(cross(dx, dy));
    if (!(area > 0.0))
        discard;
    vec3 E = (sum / wsum) * u_photon_flux / area;
    o_color = vec4(gk_brdf_diffuse_gathered(gb_material(px), dot(n, normalize(u_eye - x))) * E, 0.0);
}
