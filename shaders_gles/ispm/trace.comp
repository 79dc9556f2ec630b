// Photon tracing by a compute march through the per-pixel lists (seed 000 pass 11, Algorithm 3.5;
// research A.1.11 form (a), Appendix D.2). One invocation per photon slot: the reflected ray is
// clipped to the near plane and to the trace image, projected, and stepped one pixel along its major
// axis; at each pixel the list's nodes within ε of the ray's depth are hit candidates, the nearest
// in depth wins (order-independent), and the first pixel with a hit ends the march.
//   ε = u_eps_abs + u_eps_slope·|Δz per step| (slope-scaled; u_eps_slope = 0 is the seed's
//   constant threshold; k = 1 found every hit on the right surface in the research's experiment).
//   Self-intersection rule: a node whose geometric normal faces along the ray (dot(n, dir) > 0) is
//   the back of what the ray leaves, not a hit (u_backface = 0 turns the rule off for L9).
// The hit carries its splat radius h = C0 · d / sqrt(cosθ) · sqrt(ΔΩ) (seed: h = C0/√p · √(A/N),
// p = cosθ/d²), read here as the solid angle one photon stands for, ΔΩ = 4^l · ΔΩ_texel, so that
// A/N is the footprint a photon's block would light through a plane mirror at unit distance
// (research A.7 item 9 leaves A open); d is the whole path light→reflector→receiver, cosθ is
// clamped at u_cos_min and h to [u_h_min, u_h_max] (L14).
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
#include "ispm/common.glsl"
layout(std430, binding = 0) readonly buffer Nodes { Node nodes[]; };
layout(std430, binding = 1) readonly buffer Pixels { Pixel px[]; };
layout(std430, binding = 2) buffer Photons { ISPM_PHOTON_HEADER Photon ph[]; };
layout(std430, binding = 3) writeonly buffer Hits { Hit hits[]; };
uniform mat4 u_view;            // world -> view (camera looks down -Z)
uniform mat4 u_proj;            // view -> clip, the lists' projection
uniform ivec2 u_res;            // trace resolution
uniform float u_near;
uniform float u_tmax;           // ray length (scene diameter)
uniform float u_eps_abs, u_eps_slope;
uniform int u_backface;
uniform int u_reach;             // 1: the reach test below
uniform int u_capacity;
uniform float u_c0, u_omega_texel, u_cos_min, u_h_min, u_h_max;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_capacity)
        return;
    hits[i].pos_valid = vec4(0.0);
    if (uint(i) >= min(ph_count, uint(u_capacity)))
        return;
    Photon P = ph[i];
    if (P.org.w == 0.0)
        return;
    vec3 o = P.org.xyz, r = normalize(P.dir.xyz);
    vec3 a = (u_view * vec4(o, 1.0)).xyz;
    vec3 b = (u_view * vec4(o + r * u_tmax, 1.0)).xyz;
    if (a.z > -u_near && b.z > -u_near)
        return;   // wholly behind the near plane
    float ta = 0.0, tb = 1.0;
    if (a.z > -u_near)
        ta = (-u_near - a.z) / (b.z - a.z);
    if (b.z > -u_near)
        tb = (-u_near - a.z) / (b.z - a.z);
    vec3 A = mix(a, b, ta), B = mix(a, b, tb);
    vec4 ca = u_proj * vec4(A, 1.0), cb = u_proj * vec4(B, 1.0);
    vec2 res = vec2(u_res);
    vec2 sa = (ca.xy / ca.w * 0.5 + 0.5) * res, sb = (cb.xy / cb.w * 0.5 + 0.5) * res;
    float ia = 1.0 / ca.w, ib = 1.0 / cb.w;   // 1/w is affine in screen space
    // Liang–Barsky clip of the screen segment to the image: s in [s0, s1]
    float s0 = 0.0, s1 = 1.0;
    vec2 dsv = sb - sa;
    for (int ax = 0; ax < 2; ax++) {
        float lo = -sa[ax], hi = res[ax] - sa[ax], dv = dsv[ax];
        if (abs(dv) < 1e-9) {
            if (lo > 0.0 || hi < 0.0)
                return;
        } else {
            float t0 = lo / dv, t1 = hi / dv;
            s0 = max(s0, min(t0, t1));
            s1 = min(s1, max(t0, t1));
        }
    }
    if (s0 > s1)
        return;   // never on screen
    float len = max(abs(dsv.x), abs(dsv.y)) * (s1 - s0);
    int n = int(ceil(len)) + 1;
    float ds = n > 1 ? (s1 - s0) / float(n - 1) : 0.0;
    uint work = 0u;
    for (int k = 0; k < n; ++k) {   // outward: the first hit is the nearest
        work++;
        float s = s0 + float(k) * ds;
        ivec2 pxy = clamp(ivec2(floor(mix(sa, sb, s))), ivec2(0), u_res - 1);
        float zr = 1.0 / mix(ia, ib, s);   // the ray's linear depth here
        float zr1 = 1.0 / mix(ia, ib, min(1.0, s + max(ds, 1e-6)));
        float eps = u_eps_abs + u_eps_slope * abs(zr1 - zr);
        int pix = pxy.y * u_res.x + pxy.x;
        Pixel q = px[pix];
        if (q.head < 0 || zr < uintBitsToFloat(q.zmin) - eps || zr > uintBitsToFloat(q.zmax) + eps)
            continue;   // empty space
        float best = eps;
        int best_idx = -1;
        float dzab = B.z - A.z;
        for (int idx = q.head; idx != -1; idx = nodes[idx].next) {
            work++;
            float dz = abs(nodes[idx].depth - zr);
            if (dz < best && (u_backface == 0 || dot(ispm_decode_normal(nodes[idx].nrm), r) < 0.0)) {
                // Reach test (not in the seed; u_reach = 0 turns it off): the ray must reach the
                // node's depth within a pixel and a half of here. Near its origin a ray leaving the
                // inner wall of a 2 cm ring is within ε of the outer wall's fragments, which face
                // it; they took 29% of caustic-ring's photons (test_ispm_ring, L9).
                if (u_reach == 1 && abs(dzab) > 1e-6 * abs(A.z)) {
                    float un = (-nodes[idx].depth - A.z) / dzab;
                    float sn = un * ia / (ib + un * (ia - ib));
                    if (un < 0.0 || un > 1.0 || abs(sn - s) * max(abs(dsv.x), abs(dsv.y)) > 1.5)
                        continue;
                }
                best = dz;
                best_idx = idx;
            }
        }
        if (best_idx >= 0) {
            vec3 nh = ispm_decode_normal(nodes[best_idx].nrm);
            // The hit is where the ray reaches the node's depth (the surface's depth at this pixel),
            // not the ray's depth at the sample: along a surface's normal the sample is off by up
            // to ε, which put whole splats outside the "same surface" slab (L15 lost 2.3%).
            float u = (s * ib) / mix(ia, ib, s);   // perspective-correct parameter on [A, B]
            if (abs(dzab) > 1e-6 * abs(A.z))
                u = clamp((-nodes[best_idx].depth - A.z) / dzab, 0.0, 1.0);
            float t = mix(ta, tb, u) * u_tmax;
            float cos_t = abs(dot(nh, r));
            float dist = P.pow_d1.w + t;
            float omega = u_omega_texel * float(1u << (2u * ph_level));
            float h = clamp(u_c0 * dist * sqrt(omega / max(cos_t, u_cos_min)), u_h_min, u_h_max);
            hits[i].pos_valid = vec4(o + r * t, 1.0);
            hits[i].nrm_h = vec4(dot(nh, r) < 0.0 ? nh : -nh, h);
            hits[i].pow_dist = vec4(P.pow_d1.xyz, dist);
            atomicAdd(ph_hits, 1u);
            atomicAdd(ph_steps, work);
            return;
        }
    }
    atomicAdd(ph_steps, work);
}
