// The specular mask's mip chain as integer counts (research A.5, L20: an R8 mipmap rounds up, R32F
// needs EXT_color_buffer_float): level 0 is the RSM's mask bit, level k+1 the sum of its four
// children, so a block is "all specular" exactly when its count is 4^k. Also counts, per level,
// the blocks that hold any specular texel (emit.comp's photon budget rule).
// PHOTONS_COUNT_FETCHES: the bench's counting variant (#21, app/gi/ispm/ispm_work.c), as emit.comp's:
// per invocation its RSM texels (RGB10_A2, unfiltered), RSM depth texels (none here), storage-buffer
// loads and atomics, added to binding 6. Never in the kiosk's frames.
// @variant -
// @variant PHOTONS_COUNT_FETCHES
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
#include "ispm/common.glsl"
#ifdef PHOTONS_COUNT_FETCHES
layout(std430, binding = 6) buffer PhotonsFetches { highp uint texels, depths, loads, atomics; } photons_counted;
#endif
layout(std430, binding = 0) buffer Counts { uint counts[]; };
layout(std430, binding = 2) buffer Photons { ISPM_PHOTON_HEADER Photon ph[]; };
uniform highp sampler2D u_rsm_nrm;
uniform int u_level;       // level written
uniform int u_size;        // its size (RSM resolution >> level)
uniform int u_off;         // its offset in counts[]
uniform int u_off_prev;    // offset of level - 1
uniform int u_top;         // index of the 1x1 level
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size || p.y >= u_size)
        return;
    uint c;
    if (u_level == 0) {
        c = texelFetch(u_rsm_nrm, p, 0).a > 0.5 ? 1u : 0u;
    } else {
        int child = 2 * u_size;
        int b = u_off_prev + 2 * p.y * child + 2 * p.x;
        c = counts[b] + counts[b + 1] + counts[b + child] + counts[b + child + 1];
    }
    counts[u_off + p.y * u_size + p.x] = c;
    if (c > 0u)
        atomicAdd(ph_nonzero[u_level], 1u);
#ifdef PHOTONS_COUNT_FETCHES
    if (u_level == 0)
        atomicAdd(photons_counted.texels, 1u);
    else
        atomicAdd(photons_counted.loads, 4u);
    if (c > 0u)
        atomicAdd(photons_counted.atomics, 1u);
#endif
    if (u_level == u_top)
        ph_top = c;
}
