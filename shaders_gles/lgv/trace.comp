// Photon emission and tracing against the distance cube-maps (seed 002 passes 3-6; research B.1.2),
// one invocation per photon of one light (lgv_trace.c dispatches each light's share of the photons).
// Random numbers: PCG hashes of (photon index, bounce, frame), so a frame is reproducible.
// A photon's path: light -> [glass/mirror]* -> diffuse -> ... Its hits on diffuse surfaces:
//   the first hit after the light is direct light (the renderer's shadow-mapped direct pass has
//     it): not stored;
//   a hit after one or more specular events only (L S+ D) is a caustic photon: appended to the
//     caustic list for the SSLGV (sslgv.comp);
//   every other diffuse hit is injected into the LGV (eq. 4-5) by fixed-point atomics.
// Then Russian roulette on the albedo, cosine scattering. Mirrors reflect (times their colour);
// glass (code >= 128) reflects or refracts by Fresnel with its ior; inside glass the exit is found
// on the refractor map the code named where the photon entered (a map centred in the object,
// Szirmay-Kalos et al. [32]), with total internal reflection keeping the photon inside; a photon
// that has just left glass (refracted out of it or reflected off it) is traced on that glass's exit
// map (u_exit_maps, tracer.glsl lgv_trace_from). A photon on a specular chain (from the light, or off mirrors and glass)
// meets glass where that glass's refractor map says (glass_entry), not where the lattice maps do.
// LGV_PROBE (tests, gk_lgv_probe): no emission; each invocation traces one ray of the Probe buffer
// once and writes where it hit (w = 1) or that it left the scene (w = 0).
// TRACE_COUNT_FETCHES: the bench's counting variant (app/gi/lgv/lgv_work.c): the distance-map texels
// each invocation read (tracer.glsl) and the LGV atomics its injections made, added to TraceWork once.
// Never in the kiosk's frames.
// LGV_GLASS (lgv_photons.c lgv_trace_defines): the refractor maps, 0, 1 or 2 for several (the
// default). Without any the maps code no texel as glass (cubemap.frag), so the glass code is left
// out; with one an exit map's segment cannot meet other glass. Variants, not uniform switches: a
// group of SIMD lanes runs both sides of every branch on llvmpipe, a uniform one too, so code no
// photon needs still cost its time on every bounce (the other-glass test's second trace, the probe's).
// LGV_SEEING_MAPS: gk_lgv_debug.seeing_maps (tracer.glsl lgv_seeing_map).
// @variant -
// @variant TRACE_COUNT_FETCHES
// @variant LGV_GLASS=0
// @variant LGV_GLASS=1
// @variant LGV_GLASS=1 TRACE_COUNT_FETCHES
// @variant LGV_GLASS=0 LGV_SEEING_MAPS
// @variant LGV_PROBE
// @variant LGV_PROBE TRACE_COUNT_FETCHES
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
#ifndef LGV_GLASS
#define LGV_GLASS 2
#endif
#include "lgv/common.glsl"
#include "lgv/tracer.glsl"
struct Caustic { highp vec4 pos; highp vec4 dir; highp vec4 power; };
layout(std430, binding = 1) buffer Lgv { highp int lgv[]; };             // 12 ints per cell: R, G, B x 4 SH
layout(std430, binding = 2) buffer Caustics { highp uint n_caustic; highp uint overflow; highp uint pad0;
                                              highp uint pad1; Caustic caustic[]; };
