// Photon tracing by a compute march through the per-pixel lists (seed 000 pass 11, Algorithm 3.5;
// research A.1.11 form (a), Appendix D.2). One invocation per photon slot: the reflected ray is
// clipped to the near plane and to the trace image, projected, and stepped one pixel along its major
// axis; at each pixel the list's nodes are hit candidates, and the first pixel with a hit ends the
// march. Two hit tests:
//   the seed's (u_plane = 0): |node depth − ray depth| < ε, ε = u_eps_abs + u_eps_slope·|Δz per
//     step| (slope-scaled; u_eps_slope = 0 is its constant threshold), the smallest |Δz| wins;
//   the plane test (u_plane = 1, default): the ray meets the node's plane (its depth at the pixel
//     centre and its normal) within u_hit_px pixels of the pixel centre, the nearest along the ray
//     wins; a plane behind the photon's origin is no hit (the outer face of the wall it leaves).
//     A depth compared at the pixel centre misses surfaces seen at a grazing angle, whose depth
//     changes by more than ε across the pixel: on caustic-ring 4.7% of the photon power went
//     through the ring's 2 cm wall onto the floor behind it (research L10's tunnelling). A node
//     seen (nearly) edge-on (|cos| < u_edge_on_cos to the view ray) hits only within u_edge_reach
//     pixel footprints of its own point: its plane meets every ray crossing the pixel, also far
//     from the fragment (on caustic-ring another facet of the ring took 1% of the photons, L9).
//   Self-intersection rule: a node whose geometric normal faces along the ray (dot(n, dir) > 0) is
//   the back of what the ray leaves, not a hit (u_backface = 0 turns the rule off for L9).
// Specular chains (u_bounces > 1, not in the seed, research L7): a hit on a mirror node (Node.spec)
// reflects the photon again (power × the mirror's specular albedo, the Phong lobe of its roughness
// from the photon's key, about the normal at the hit: the node's normal turned by its shape operator
// over the hit's offset from the node's point, ispm_normal_at; u_mirror_shape = 0 reflects about the
// node's own normal) and the march restarts there, until a non-mirror surface or u_bounces
// specular bounces in all (the emission's counts); with u_bounces = 1 a mirror hit ends the photon
// as in the seed (the mirror's ρ_d of 0 shows nothing of it).
// The hit carries its splat radius h = C0 · d / sqrt(cosθ) · sqrt(ΔΩ) (seed: h = C0/√p · √(A/N),
// p = cosθ/d²), read here as the solid angle one photon stands for, ΔΩ = 4^l · ΔΩ_texel, so that
// A/N is the footprint a photon's block would light through a plane mirror at unit distance
// (research A.7 item 9 leaves A open); d is the whole path light→reflector(s)→receiver, cosθ is
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
uniform int u_plane;            // 1: the plane test; 0: the seed's depth test
uniform float u_hit_px;         // the plane test's reach around the pixel centre (pixels)
uniform float u_edge_on_cos;    // nodes seen at |cos| below this are "edge-on"
uniform float u_edge_reach;     // an edge-on node's plane hit: at most this many pixel footprints off
uniform float u_skip_rel;       // empty-space skip margin, relative depth (see march)
uniform int u_bounces;          // specular bounces in all (1: the seed's)
uniform int u_mirror_shape;     // 1: further bounces reflect about the normal at the hit (Node.shape)
uniform int u_capacity;
uniform float u_c0, u_omega_texel, u_cos_min, u_h_min, u_h_max;

uint work = 0u;                 // march steps + list nodes visited (L19)

// The view-space point of trace pixel p at linear depth z (the lists' node positions).
vec3 pixel_point(ivec2 p, float z)
{
    vec2 ndc = (vec2(p) + 0.5) / vec2(u_res) * 2.0 - 1.0;
    return z * vec3((ndc.x + u_proj[2][0]) / u_proj[0][0], (ndc.y + u_proj[2][1]) / u_proj[1][1], -1.0);
}

