// Photon rays traced against the distance cube-maps (seed 002 §3; research B.2.1-B.2.3): the initial
// testing point (ITP) by angle partition on the map nearest the photon, then secant refinement on
// the map nearest the ITP (at most two maps per ray). Included by trace.comp.
uniform highp usampler2DArray u_dist;   // R32UI float bits, min-reduced mips
uniform mediump sampler2DArray u_nrm;
uniform mediump sampler2DArray u_alb;
uniform int u_res;            // face resolution (level 0)
uniform int u_levels;         // distance mip levels
uniform int u_n_maps;         // lattice maps: layers 0 .. 6 n - 1
uniform int u_n_refractors;   // refractor maps after them
uniform int u_q;              // angle partition intervals (Q = 8)
uniform int u_loops;          // angle partition loops (<= 3)
uniform float u_itp_eps;      // stop when the ITP moves less than this (m)
uniform int u_secant_steps;
uniform vec3 u_bmin;          // the scene's bounds (a little padded): a ray leaving them met nothing
uniform vec3 u_bmax;
uniform int u_itp_mode;       // 0 angle partition (the seed), 1 planar ITP (Fig. 4's comparison)
uniform int u_bounds_hit;     // 1: a ray reaching the bounds where the map sees a surface met it (lgv_secant)
layout(std430, binding = 0) readonly buffer Maps { highp vec4 centre[]; };
// TRACE_COUNT_FETCHES (the bench's counting variant, app/gi/lgv/lgv_work.c): every distance-map
// texel read, the partition's, the secant's and the map choice's alike, counted per invocation in
// g_dist_fetches; trace.comp adds it to its buffer once.
#ifdef TRACE_COUNT_FETCHES
highp uint g_dist_fetches = 0u;
#endif

highp float lgv_dist(int map, highp vec3 d, int level)
{
    highp vec2 uv;
    int f = lgv_face_of(d, uv);
    int res = max(u_res >> level, 1);
    ivec2 t = clamp(ivec2((uv * 0.5 + 0.5) * float(res)), ivec2(0), ivec2(res - 1));
#ifdef TRACE_COUNT_FETCHES
    g_dist_fetches++;
#endif
    return uintBitsToFloat(texelFetch(u_dist, ivec3(t, map * 6 + f), level).r);
}

ivec3 lgv_texel(int map, highp vec3 d)
{
    highp vec2 uv;
    int f = lgv_face_of(d, uv);
    ivec2 t = clamp(ivec2((uv * 0.5 + 0.5) * float(u_res)), ivec2(0), ivec2(u_res - 1));
    return ivec3(t, map * 6 + f);
}

// The normal map m stores towards d, interpolated bilinearly between the face's four nearest texels
// (clamped at the face's edges). For a refractor map, whose centre lies inside its object, every
// texel holds that one smooth surface, so the interpolation has no silhouettes to cross.
highp vec3 lgv_normal_smooth(int m, highp vec3 d)
{
    highp vec2 uv;
    int f = lgv_face_of(d, uv);
    highp vec2 t = (uv * 0.5 + 0.5) * float(u_res) - 0.5;
    ivec2 t0 = ivec2(floor(t));
    highp vec2 w = t - vec2(t0);
    highp vec3 n = vec3(0.0);
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 tk = clamp(t0 + o, ivec2(0), ivec2(u_res - 1));
        highp float wk = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y);
        n += wk * (texelFetch(u_nrm, ivec3(tk, m * 6 + f), 0).xyz * 2.0 - 1.0);
    }
    return normalize(n);
}

int lgv_nearest_map(highp vec3 x, int first, int count)
{
    int best = first;
    highp float bd = 1e30;
    for (int m = first; m < first + count; m++) {
        highp vec3 c = centre[m].xyz - x;
        highp float d = dot(c, c);
        if (d < bd) {
            bd = d;
            best = m;
        }
    }
    return best;
}

