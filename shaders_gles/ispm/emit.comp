// Photon selection and reflection (seed 000 passes 8 and 9, photon-mapping-000-004.md A.1.9).
// One invocation per block of the chosen mask level l. Level choice:
//   faithful (u_faithful = 1): l = the smallest level with M / 4^l <= N (M specular texels, N the
//     photon budget), one photon per block whose count is 4^l (the seed's "texel = 1" rule);
//   default: the smallest level whose blocks holding any specular texel number <= N, one photon per
//     such block. Partially covered blocks are what thin reflectors consist of at coarse levels;
//     dropping them loses energy when l changes (research L12).
// Either way a photon carries the incident flux of its whole block, Σ I·ΔΩ over the block's
// specular texels (L12: the caustic's energy stays continuous when the count jumps ×4), and starts
// at the block's specular texel nearest the block centre (a texel of the surface, not a mip average).
// Russian roulette picks diffuse (dropped: vpl's part), specular (traced, Φ·s/P_s) or absorbed; the
// direction is the Phong lobe about the mirror direction with the corrected sampling
// θ = arccos(ξ^{1/(α+1)}) (errata A.7 item 1), frame of Algorithm 3.3; below-surface samples are
// absorbed. A photon's slot comes from an atomic counter (compaction); its random numbers are keyed
// by its RSM block (A.7 item 14), or by its slot in the faithful "list index" mode (L13).
// PHOTONS_COUNT_FETCHES: the bench's counting variant (#21, app/gi/ispm/ispm_work.c), as mask.comp's:
// per block its count's load, the RSM normal texels its loop reads, its photon's 3 RSM texels and
// depth texel, and its atomics (the slot, an overflow, a reflection), added to binding 6. The level
// choice's reads of the header, the same in every invocation, are not counted. Never in the kiosk's
// frames.
// @variant -
// @variant PHOTONS_COUNT_FETCHES
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
#include "ispm/common.glsl"
#ifdef PHOTONS_COUNT_FETCHES
layout(std430, binding = 6) buffer PhotonsFetches { highp uint texels, depths, loads, atomics; } photons_counted;
#define PHOTONS_COUNT(field, n) atomicAdd(photons_counted.field, uint(n))
#else
#define PHOTONS_COUNT(field, n)
#endif
layout(std430, binding = 0) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 2) buffer Photons { ISPM_PHOTON_HEADER Photon ph[]; };
uniform highp sampler2D u_rsm_depth;
uniform highp sampler2D u_rsm_nrm;
uniform highp sampler2D u_rsm_spec;
uniform highp sampler2D u_rsm_diff;
uniform int u_res;             // RSM resolution (power of two)
uniform int u_top;             // index of its 1x1 level
uniform int u_budget;          // N
uniform int u_capacity;        // photon slots
uniform int u_faithful;        // 1: full blocks and the l = ceil(log4(M/N)) rule
uniform int u_rng_by_slot;     // 1: random numbers by compacted index (the faithful reading, L13)
uniform uint u_shuffle_mul;    // odd: block order permutation (emulates a GPU's compaction order)
uniform uint u_shuffle_add;
uniform mat4 u_light_inv_vp;   // RSM clip -> world
uniform mat3 u_light_rot;      // RSM view -> world (columns: right, up, back)
uniform vec3 u_light_pos;
uniform vec3 u_light_axis;     // spot axis (world)
uniform vec3 u_radiant;        // colour · intensity (cd)
uniform int u_spot;            // 1: spot cone profile
uniform vec2 u_cone;           // cos(outer), cos(inner)
uniform float u_tan_half;      // tan of the RSM's half field of view

int level_offset(int l)
{
    int off = 0;
    for (int k = 0; k < l; k++)
        off += (u_res >> k) * (u_res >> k);
    return off;
}

int choose_level()
{
    uint n = uint(u_budget);
    if (u_faithful == 1) {
        uint m = ph_top;
        for (int l = 0; l < u_top; l++)
            if ((m >> (2 * l)) + ((m & ((1u << (2 * l)) - 1u)) != 0u ? 1u : 0u) <= n)
                return l;
        return u_top;
    }
    for (int l = 0; l < u_top; l++)
        if (ph_nonzero[l] <= n)
            return l;
    return u_top;
}