// The first surface the ray o + r·t (t in (0, u_tmax]) meets in the lists: its node, t and the
// node's view-space point (its depth at its pixel's centre).
bool march(vec3 o, vec3 r, out int hit_node, out float hit_t, out vec3 hit_pn)
{
    vec3 a = (u_view * vec4(o, 1.0)).xyz;
    vec3 b = (u_view * vec4(o + r * u_tmax, 1.0)).xyz;
    if (a.z > -u_near && b.z > -u_near)
        return false;   // wholly behind the near plane
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
                return false;
        } else {
            float t0 = lo / dv, t1 = hi / dv;
            s0 = max(s0, min(t0, t1));
            s1 = min(s1, max(t0, t1));
        }
    }
    if (s0 > s1)
        return false;   // never on screen
    float len = max(abs(dsv.x), abs(dsv.y)) * (s1 - s0);
    int n = int(ceil(len)) + 1;
    float ds = n > 1 ? (s1 - s0) / float(n - 1) : 0.0;
    mat3 view_rot = mat3(u_view);
    float px_angle = 2.0 * max(1.0 / u_proj[0][0], 1.0 / u_proj[1][1]) / float(max(u_res.x, u_res.y));
    vec3 AB = B - A;
    for (int k = 0; k < n; ++k) {   // outward: the first hit is the nearest
        work++;
        float s = s0 + float(k) * ds;
        vec2 sp = mix(sa, sb, s);
        ivec2 pxy = clamp(ivec2(floor(sp)), ivec2(0), u_res - 1);
        float zr = 1.0 / mix(ia, ib, s);   // the ray's linear depth here
        float zr1 = 1.0 / mix(ia, ib, min(1.0, s + max(ds, 1e-6)));
        float eps = u_eps_abs + u_eps_slope * abs(zr1 - zr);
        int pix = pxy.y * u_res.x + pxy.x;
        Pixel q = px[pix];
        // Empty space: the ray's depth is outside the list's range. With the plane test a node's
        // surface may lie off its centre depth by its slope over the reach (u_skip_rel of the
        // depth: the slope of a surface seen at u_edge_on_cos).
        float margin = eps + (u_plane == 1 ? u_skip_rel * zr + abs(zr1 - zr) : 0.0);
        if (q.head < 0 || zr < uintBitsToFloat(q.zmin) - margin || zr > uintBitsToFloat(q.zmax) + margin)
            continue;
        float best = u_plane == 1 ? 2.0 : eps;   // plane test: the least u; seed: the least |Δz|
        int best_idx = -1;
        float best_u = 0.0;
        vec3 best_pn = vec3(0.0);
        for (int idx = q.head; idx != -1; idx = nodes[idx].next) {
            work++;
            Node nd = nodes[idx];
            vec3 nw = ispm_decode_normal(nd.nrm);
            if (u_backface == 1 && dot(nw, r) >= 0.0)
                continue;
            vec3 pn = pixel_point(pxy, nd.depth), nv = view_rot * nw;
            float den = dot(AB, nv);
            if (u_plane == 1) {
                if (abs(den) < 1e-12)
                    continue;   // along the plane
                float u = dot(pn - A, nv) / den;
                if (u < 0.0 || u > 1.0 || u >= best)
                    continue;
                vec3 Q = A + AB * u;
                vec4 cq = u_proj * vec4(Q, 1.0);
                vec2 d = (cq.xy / cq.w * 0.5 + 0.5) * res - (vec2(pxy) + 0.5);
                if (max(abs(d.x), abs(d.y)) > u_hit_px)
                    continue;
                // a node seen nearly edge-on: its plane meets every ray crossing the pixel, also
                // far from the fragment; only within u_edge_reach pixel footprints of it
                if (abs(dot(nv, pn)) < u_edge_on_cos * length(pn) && distance(Q, pn) > u_edge_reach * nd.depth * px_angle)
                    continue;
                best = u, best_idx = idx, best_u = u, best_pn = pn;
            } else {
                // the seed's test
                float dz = abs(nd.depth - zr);
                if (dz >= best)
                    continue;
                // where the ray reaches the node's depth (the surface's depth at this pixel)
                float u = (s * ib) / mix(ia, ib, s);   // perspective-correct parameter on [A, B]
                if (abs(AB.z) > 1e-6 * abs(A.z))
                    u = clamp((-nd.depth - A.z) / AB.z, 0.0, 1.0);
                best = dz, best_idx = idx, best_u = u, best_pn = pn;
            }
        }
        if (best_idx >= 0) {
            hit_node = best_idx;
            hit_t = mix(ta, tb, best_u) * u_tmax;
            hit_pn = best_pn;
            return true;
        }
    }
    return false;
}

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
    vec3 o = P.org.xyz, r = normalize(P.dir.xyz), power = P.pow_d1.xyz;
    uint key = uint(P.dir.w);
    float dist = P.pow_d1.w;
    for (int bounce = 1; bounce <= u_bounces; bounce++) {
        int node;
        float t;
        vec3 pn;
        if (!march(o, r, node, t, pn))
            break;
        Node nd = nodes[node];
        vec3 nh = ispm_decode_normal(nd.nrm);
        vec3 x = o + r * t;
        dist += t;
        if (nd.spec != 0u && bounce < u_bounces) {   // a mirror: reflect and march on
            vec4 sr = unpackUnorm4x8(nd.spec);
            // the hit's offset from the node's point, rotated from view to world (u_view is rigid)
            vec3 dp = transpose(mat3(u_view)) * ((u_view * vec4(x, 1.0)).xyz - pn);
            vec3 nm = u_mirror_shape == 1 ? ispm_normal_at(nh, nd.shape, dp) : nh;
            vec3 nf = dot(nh, r) < 0.0 ? nm : -nm;
            vec3 rn = ispm_phong_lobe(reflect(r, nf), sr.a, key, 1u + 2u * uint(bounce));
            if (dot(rn, nf) <= 0.0)
                break;   // below the surface: absorbed
            o = x, r = rn, power *= sr.rgb;
            continue;
        }
        float cos_t = abs(dot(nh, r));
        float omega = u_omega_texel * float(1u << (2u * ph_level));
        float h = clamp(u_c0 * dist * sqrt(omega / max(cos_t, u_cos_min)), u_h_min, u_h_max);
        hits[i].pos_valid = vec4(x, float(bounce));   // w: the specular bounces on its path
        hits[i].nrm_h = vec4(dot(nh, r) < 0.0 ? nh : -nh, h);
        hits[i].pow_dist = vec4(power, dist);
        atomicAdd(ph_hits, 1u);
        break;
    }
    atomicAdd(ph_steps, work);
}