// The lattice map nearest x among those that see x (x no farther from the centre than the map's
// surface that way, within a texel's footprint); the nearest of all when none does. The seed's
// "nearest map" presumes it sees the photon: a centre pushed out of a thin wall lies beside it, and
// the photons on the wall's other side, nearest to it, were traced on a map that sees only the wall
// (light-leak, 27 maps: 55% of the LGV's flux landed in the unlit room). Only with LGV_SEEING_MAPS
// (gk_lgv_debug.seeing_maps, a define of trace.comp's variant: llvmpipe runs a branch a uniform
// switch turns off too, this loop's first iteration included); without it the nearest.
int lgv_seeing_map(highp vec3 x)
{
    int nearest = lgv_nearest_map(x, 0, u_n_maps);
#ifndef LGV_SEEING_MAPS
    return nearest;
#else
    int best = -1;
    highp float bd = 1e30;
    for (int m = 0; m < u_n_maps; m++) {
        highp vec3 c = x - centre[m].xyz;
        highp float d2 = dot(c, c);
        if (d2 >= bd)
            continue;
        highp float dm = lgv_dist(m, c, 0);
        highp float reach = dm * (1.0 + 2.0 / float(u_res));
        if (d2 <= reach * reach) {
            bd = d2;
            best = m;
        }
    }
    return best >= 0 ? best : nearest;
#endif
}

// Eq. (2)-(3): f = d^2 a for impostor p (relative to the centre), photon t (relative to the
// centre), ray direction r; infinite when the impostor lies behind the photon.
highp float lgv_energy(highp vec3 p, highp vec3 t, highp vec3 r)
{
    highp vec3 pt = p - t;
    highp float len = length(pt), along = dot(pt, r);
    if (along <= 0.0)
        return 1e30;
    highp float d = abs(len - along), a = len + along;
    return d * d * a;
}

// Direction at angle phi of the fan from t^ (phi 0) towards r^ (phi theta) in the plane (t^, b).
highp vec3 lgv_fan(highp vec3 th, highp vec3 b, highp float phi) { return cos(phi) * th + sin(phi) * b; }

// The ITP of ray x + d r on map m (angle partition, B.2.1); false when every impostor of the fan
// lies behind the photon.
bool lgv_itp_angle(int m, highp vec3 x, highp vec3 r, out highp vec3 itp)
{
    highp vec3 v = centre[m].xyz;
    highp vec3 t = x - v;
    highp float tl = length(t);
    if (tl < 1e-6) {
        itp = v + lgv_dist(m, r, 0) * r;
        return true;
    }
    highp vec3 th = t / tl;
    highp float c = clamp(dot(th, r), -1.0, 1.0);
    highp float theta = acos(c);
    highp vec3 b = r - c * th;
    if (length(b) < 1e-5)
        b = abs(th.x) < 0.9 ? cross(th, vec3(1.0, 0.0, 0.0)) : cross(th, vec3(0.0, 1.0, 0.0));
    b = normalize(b);
    highp float lo = 0.0, hi = theta;
    highp vec3 prev = vec3(1e30);
    bool found = false;
    for (int loop = 0; loop < u_loops; loop++) {
        // coarse min-reduced mips first (research B.1.2), level 0 in the last loop
        int level = clamp(u_loops - 1 - loop, 0, u_levels - 1);
        highp float step = (hi - lo) / float(u_q);
        highp vec3 w0 = lgv_fan(th, b, lo);
        highp float f0 = lgv_energy(lgv_dist(m, w0, level) * w0, t, r);
        highp float best = 1e30;
        int bi = -1;
        for (int i = 0; i < u_q; i++) {
            highp vec3 w1 = lgv_fan(th, b, lo + step * float(i + 1));
            highp float f1 = lgv_energy(lgv_dist(m, w1, level) * w1, t, r);
            highp float g = f0 + f1;
            if (g < best) {
                best = g;
                bi = i;
            }
            f0 = f1;
        }
        if (bi < 0 || best >= 1e29)
            break;
        lo = lo + step * float(bi);
        hi = lo + step;
        highp vec3 q = lgv_fan(th, b, 0.5 * (lo + hi));
        itp = v + lgv_dist(m, q, 0) * q;
        found = true;
        if (distance(itp, prev) < u_itp_eps)
            break;
        prev = itp;
    }
    return found;
}

