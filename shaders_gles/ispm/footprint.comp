// Splat footprints from the photons' neighbours (not in the seed; ispm_radius=footprint, an
// improvement behind a switch; in the spirit of photon differentials and of the ellipsoid splats of
// McGuire & Luebke's image-space photon mapping, research Part A's [ML09]). The
// photons of neighbouring RSM blocks leave the mirror side by side; where they land, the vectors to
// the neighbours' hits span the photon's flux tube on the receiver, d_x and d_y (central
// differences, one-sided where a neighbour is missing). The disk of a plane mirror (the seed's
// h = C0·d·√(ΔΩ/cosθ)) is this tube made round; a curved mirror stretches it along a caustic line
// and squeezes it across, where a round disk blurs the line sideways. Here each hit's splat is the
// ellipse M·(disk of radius C0), M = [d_x d_y] in the receiver's tangent plane: semi-axes C0·σ1,
// C0·σ2 (the singular values of M) along M's left singular vectors. Across a fold both neighbours
// land on the same side, so the central difference and the ellipse's minor axis shrink to the
// line's own width. Each semi-axis is that width combined in quadrature with u_h_pixels kernel
// samples as the camera sees the axis (splat.frag averages these ellipses' kernel over u_samples²
// points per splat pixel, so u_h_pixels of those samples deposit the power as u_h_pixels pixels do
// for point-sampled disks, L15), and clamped at u_h_max (L14); in quadrature rather than max(), so
// the footprint's measure of the tube still counts where it is near that size. No u_h_min: that
// clamp guards the seed's radius formula (d -> 0, L14); here the samples' size is the least one. A neighbour counts if it landed after as many specular bounces (Hit.pos_valid.w), on the
// same surface (normals within acos(u_normal_cos), the splats' "same surface") and within u_h_max;
// a hit with no usable neighbour along an axis keeps the round disk of the radius it has
// (Hit.nrm_h.w: the seed's or the density's). The kernel stays normalised over the ellipse's area,
// so every splat still deposits its Φ: only the shape of the blur changes.
//   u_phase 0: clear the block -> slot map; 1: fill it (a photon's key is its RSM block at the
//   chosen level, emit.comp, unless debug rng_by_slot keys it by slot: then every hit keeps its
//   disk); 2: the ellipses.
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
// bindings 0-3: ES 3.1 guarantees four storage blocks and bindings to a compute shader
#include "ispm/common.glsl"
layout(std430, binding = 0) readonly buffer Photons { ISPM_PHOTON_HEADER Photon ph[]; };
layout(std430, binding = 1) readonly buffer Hits { Hit hits[]; };
layout(std430, binding = 2) buffer Blocks { int slot_of_block[]; };
layout(std430, binding = 3) writeonly buffer Feet { vec4 feet[]; };   // 2 per hit: (e1, a1), (e2, a2)
uniform int u_phase;
uniform int u_capacity;
uniform int u_res;              // RSM resolution (the block grid at level 0)
uniform int u_keyed_by_block;   // 0: keys are slots (debug rng_by_slot), no neighbours known
uniform vec3 u_cam;
uniform float u_pixel_angle;    // a splat pixel's size at unit distance
uniform float u_h_pixels;       // least semi-axis, in kernel samples (h_pixels / samples per side)
uniform float u_c0, u_h_max, u_normal_cos;

int level_offset(int l)
{
    int off = 0;
    for (int k = 0; k < l; k++)
        off += (u_res >> k) * (u_res >> k);
    return off;
}

// The hit of the photon of block (bx, by) if it can stand beside hit i's: else -1.
int neighbour(int bx, int by, int rl, Hit hi)
{
    if (bx < 0 || by < 0 || bx >= rl || by >= rl)
        return -1;
    int j = slot_of_block[by * rl + bx];
    if (j < 0)
        return -1;
    Hit hj = hits[j];
    if (hj.pos_valid.w != hi.pos_valid.w || dot(hj.nrm_h.xyz, hi.nrm_h.xyz) < u_normal_cos ||
        distance(hj.pos_valid.xyz, hi.pos_valid.xyz) > u_h_max)
        return -1;
    return j;
}

