// Splat radius from the local photon density (not in the seed; ispm_radius=density, an improvement
// behind a switch). The seed's h = C0 · d · sqrt(ΔΩ / cosθ) (trace.comp) is a plane mirror's
// footprint: a curved mirror focuses or spreads its photons whatever the path length, so the
// focused cusps of a concave ring come out blurred and its spread parts noisy. Here, as photon
// mapping's k nearest photons: the hits are counted in a screen grid of u_cell-pixel cells
// (u_phase 1, after u_phase 0 cleared it), and each hit's disk gets the radius that holds u_k
// photons at the density of the (2·1+1)² cells round it (u_phase 2):
//   h = sqrt(k · A / (π · n)),  A = the window's area on the receiver (its pixel footprint at the
//   hit's distance, over |cosθ_view| ≥ 0.2), n = photons in it (the hit itself included),
// clamped to [u_h_min, u_h_max] like the seed's (L14). Every disk still deposits its Φ (the kernel
// is normalised), so only the blur changes, never the energy.
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
#include "ispm/common.glsl"
layout(std430, binding = 3) buffer Hits { Hit hits[]; };
layout(std430, binding = 4) buffer Grid { uint cells[]; };
uniform int u_phase;            // 0 clear, 1 count, 2 radius
uniform int u_capacity;
uniform ivec2 u_grid;           // cells
uniform float u_cell;           // output pixels per cell side
uniform mat4 u_viewproj;
uniform vec3 u_cam;
uniform float u_pixel_angle;    // an output pixel's size at unit distance
uniform float u_k;
uniform float u_h_min, u_h_max;

ivec2 cell_of(vec3 x)
{
    vec4 c = u_viewproj * vec4(x, 1.0);
    if (c.w <= 0.0)
        return ivec2(-1);
    vec2 p = (c.xy / c.w * 0.5 + 0.5) * vec2(u_grid);
    ivec2 q = ivec2(floor(p));
    return (q.x < 0 || q.y < 0 || q.x >= u_grid.x || q.y >= u_grid.y) ? ivec2(-1) : q;
}

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (u_phase == 0) {
        if (i < u_grid.x * u_grid.y)
            cells[i] = 0u;
        return;
    }
    if (i >= u_capacity || hits[i].pos_valid.w == 0.0)
        return;
    vec3 x = hits[i].pos_valid.xyz;
    ivec2 q = cell_of(x);
    if (q.x < 0)
        return;   // off screen: the seed's radius stays
    if (u_phase == 1) {
        atomicAdd(cells[q.y * u_grid.x + q.x], 1u);
        return;
    }
    uint n = 0u;
    int cells_in = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            ivec2 c = q + ivec2(dx, dy);
            if (c.x < 0 || c.y < 0 || c.x >= u_grid.x || c.y >= u_grid.y)
                continue;
            n += cells[c.y * u_grid.x + c.x];
            cells_in++;
        }
    vec3 to_cam = u_cam - x;
    float dcam = length(to_cam);
    float cos_v = max(abs(dot(hits[i].nrm_h.xyz, to_cam / dcam)), 0.2);
    float side = u_cell * u_pixel_angle * dcam;
    float area = float(cells_in) * side * side / cos_v;
    hits[i].nrm_h.w = clamp(sqrt(u_k * area / (3.14159265 * float(max(n, 1u)))), u_h_min, u_h_max);
}