// Yao et al.'s planar ITP as this project reads it (research B.5 item 2): the point of the ray
// nearest the map's centre (the foot of the perpendicular from V), or the photon when that lies
// behind it.
highp vec3 lgv_itp_planar(int m, highp vec3 x, highp vec3 r)
{
    highp float d = max(dot(centre[m].xyz - x, r), 0.0);
    return x + d * r;
}

// Secant error e(d) = |x(d)| - D(x(d)/|x(d)|) on map m (B.2.3): < 0 in front of the surface.
highp float lgv_err(int m, highp vec3 x0, highp vec3 r, highp float d)
{
    highp vec3 p = x0 + d * r;
    highp float l = length(p);
    return l - lgv_dist(m, p / max(l, 1e-12), 0);
}

// A ray that reaches the scene's bounds still in front of map m's surface: the bounds hold every
// surface, so where the map sees one that way (its texel is not empty) the ray met it at the bounds,
// a box's wall lying on them. The nearest texel's distance is the texel centre's: across a texel
// of a wall seen obliquely it differs by ~ d tan(angle) x the texel's angle (64^2: 2% of d at 60
// degrees), far more than the bounds' 0.1% padding, so the error test alone leaves such rays in
// front of the wall (test_lgv: 99.7% of glass's photon-like rays with no hit had their true
// surface at the bounds). p is relative to the map's centre.
bool lgv_bounds_hit(int m, highp vec3 p)
{
    return u_bounds_hit == 1 && lgv_dist(m, p, 0) < 0.5 * LGV_FAR;
}

// Secant iterations on map m inside the bracket [dl, dp], whose errors el and ep differ in sign (either
// way: a refractor map's outside is behind its surface); returns the last estimate.
highp float lgv_refine(int m, highp vec3 x0, highp vec3 r, highp float dl, highp float el, highp float dp, highp float ep)
{
    highp float d = dp;
    for (int k = 0; k < u_secant_steps; k++) {
        highp float den = ep - el;
        d = clamp(abs(den) > 1e-12 ? dl - el * (dp - dl) / den : 0.5 * (dl + dp), dl, dp);
        highp float e = lgv_err(m, x0, r, d);
        if ((e < 0.0) == (el < 0.0))
            dl = d, el = e;
        else
            dp = d, ep = e;
    }
    return d;
}

// Secant refinement on map m from the initial distance d0 along the ray; returns the hit
// distance, or -1 when the ray leaves the scene (at d_max) in front of every surface.
highp float lgv_secant(int m, highp vec3 x, highp vec3 r, highp float d0, highp float d_start, highp float d_max)
{
    highp vec3 x0 = x - centre[m].xyz;
    highp float dl = d_start, el = lgv_err(m, x0, r, dl);
    highp float dp = clamp(d0, 2.0 * d_start, max(d_max, 2.0 * d_start)), ep = lgv_err(m, x0, r, dp);
    if (ep < 0.0) {
        // undershoot: step on (x1.5) until behind a surface
        bool hit = false;
        for (int k = 0; k < 16 && !hit; k++) {
            dl = dp;
            el = ep;
            if (dp >= d_max)
                return lgv_bounds_hit(m, x0 + d_max * r) ? d_max : -1.0;
            dp = min(dp * 1.5 + d_start, d_max);
            ep = lgv_err(m, x0, r, dp);
            hit = ep >= 0.0;
        }
        if (!hit)
            return -1.0;
    } else if (el >= 0.0) {
        // the start is hidden from this map: the first in-front sample of [d_start, dp] brackets
        bool ok = false;
        highp float pe = el, pd = dl;
        for (int k = 1; k <= 8 && !ok; k++) {
            highp float dk = d_start + (dp - d_start) * float(k) / 8.0, ek = lgv_err(m, x0, r, dk);
            if (pe < 0.0 && ek >= 0.0) {
                dl = pd, el = pe, dp = dk, ep = ek;
                ok = true;
            }
            pd = dk, pe = ek;
        }
        if (!ok)
            return dp; // no bracket: trust the initial point
    }
    return lgv_refine(m, x0, r, dl, el, dp, ep);
}