layout(std430, binding = 3) buffer Stats { highp uint st[]; };           // lgv_internal.h LGV_ST_*
layout(std430, binding = 4) buffer Probe { highp vec4 probe[]; };        // (origin, dir) in, (hit, w) out
#ifdef TRACE_COUNT_FETCHES
layout(std430, binding = 5) buffer TraceWork { highp uint dist_fetches; highp uint lgv_atomics; } trace_counted;
highp uint g_lgv_atomics = 0u;
#endif
uniform int u_photons;        // this light's photons
uniform uint u_first;         // index of its first photon among all lights' (the hash key)
uniform uint u_frame;
uniform int u_light_kind;     // 0 point, 1 spot, 2 rectangle
uniform vec3 u_light_pos;
uniform vec3 u_light_dir;
uniform vec3 u_light_u;       // rectangle half axes (m)
uniform vec3 u_light_v;
uniform vec2 u_cone;          // spot: cos(outer), cos(inner)
uniform vec3 u_power;         // photon power: the light's flux / its photons (rgb)
uniform int u_bounces;        // longest path (surface events)
uniform vec3 u_grid_min;      // LGV
uniform float u_cell;
uniform ivec3 u_dims;
uniform float u_inject_scale; // eq. (4)'s constant with the errata fixed (lgv_internal.h)
uniform float u_fixed;        // fixed-point units per unit of SH coefficient
uniform int u_inject_lobe;    // 1: a clamped cosine lobe around -n, no (Theta, n)+ (gk_lgv_debug.inject_lobe)
uniform int u_caustic_cap;
uniform int u_sphere_normals; // 1 (tests): glass normals from the refractor map's centre, exact on a sphere centred there
uniform int u_refractor_surface; // 1: glass hits placed on its refractor map (enter_glass), normals interpolated there
uniform int u_snap;           // 1: diffuse hits moved onto the map's surface (lgv_internal.h LGV_SNAP_HITS)
uniform int u_plane_hits;     // 1: the LGV's photons injected where the ray meets the map texel's plane (texel_plane_hit)
uniform int u_exit_maps;      // 1: a photon leaving glass is traced on its exit map (tracer.glsl lgv_trace_from)
uniform int u_refractor_entry; // 1: a photon on a specular chain meets glass where its refractor map says (glass_entry)

highp uint g_rng;
highp float rnd()
{
    g_rng = lgv_pcg(g_rng);
    return float(g_rng >> 8) * (1.0 / 16777216.0);
}

highp vec3 any_perp(highp vec3 n) { return abs(n.x) < 0.9 ? normalize(cross(n, vec3(1, 0, 0))) : normalize(cross(n, vec3(0, 1, 0))); }

highp vec3 cosine_dir(highp vec3 n)
{
    highp float u1 = rnd(), u2 = rnd();
    highp float r = sqrt(u1), phi = 6.28318531 * u2;
    highp vec3 t = any_perp(n), b = cross(n, t);
    return normalize(r * cos(phi) * t + r * sin(phi) * b + sqrt(max(0.0, 1.0 - u1)) * n);
}

highp float fresnel(highp float cos_i, highp float eta) // eta = eta_t / eta_i (ref/materials.c)
{
    highp float s2 = (1.0 - cos_i * cos_i) / (eta * eta);
    if (s2 >= 1.0)
        return 1.0;
    highp float ct = sqrt(1.0 - s2);
    highp float rs = (cos_i - eta * ct) / (cos_i + eta * ct), rp = (eta * cos_i - ct) / (eta * cos_i + ct);
    return 0.5 * (rs * rs + rp * rp);
}

void inject(highp vec3 x, highp vec3 theta, highp vec3 n, highp vec3 flux_fr)
{
    // Every surface lies inside the grid (it spans the scene's bounds), so a hit up to a cell outside
    // it is the maps' position error on a surface at the bounds (a box's walls): it belongs to the
    // boundary cell. Dropping it lost about half the photons on glass's and cornell's walls, floor
    // and ceiling, whose hits scatter ~1 mm either side of the surface.
    ivec3 c = ivec3(floor((x - u_grid_min) / u_cell));
    if (any(lessThan(c, ivec3(-1))) || any(greaterThan(c, u_dims)))
        return;
    c = clamp(c, ivec3(0), u_dims - 1);
    // eq. (4) I_j = k (Theta_j, n)+ Phi_p f_r; eq. (5) c += I_j y(-Theta_j). With u_inject_lobe,
    // research B.2.4's A/B: c += k Phi_p f_r lobe(-n), the clamped cosine's SH (pi, 2 pi / 3 per
    // band) around -n. A photon's arrival angle is already in the photons' density on the surface;
    // eq. (4)'s (Theta, n)+ times eq. (7)'s y(-n) weighs it again, cos g (0.25 + 0.75 cos g) (k makes
    // that right only for cosine-distributed arrivals); the lobe read back by eq. (7) on its own
    // surface weighs every photon alike (0.75), the photon density estimate.
    highp vec3 i = u_inject_scale * (u_inject_lobe != 0 ? 1.0 : max(dot(theta, n), 0.0)) * flux_fr;
    highp vec4 y = u_inject_lobe != 0 ? vec4(3.14159265, vec3(2.0943951)) * lgv_sh(-n) : lgv_sh(-theta);
    int base = 12 * ((c.z * u_dims.y + c.y) * u_dims.x + c.x);
    for (int ch = 0; ch < 3; ch++)
        for (int k = 0; k < 4; k++) {
            atomicAdd(lgv[base + 4 * ch + k], int(round(i[ch] * y[k] * u_fixed)));
#ifdef TRACE_COUNT_FETCHES
            g_lgv_atomics++;
#endif
        }
    atomicAdd(st[1], 1u);
}