// I(ω)·ΔΩ of RSM texel t: ΔΩ = (2 tanΘ / R)² / (1 + u² + v²)^{3/2} (research A.1.3)
vec3 incident_flux(ivec2 t)
{
    vec2 uv = ((vec2(t) + 0.5) / float(u_res) * 2.0 - 1.0) * u_tan_half;
    float texel = 2.0 * u_tan_half / float(u_res);
    float dOmega = texel * texel / pow(1.0 + dot(uv, uv), 1.5);
    float I = 1.0;
    if (u_spot == 1) {
        vec3 w = normalize(u_light_rot * vec3(uv, -1.0));
        float t2 = clamp((dot(w, u_light_axis) - u_cone.x) / max(u_cone.y - u_cone.x, 1e-4), 0.0, 1.0);
        I = t2 * t2;
    }
    return u_radiant * (I * dOmega);
}

void main()
{
    int l = choose_level();
    if (gl_GlobalInvocationID.x == 0u)
        ph_level = uint(l);
    int rl = u_res >> l;
    uint blocks = uint(rl * rl);
    uint i = gl_GlobalInvocationID.x;
    if (i >= blocks)
        return;
    uint b = (i * u_shuffle_mul + u_shuffle_add) & (blocks - 1u);   // a bijection: blocks is 4^k
    uint c = counts[level_offset(l) + int(b)];
    PHOTONS_COUNT(loads, 1);
    uint full = 1u << (2 * l);
    if (c == 0u || (u_faithful == 1 && c != full))
        return;
    int side = 1 << l;
    ivec2 base = ivec2(int(b) % rl, int(b) / rl) * side;
    vec3 flux = vec3(0.0);
    ivec2 rep = base;
    float best = 1e30;
    vec2 centre = vec2(base) + 0.5 * float(side) - 0.5;
    for (int y = 0; y < side; y++)
        for (int x = 0; x < side; x++) {
            ivec2 t = base + ivec2(x, y);
            if (texelFetch(u_rsm_nrm, t, 0).a < 0.5)
                continue;
            flux += incident_flux(t);
            vec2 dc = vec2(t) - centre;
            float d2 = dot(dc, dc);
            if (d2 < best)
                best = d2, rep = t;
        }
    PHOTONS_COUNT(texels, side * side);
    uint slot = atomicAdd(ph_count, 1u);
    PHOTONS_COUNT(atomics, 1);
    if (slot >= uint(u_capacity)) {
        atomicAdd(ph_overflow, 1u);
        PHOTONS_COUNT(atomics, 1);
        return;
    }
    PHOTONS_COUNT(texels, 3);   // the representative's normal, specular and diffuse texels
    PHOTONS_COUNT(depths, 1);
    float depth = texelFetch(u_rsm_depth, rep, 0).r;
    vec4 wp = u_light_inv_vp * vec4((vec2(rep) + 0.5) / float(u_res) * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 x = wp.xyz / wp.w;
    vec3 n = normalize(texelFetch(u_rsm_nrm, rep, 0).xyz * 2.0 - 1.0);
    vec4 sr = texelFetch(u_rsm_spec, rep, 0);
    vec3 s = sr.rgb, d = texelFetch(u_rsm_diff, rep, 0).rgb;
    float rough = sr.a;
    uint key = u_rng_by_slot == 1 ? slot : uint(level_offset(l)) + b;
    ph[slot].org = vec4(x, 0.0);
    // Russian roulette (A.1.9)
    vec3 ds = d + s;
    float pr = max(ds.r, max(ds.g, ds.b));
    float sum = ds.r + ds.g + ds.b;
    float pd = sum > 0.0 ? (d.r + d.g + d.b) / sum * pr : 0.0;
    float ps = pr - pd;
    float xi = ispm_random(key, 0u);
    if (xi <= pd || xi > pd + ps || ps <= 0.0)
        return;   // diffuse (vpl's part) or absorbed
    vec3 win = normalize(x - u_light_pos);
    vec3 rm = reflect(win, n);
    vec3 r = ispm_phong_lobe(rm, rough, key, 1u);
    if (dot(r, n) <= 0.0)
        return;   // below the surface: absorbed
    atomicAdd(ph_reflected, 1u);
    PHOTONS_COUNT(atomics, 1);
    ph[slot].org.w = 1.0;
    ph[slot].dir = vec4(r, float(key));   // the key (< 2^24, exact): further bounces draw from it (L13)
    ph[slot].pow_d1 = vec4(flux * s / ps, length(x - u_light_pos));
}