// Distance along x + d r to where the ray leaves the scene's bounds.
highp float lgv_exit(highp vec3 x, highp vec3 r)
{
    highp vec3 inv = 1.0 / (abs(r) + vec3(1e-12)) * sign(r + vec3(1e-24));
    highp vec3 t1 = (u_bmin - x) * inv, t2 = (u_bmax - x) * inv;
    highp vec3 tf = max(t1, t2);
    return max(min(tf.x, min(tf.y, tf.z)), 0.0);
}

// Where ray x + d r first meets the scene by the maps: hit distance (or -1) and the map it was
// refined on (its texel holds the surface). An ITP with nothing behind it (every impostor of the
// fan behind the photon, or the map empty that way) falls back to where the ray leaves the bounds.
// forced >= 0: that map for both the ITP and the secant, with no footprint skipped at the start
// (trace.comp's exit maps, which do not hold the surface the photon leaves), and the lattice map
// that sees the photon's point for the second march. One code path for both: with a second copy of
// the search for the exit maps, which SIMD lanes taking either path run one after the other, the
// trace pass took 1.19x this one's time (bench_compare, glass, lgv, 6 interleaved runs).
// The photon's own map is chosen once for both marches (llvmpipe evaluates both sides of each `?:`).
// LGV_GLASS 0 (trace.comp: no refractor maps, so no exit maps): never forced.
highp float lgv_trace_from(int forced, highp vec3 x, highp vec3 r, out int map)
{
#if defined(LGV_GLASS) && LGV_GLASS == 0
    forced = -1;
#endif
    int own = lgv_seeing_map(x);
    int m1 = forced >= 0 ? forced : own;
    highp vec3 itp;
    bool ok = true;
    if (u_itp_mode == 1)
        itp = lgv_itp_planar(m1, x, r);
    else
        ok = lgv_itp_angle(m1, x, r, itp);
    highp float exit_d = lgv_exit(x, r);
    highp float d0 = ok ? dot(itp - x, r) : exit_d;
    if (!(d0 < exit_d)) // beyond the bounds (or an empty direction at LGV_FAR)
        d0 = exit_d;
    map = forced >= 0 ? forced : lgv_seeing_map(x + d0 * r);
    highp float start = forced >= 0 ? 1e-4 : 2.0 * length(x - centre[map].xyz) * 2.0 / float(u_res) + 1e-4;
    highp float d = lgv_secant(map, x, r, d0, start, exit_d);
    if (d < 0.0 && (map != m1 || forced >= 0)) {
        // The ITP's map saw nothing in front of the ray before the bounds (the surface it meets is
        // hidden from that map, or too few of its texels cover it): march again on the photon's
        // own map, still at most two maps per ray. Without it 11.6% of glass's photon-like rays
        // that meet a surface left the scene (test_lgv: "no hit at all").
        int m2 = forced >= 0 ? own : m1;
        highp float start1 = 2.0 * length(x - centre[m2].xyz) * 2.0 / float(u_res) + 1e-4;
        d = lgv_secant(m2, x, r, 2.0 * start1, start1, exit_d);
        if (d >= 0.0)
            map = m2;
    }
    return d;
}

highp float lgv_trace(highp vec3 x, highp vec3 r, out int map) { return lgv_trace_from(-1, x, r, map); }