void emit(out highp vec3 x, out highp vec3 d, out highp vec3 power)
{
    power = u_power;
    if (u_light_kind == 2) {
        x = u_light_pos + (2.0 * rnd() - 1.0) * u_light_u + (2.0 * rnd() - 1.0) * u_light_v;
        d = cosine_dir(u_light_dir);
        return;
    }
    x = u_light_pos;
    highp float cmin = u_light_kind == 1 ? u_cone.x : -1.0;
    highp float z = 1.0 - rnd() * (1.0 - cmin), phi = 6.28318531 * rnd();
    highp float s = sqrt(max(0.0, 1.0 - z * z));
    highp vec3 axis = u_light_kind == 1 ? u_light_dir : vec3(0, 0, 1);
    highp vec3 t = any_perp(axis), b = cross(axis, t);
    d = normalize(s * cos(phi) * t + s * sin(phi) * b + z * axis);
    if (u_light_kind == 1) // the spot's smooth edge, as lights.glsl
        power *= clamp((z - u_cone.x) / max(u_cone.y - u_cone.x, 1e-4), 0.0, 1.0);
}

// Where ray x + t r meets the plane of map m's texel tx (the surface point the texel holds, at its
// stored distance ds along the direction through the texel's centre, and the texel's normal n): the
// LGV photon's place on a flat surface. The snap (u_snap) puts a photon at its own texel's distance
// along the direction to the secant's point, a shell round the map's centre that crosses an oblique
// wall, so the photons on the wall gather in bands of the texels' pattern (64^2: ~1.5 cm on glass's
// walls, a 48-cell cell is 1.25 cm); the secant's own point lies up to a centimetre beyond the floor
// (README lgv). `fallback` when the ray grazes the plane, or the plane's point lies farther than two
// texel footprints from the secant's point `hit` or outside the scene's bounds (the texel holds
// another surface, at an edge: inside a box the other wall's plane is met beyond the box; 162 of
// glass's 295,181 photons at 48 cells were dropped more than a cell outside the grid without that).
highp vec3 texel_plane_hit(int m, ivec3 tx, highp float ds, highp vec3 n, highp vec3 x, highp vec3 r, highp vec3 hit,
                           highp vec3 fallback)
{
    int f = tx.z - 6 * m;
    highp vec2 uv = (vec2(tx.xy) + 0.5) / float(u_res) * 2.0 - 1.0;
    highp vec3 p = centre[m].xyz + ds * normalize(lgv_face_w(f) + uv.x * lgv_face_u(f) + uv.y * lgv_face_v(f));
    highp float den = dot(r, n);
    if (abs(den) < 0.05)
        return fallback;
    highp vec3 q = x + (dot(p - x, n) / den) * r;
    bool inside = all(greaterThanEqual(q, u_bmin)) && all(lessThanEqual(q, u_bmax));
    return inside && distance(q, hit) < 4.0 * ds / float(u_res) ? q : fallback;
}

