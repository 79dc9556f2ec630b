// Final shading of the lgv method (seed 002 §4.2-4.3), added to the HDR image: the LGV by eq. (7),
// L = 4 (c_p . y(-n))+ / l^2, c_p read at the centre of the pixel's own cell along the axis nearest
// its normal and trilinear across the other two (own_cell_uvw; or, with u_own_cell off, trilinear at
// the pixel's position moved u_offset cells along its normal, research B.5 item 8), plus the SSLGV's
// caustics, L = 4 (c . y(-n))+ / A(p), A(p) the world area of the SSLGV pixel on the surface
// (research B.2.7's footprint, exact for a square pixel).
// @variant -
// LOOKUP_COUNT_FETCHES: the bench's counting variant (app/gi/lgv/lgv_work.c): per fragment its
// trilinear reads of the three LGV volumes and its reads of the three SSLGV images, added to
// LookupFetches once. Never in the kiosk's frames.
// @variant -
// @variant LOOKUP_COUNT_FETCHES
precision highp float;
#include "common/gbuffer.glsl"
#include "lgv/common.glsl"
in vec2 v_uv;
uniform highp sampler3D u_vol_r;
uniform highp sampler3D u_vol_g;
uniform highp sampler3D u_vol_b;
uniform highp sampler2D u_ss_r;
uniform highp sampler2D u_ss_g;
uniform highp sampler2D u_ss_b;
uniform vec3 u_grid_min;
uniform vec3 u_grid_size;     // dims * cell (m)
uniform float u_cell;
uniform vec2 u_ss_size;       // SSLGV pixels
uniform vec2 u_tan_half;      // tan of the camera's half field of view, x and y
uniform vec3 u_forward;       // camera forward (unit)
uniform int u_parts;          // 1 LGV, 2 SSLGV, 3 both
uniform float u_offset;       // cells along the normal the LGV is read at (0.5; gk_lgv_debug.lookup_offset)
uniform int u_own_cell;       // 1: the surface's own cell along the axis nearest n (gk_lgv_debug.lookup_own_cell)
out vec4 o_color;
#ifdef LOOKUP_COUNT_FETCHES
layout(std430, binding = 6) buffer LookupFetches { highp uint volume; highp uint screen; } lookup_counted;
highp uint g_screen_fetches = 0u;
#endif

// The SSLGV over this pixel's footprint. Finer than the image (lgv_sslgv wider than the view), the
// SSLGV texels the pixel covers, weighted by their overlap (a box filter: every SSLGV texel's
// energy reaches the image, whatever the diffusion left sparse; a bilinear tap would read 2x2 of
// them and skip the rest: the caustic's image energy then varied 6% with C0). Coarser, bilinear.
vec3 ss_sample(ivec2 px, vec4 yn)
{
    vec2 img = vec2(textureSize(u_gb_depth, 0));
    vec2 ratio = u_ss_size / img;
    if (ratio.x <= 1.0 && ratio.y <= 1.0) {
#ifdef LOOKUP_COUNT_FETCHES
        g_screen_fetches += 3u;
#endif
        return vec3(max(dot(texture(u_ss_r, v_uv), yn), 0.0), max(dot(texture(u_ss_g, v_uv), yn), 0.0),
                    max(dot(texture(u_ss_b, v_uv), yn), 0.0));
    }
    vec2 a = vec2(px) * ratio, b = a + ratio; // the footprint in SSLGV texels
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int y = int(floor(a.y)); y < int(ceil(b.y)); y++)
        for (int x = int(floor(a.x)); x < int(ceil(b.x)); x++) {
            vec2 lo = max(a, vec2(x, y)), hi = min(b, vec2(x + 1, y + 1));
            float w = max(hi.x - lo.x, 0.0) * max(hi.y - lo.y, 0.0);
            ivec2 t = min(ivec2(x, y), ivec2(u_ss_size) - 1);
            sum += w * vec3(dot(texelFetch(u_ss_r, t, 0), yn), dot(texelFetch(u_ss_g, t, 0), yn),
                            dot(texelFetch(u_ss_b, t, 0), yn));
            wsum += w;
#ifdef LOOKUP_COUNT_FETCHES
            g_screen_fetches += 3u;
#endif
        }
    return max(sum / max(wsum, 1e-12), vec3(0.0));
}
// Where eq. (7) reads the LGV for a surface at x with normal n: at the centre of the cell x lies in
// along the axis nearest n (the cell its own photons were injected into, trace.comp inject: the
// density estimate f_r sum Phi / l^2 the injection's constant is made for), trilinear across the
// other two. Half a cell along n reads that cell at its centre only for a surface on a cell face; a
// surface f of a cell inside its cell reads 1 - f of its photons and f of the empty cell in front.
vec3 own_cell_uvw(vec3 x, vec3 n)
{
    vec3 g = (x - u_grid_min) / u_cell, dims = u_grid_size / u_cell, a = abs(n);
    int k = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    g[k] = clamp(floor(g[k]), 0.0, dims[k] - 1.0) + 0.5; // a surface at the bounds: the boundary cell (inject's clamp)
    return g / dims;
}
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    float depth = gb_depth(px);
    if (gb_background(depth))
        discard;
    vec3 x = gb_world_at(v_uv, depth);
    vec3 n = normalize(texelFetch(u_gb_normal, px, 0).xyz);
    vec4 yn = lgv_sh(-n);
    vec3 c = vec3(0.0);
    if ((u_parts & 1) != 0) {
        vec3 uvw = (x + u_offset * u_cell * n - u_grid_min) / u_grid_size;
        if (u_own_cell != 0)
            uvw = own_cell_uvw(x, n);
        vec3 e = vec3(max(dot(texture(u_vol_r, uvw), yn), 0.0), max(dot(texture(u_vol_g, uvw), yn), 0.0),
                      max(dot(texture(u_vol_b, uvw), yn), 0.0));
        c += 4.0 * e / (u_cell * u_cell);
#ifdef LOOKUP_COUNT_FETCHES
        atomicAdd(lookup_counted.volume, 3u);
#endif
    }
    if ((u_parts & 2) != 0) {
        vec3 v = u_eye - x;
        float z = dot(-v, u_forward);
        float area = abs((2.0 * u_tan_half.x / u_ss_size.x) * (2.0 * u_tan_half.y / u_ss_size.y) * z * z * z /
                         max(dot(v, n), 1e-6));
        c += 4.0 * ss_sample(px, yn) / max(area, 1e-12);
#ifdef LOOKUP_COUNT_FETCHES
        atomicAdd(lookup_counted.screen, g_screen_fetches);
#endif
    }
    o_color = vec4(c, 1.0);
}