// The tube's side along one block axis (e), projected into the plane of normal n; false if neither
// neighbour is usable.
bool side(int bx, int by, ivec2 e, int rl, Hit hi, out vec3 d)
{
    int p = neighbour(bx + e.x, by + e.y, rl, hi), m = neighbour(bx - e.x, by - e.y, rl, hi);
    vec3 c = hi.pos_valid.xyz;
    if (p >= 0 && m >= 0)
        d = 0.5 * (hits[p].pos_valid.xyz - hits[m].pos_valid.xyz);
    else if (p >= 0)
        d = hits[p].pos_valid.xyz - c;
    else if (m >= 0)
        d = c - hits[m].pos_valid.xyz;
    else
        return false;
    vec3 n = hi.nrm_h.xyz;
    d -= n * dot(n, d);
    return true;
}

// The least semi-axis along e: u_h_pixels kernel samples as the camera sees e (foreshortened by the
// view ray, at most 5x, as the radius' cosθ clamp).
float least_axis(vec3 x, vec3 e)
{
    vec3 v = x - u_cam;
    float dist = length(v);
    v /= dist;
    float across = max(length(e - v * dot(e, v)), 0.2);
    return u_h_pixels * u_pixel_angle * dist / across;
}

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    int l = int(ph_level);
    int rl = u_res >> l;
    if (u_phase == 0) {
        if (i < rl * rl)
            slot_of_block[i] = -1;
        return;
    }
    if (i >= u_capacity || uint(i) >= ph_count)
        return;
    Hit hi = hits[i];
    int b = int(ph[i].dir.w) - level_offset(l);
    if (u_phase == 1) {
        if (u_keyed_by_block == 1 && hi.pos_valid.w != 0.0 && b >= 0 && b < rl * rl)
            slot_of_block[b] = i;
        return;
    }
    vec3 n = hi.nrm_h.xyz, t, bt;
    ispm_tangent_frame(n, t, bt);
    // the round disk of the hit's own radius, unless both sides of the tube are known
    feet[2 * i] = vec4(t, hi.nrm_h.w);
    feet[2 * i + 1] = vec4(bt, hi.nrm_h.w);
    vec3 dx, dy;
    if (u_keyed_by_block == 0 || hi.pos_valid.w == 0.0 || b < 0 || b >= rl * rl ||
        !side(b % rl, b / rl, ivec2(1, 0), rl, hi, dx) || !side(b % rl, b / rl, ivec2(0, 1), rl, hi, dy))
        return;
    // M = [dx dy] in the frame (t, bt); the ellipse's axes are the eigenvectors of M·Mᵀ
    vec2 mx = vec2(dot(dx, t), dot(dx, bt)), my = vec2(dot(dy, t), dot(dy, bt));
    float a = mx.x * mx.x + my.x * my.x, c = mx.y * mx.y + my.y * my.y, o = mx.x * mx.y + my.x * my.y;
    float mid = 0.5 * (a + c), rad = sqrt(max(0.25 * (a - c) * (a - c) + o * o, 0.0));
    float l1 = mid + rad, l2 = max(mid - rad, 0.0);
    vec2 v1 = abs(o) > 1e-12 * (a + c) ? normalize(vec2(o, l1 - a)) : (a >= c ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
    vec3 e1 = v1.x * t + v1.y * bt, e2 = -v1.y * t + v1.x * bt;
    vec3 x = hi.pos_valid.xyz;
    float p1 = least_axis(x, e1), p2 = least_axis(x, e2);
    float a1 = min(sqrt(u_c0 * u_c0 * l1 + p1 * p1), u_h_max);
    float a2 = min(sqrt(u_c0 * u_c0 * l2 + p2 * p2), u_h_max);
    feet[2 * i] = vec4(e1, a1);
    feet[2 * i + 1] = vec4(e2, a2);
}