// The exit of a photon inside glass at x going r: on the refractor map of the glass it is in (`glass`,
// named by the material code of the surface it entered), marched from x until behind the object's
// surface, then secant. Returns the distance or -1.
highp float trace_inside(int glass, highp vec3 x, highp vec3 r, out int map)
{
    map = glass;
    highp vec3 x0 = x - centre[map].xyz;
    highp float reach = 2.0 * centre[map].w, step = reach / 16.0; // the object's diameter in 16 steps
    highp float dl = 1e-4, el = lgv_err(map, x0, r, dl);
    for (int k = 1; k <= 16; k++) {
        highp float dp = step * float(k), ep = lgv_err(map, x0, r, dp);
        if (ep >= 0.0)
            return lgv_refine(map, x0, r, dl, el, dp, ep);
        dl = dp, el = ep;
    }
    return -1.0;
}

// The chord [t0, t1] of ray x + t r through refractor map m's bounding sphere (centre, radius w);
// false when the line misses it.
bool refractor_chord(int m, highp vec3 x, highp vec3 r, out highp float t0, out highp float t1)
{
    highp vec3 oc = x - centre[m].xyz;
    highp float b = dot(oc, r), disc = b * b - (dot(oc, oc) - centre[m].w * centre[m].w);
    t0 = -b - sqrt(max(disc, 0.0)), t1 = -b + sqrt(max(disc, 0.0));
    return disc > 0.0;
}

// Whether ray x + d r passes through the bounding sphere of a refractor other than `own` before
// distance d: the exit maps leave all glass out, so such a segment is traced on the lattice maps.
bool other_glass_before(int own, highp vec3 x, highp vec3 r, highp float d)
{
    for (int m = u_n_maps; m < u_n_maps + u_n_refractors; m++) {
        highp float t0, t1;
        if (m != own && refractor_chord(m, x, r, t0, t1) && t0 < d && t1 > 0.0)
            return true;
    }
    return false;
}

// Where ray x + d r enters the glass of refractor map m near a lattice map's hit on it at distance d:
// the first outside-to-inside change of the refractor map's error in [d - 2w, d + w] (w: two of the
// lattice map's texel footprints there), refined by the secant. -1 when the ray does not enter the
// object there: the lattice maps see glass from afar, a few texels, and their coarse copy of it lies
// up to a footprint outside it, so a photon that has just left the glass met that copy again at once
// (glass, 0.26M photons: 3,944 of the 5,093 glass hits after leaving glass lay within 2 cm).
highp float enter_glass(int m, highp vec3 x, highp vec3 r, highp float d, highp float w)
{
    highp vec3 x0 = x - centre[m].xyz;
    highp float dl = max(d - 2.0 * w, 0.0), el = lgv_err(m, x0, r, dl);
    if (el < 0.0)
        return dl; // already inside at the window's start: the entry is no later
    highp float step = (d + w - dl) / 24.0;
    for (int k = 0; k < 24; k++) {
        highp float dp = dl + step, ep = lgv_err(m, x0, r, dp);
        if (ep < 0.0)
            return lgv_refine(m, x0, r, dl, el, dp, ep);
        dl = dp, el = ep;
    }
    return -1.0;
}

// Where ray x + r t (t < d; d < 0: no hit) first enters the glass of a refractor other than `skip`,
// found on the refractor maps themselves: over the ray's chord through the object's bounding
// sphere, the first outside-to-inside change of the refractor map's error in 32 steps, refined by
// the secant; -1 when it enters none. The lattice maps see a glass sphere from afar, a few texels
// each, and a ray aimed at it passed through their coarse copy (glass, 0.26M photons: 886 of the
// 3,229 light photons aimed at the sphere landed on a diffuse surface behind it, the rim's light
// and the caustic's with it).
highp float glass_entry(int skip, highp vec3 x, highp vec3 r, highp float d, out int glass)
{
    highp float best = -1.0;
    glass = -1;
    for (int m = u_n_maps; m < u_n_maps + u_n_refractors; m++) {
        highp float t0, t1;
        if (m == skip || !refractor_chord(m, x, r, t0, t1))
            continue;
        highp vec3 oc = x - centre[m].xyz;
        t0 = max(t0, 0.0);
        if (d >= 0.0)
            t1 = min(t1, d);
        if (t1 <= t0 || (best >= 0.0 && t0 >= best))
            continue;
        highp float step = (t1 - t0) / 32.0, dl = t0, el = lgv_err(m, oc, r, dl);
        for (int k = 1; k <= 32 && el >= 0.0; k++) {
            highp float dp = t0 + step * float(k), ep = lgv_err(m, oc, r, dp);
            if (ep < 0.0) {
                best = lgv_refine(m, oc, r, dl, el, dp, ep), glass = m;
                break;
            }
            dl = dp, el = ep;
        }
    }
    return best;
}

void trace_invocation()
{
    uint id = gl_GlobalInvocationID.x;
    if (int(id) >= u_photons)
        return;
#ifdef LGV_PROBE
    int map;
    highp vec3 o = probe[2u * id].xyz, r = normalize(probe[2u * id + 1u].xyz);
    highp float d = lgv_trace(o, r, map);
    probe[2u * id] = d >= 0.0 ? vec4(o + d * r, 1.0) : vec4(0.0);
#else
    g_rng = lgv_pcg((u_first + id) * 9781u + u_frame * 6271u + 1u);
    highp vec3 x, r, flux;
    emit(x, r, flux);
    bool specular_only = true, inside = false;
    int events = 0, left_glass = -1; // the refractor map of the glass the photon has just left
    int in_glass = -1;               // ... and of the glass it is in (while inside)
    for (int bounce = 0; bounce < u_bounces; bounce++) {
        int map;
        // A photon that has just left glass is traced on its exit map, centred in the glass with the
        // glass left out ([32]'s environment map of the refractor): the lattice maps see a glass
        // sphere as a solid, and the floor under it, hidden from every centre outside it, is where
        // the sphere focuses the light of the room above; those photons landed on what the lattice
        // maps saw beside the sphere. Exact for convex glass, which the photon cannot meet again;
        // when another glass object lies on the way the segment is traced on the lattice maps.
#if LGV_GLASS > 0
        int exit_map = left_glass >= 0 ? left_glass + u_n_refractors : -1;
        highp float d = inside ? trace_inside(in_glass, x, r, map) : lgv_trace_from(exit_map, x, r, map);
#if LGV_GLASS > 1
        if (exit_map >= 0 && map == exit_map && d >= 0.0 && other_glass_before(left_glass, x, r, d))
            d = lgv_trace(x, r, map);
#endif
        bool on_refractor = false; // the hit was found on its refractor map (glass_entry)
        if (u_refractor_entry == 1 && specular_only && !inside) {
            int glass;
            highp float dg = glass_entry(left_glass, x, r, d, glass);
            if (dg >= 0.0)
                d = dg, map = glass, on_refractor = true;
        }
#else
        highp float d = lgv_trace(x, r, map);
#endif
        left_glass = -1;
        atomicAdd(st[0], 1u);
        if (d < 0.0) {
            atomicAdd(st[3], 1u);
            return; // left the scene
        }
        highp vec3 hit = x + d * r;
        ivec3 tx = lgv_texel(map, hit - centre[map].xyz);
        highp vec3 n = normalize(texelFetch(u_nrm, tx, 0).xyz * 2.0 - 1.0);
        highp vec4 alb = texelFetch(u_alb, tx, 0);
        int code = int(alb.a * 255.0 + 0.5);
#if LGV_GLASS > 0
        int refractor = u_n_maps + (code - 128) / 32; // code 128 + 32 r + q: refractor map r, ior 1 + 0.05 q
        if (code >= 128 && refractor < u_n_maps + u_n_refractors) {
            // Glass is seen from afar by the lattice maps (a sphere of glass: a few texels each),
            // whose nearest texel's place and normal scatter the refraction: its refractor map,
            // centred in it, holds the same surface finely and smoothly (u_refractor_surface).
            if (u_refractor_surface == 1 && !inside && !on_refractor) {
                highp float w = 4.0 * length(hit - centre[map].xyz) / float(u_res);
                highp float de = enter_glass(refractor, x, r, d, w);
                if (de < 0.0) {
                    x = hit + r * 1e-4; // not the object: trace on (a segment, no event)
                    continue;
                }
                hit = x + de * r;
            }
            if (u_sphere_normals == 1)
                n = normalize(hit - centre[refractor].xyz);
            else if (u_refractor_surface == 1)
                n = lgv_normal_smooth(refractor, hit - centre[refractor].xyz);
        }
        bool front = dot(n, r) < 0.0;
        highp vec3 ns = front ? n : -n; // facing the incoming photon
        if (code >= 128) {
            // glass: entering when the photon meets the outside of the surface
            highp float ior = 1.0 + 0.05 * float((code - 128) % 32);
            bool entering = !inside;
            highp float eta = entering ? ior : 1.0 / ior;
            highp float ci = abs(dot(r, ns));
            if (rnd() < fresnel(ci, eta)) {
                r = reflect(r, ns);
            } else {
                r = refract(r, ns, 1.0 / eta);
                flux *= alb.rgb;
                inside = entering;
                in_glass = refractor;
            }
            if (!inside && u_exit_maps == 1 && refractor < u_n_maps + u_n_refractors)
                left_glass = refractor;
            x = hit + r * 1e-4;
            events++;
            continue;
        }
#else
        highp vec3 ns = dot(n, r) < 0.0 ? n : -n; // facing the incoming photon
#endif
        if (code == 1) {
            r = reflect(r, ns);
            flux *= alb.rgb;
            x = hit + ns * 1e-4;
            events++;
            continue;
        }
        // diffuse hit: f_r = albedo / pi. The photon lands where the map's texel says the surface
        // is (the impostor's point: its stored distance along the direction from the map's
        // centre): the secant stops within its last bracket, which on a ray meeting the floor
        // under glass's refractor can lie a centimetre beyond it, and the SSLGV refuses a photon
        // farther than h (a few mm) from the visible surface (glass at 0.26M photons: 34% of the
        // caustic photons were refused, 6% with the snap). u_snap = 0: the secant's point.
        highp float footprint = 0.0; // how far from the surface the map places the photon (m)
        highp vec3 lgv_hit = hit;    // where an LGV photon is injected
        if (u_snap == 1 || u_plane_hits == 1) {
            highp vec3 dc = hit - centre[map].xyz;
            highp float ds = lgv_dist(map, dc, 0);
            if (ds < 0.5 * LGV_FAR) {
                highp vec3 snapped = centre[map].xyz + normalize(dc) * ds;
                lgv_hit = u_snap == 1 ? snapped : hit;
                if (u_plane_hits == 1)
                    lgv_hit = texel_plane_hit(map, tx, ds, n, x, r, hit, lgv_hit);
                if (u_snap == 1)
                    hit = snapped, footprint = 2.0 * ds / float(u_res);
            }
        }
        highp vec3 fr = alb.rgb * 0.31830989;
        if (events > 0 && specular_only) {
            uint slot = atomicAdd(n_caustic, 1u);
            if (int(slot) < u_caustic_cap)
                caustic[slot] = Caustic(vec4(hit, footprint), vec4(-r, 0.0), vec4(flux * fr, 0.0));
            else
                atomicAdd(overflow, 1u);
            atomicAdd(st[2], 1u);
        } else if (events > 0) {
            inject(lgv_hit, -r, ns, flux * fr);
        }
        // Russian roulette on the albedo, then a cosine-distributed bounce
        highp float p = min(max(alb.r, max(alb.g, alb.b)), 0.95);
        if (rnd() >= p)
            return;
        flux *= alb.rgb / p;
        r = cosine_dir(ns);
        x = hit + ns * 1e-4;
        specular_only = false;
        events++;
    }
#endif
}

void main()
{
    trace_invocation();
#ifdef TRACE_COUNT_FETCHES
    atomicAdd(trace_counted.dist_fetches, g_dist_fetches);
    atomicAdd(trace_counted.lgv_atomics, g_lgv_atomics);
#endif
}
