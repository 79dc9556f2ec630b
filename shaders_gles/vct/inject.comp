// Direct-light injection (thesis §3.1: the voxelization fragment shader's diffuse direct light, here a
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0
// @variant CONSERVATIVE=0 AVERAGE_CAS=1 EMISSIVE=1
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 INJECT_COUNT_FETCHES=1
// separate pass so a moving light re-injects without re-voxelizing). Per occupied voxel:
//   albedo rho, normal n, position x = means over the fragments the voxelizer averaged;
//   E_i  = irradiance from light i at x on n [lux = lm/m^2]:
//            point/spot: I_i(w) * max(n.l, 0) / d^2, I_i = colour * intensity [cd] along the axis,
//                        times the glTF spot falloff, times cos(theta_emit) for one-sided emitters;
//            directional: E_i = colour * illuminance [lux] * max(n.l, 0);
//   V_i  = shadow-map visibility (3x3 PCF), 1 without a shadow map; u_shadow_ambient instead of 0
//          in shadow (0.07 in the thesis code's faithful mode, 0 calibrated); where the light's map
//          does not reach (render_gi.c gives a point light one 160-degree face along its axis), a
//          ray through the voxels' occupancy (not in the thesis, whose spot light's map covers its
//          cone; without it a voxel there was lit through every wall: see voxel_visibility);
//   L_o  = rho / pi * sum_i E_i V_i + L_emit          [nits = cd/m^2]: outgoing diffuse radiance,
// stored premultiplied as (L_o * alpha, alpha), alpha = 1 for an occupied voxel (thesis A.1.3).
// RGBA16F, so HDR radiance is not clipped (the thesis's RGBA8 saturates at 1).
#include "vct/common.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = 1) readonly buffer Scratch { uint s[]; };
#include "vct/voxel_read.glsl"
layout(binding = 0, rgba16f) writeonly uniform highp image3D u_out;

#define MAX_LIGHTS 4
uniform ivec3 u_region_lo;
uniform ivec3 u_region_size;
uniform vec3 u_grid_origin;
uniform float u_voxel_size;
uniform float u_emission_max;        // dequantisation of the emission channels
uniform int u_n_lights;
uniform int u_light_type[MAX_LIGHTS];       // 0 point, 1 spot, 2 directional
uniform vec3 u_light_pos[MAX_LIGHTS];
uniform vec3 u_light_dir[MAX_LIGHTS];       // emission axis
uniform vec3 u_light_radiant[MAX_LIGHTS];   // colour * intensity (cd or lux)
uniform vec2 u_light_spot[MAX_LIGHTS];      // glTF spot: scale, offset
uniform int u_light_lambert[MAX_LIGHTS];    // one-sided rectangle/disc emitter
uniform int u_light_shadow[MAX_LIGHTS];
uniform mat4 u_shadow_vp[MAX_LIGHTS];
uniform vec3 u_shadow_range[MAX_LIGHTS];   // the map's near, far, and 1 if perspective (gk_gi_light)
uniform float u_shadow_ambient;
uniform float u_shadow_bias;               // world units, along the map's axis
uniform highp sampler2D u_shadow0;
uniform highp sampler2D u_shadow1;
uniform highp sampler2D u_shadow2;
uniform highp sampler2D u_shadow3;
// The bench's counting variant (app/gi/vct/vct_work.c): the shadow-map fetches each voxel made,
// added to a buffer once per voxel. Never in the kiosk's frames.
#ifdef INJECT_COUNT_FETCHES
layout(std430, binding = 2) buffer InjectFetches { highp uint shadow_fetches; } inject_counted;
highp uint inject_fetches = 0u;
#define INJECT_COUNT(n) inject_fetches += uint(n)
#else
#define INJECT_COUNT(n)
#endif


float shadow_depth(int i, vec2 uv)   // constant sampler indices only (GLSL ES)
{
    if (i == 0) return textureLod(u_shadow0, uv, 0.0).r;
    if (i == 1) return textureLod(u_shadow1, uv, 0.0).r;
    if (i == 2) return textureLod(u_shadow2, uv, 0.0).r;
    return textureLod(u_shadow3, uv, 0.0).r;
}

// Visibility of the light at lp from world x along the voxel grid (Amanatides & Woo's traversal):
// 0 when the segment crosses an occupied voxel, 1 otherwise. The voxel x lies in is not tested (it
// is x's own surface), nor are the last 1.5 voxels before the light (a fixture around it), nor
// anything outside the grid. For the voxels a light's map does not cover: light-leak's lamp hangs
// 0.8 m under the ceiling with its 160-degree map pointing down, so the dark room's ceiling and the
// upper part of its walls lay outside the map and were injected lit, straight through the wall.
float voxel_visibility(vec3 x, vec3 lp)
{
    vec3 a = (x - u_grid_origin) / u_voxel_size, b = (lp - u_grid_origin) / u_voxel_size;
    vec3 d = b - a;
    float len = length(d);
    if (len < 2.0) return 1.0;
    d /= len;
    ivec3 c = ivec3(floor(a));
    ivec3 stp = ivec3(sign(d));
    vec3 inv = vec3(abs(d.x) > 1e-6 ? 1.0 / abs(d.x) : 1e30, abs(d.y) > 1e-6 ? 1.0 / abs(d.y) : 1e30,
                    abs(d.z) > 1e-6 ? 1.0 / abs(d.z) : 1e30);
    // distance along the ray to the first boundary on each axis
    vec3 t_next = vec3(d.x >= 0.0 ? float(c.x + 1) - a.x : a.x - float(c.x),
                       d.y >= 0.0 ? float(c.y + 1) - a.y : a.y - float(c.y),
                       d.z >= 0.0 ? float(c.z + 1) - a.z : a.z - float(c.z)) * inv;
    for (int k = 0; k < 3 * 256; k++) {
        float t = min(t_next.x, min(t_next.y, t_next.z));
        if (t > len - 1.5) break;
        if (t_next.x <= t_next.y && t_next.x <= t_next.z) { c.x += stp.x; t_next.x += inv.x; }
        else if (t_next.y <= t_next.z) { c.y += stp.y; t_next.y += inv.y; }
        else { c.z += stp.z; t_next.z += inv.z; }
        if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(u_res)))) break;
        if (vct_voxel_occupied(c)) return 0.0;
    }
    return 1.0;
}

// Window depth z of light i's map -> distance along its axis (world): the shadow test compares
// these, since a bias in window depth is a distance that grows with d^2 / near in a perspective map.
float map_distance(int i, float z)
{
    vec3 r = u_shadow_range[i];
    return r.z > 0.5 ? r.x * r.y / (r.y - z * (r.y - r.x)) : r.x + z * (r.y - r.x);
}

// The fraction of light i that reaches x: the light's map (3x3 PCF) where it covers x; elsewhere a
// voxel ray for a point or spot light. A directional light's map covers the scene; a one-sided
// emitter's 160-degree map covers all but its grazing 10 degrees (cos_emit < 0.17), where a ray to its
// centre runs along the ceiling it is set in (cornell: the upper walls' voxels were shadowed, error
// against the one-bounce reference 0.0743 -> 0.0762), so there it stays unshadowed as before.
// The lookup point leaves the surface along its normal by a voxel, or by NORMAL_OFFSET_TEXELS of the
// map's texels at that depth where those are larger (normal-offset shadows): the 3x3 PCF's
// neighbours see a receiver inclined by theta at depths a texel x tan(theta) apart, so an offset
// smaller than a texel shadows the surface itself. At 128^3 on cornell a voxel (4.3 mm) is less than
// a texel of the light's 1024^2 map at the floor (~5.5 mm): the error against the one-bounce ruler rose
// 0.0804 -> 0.0811 with the bias a quarter voxel, before this offset (tests/e2e/gi_bounce.sh).
const float NORMAL_OFFSET_TEXELS = 1.5;
float lit_fraction(int i, vec3 x, vec3 nd)
{
    vec3 xs = x + nd * u_voxel_size;
    vec4 c = u_shadow_vp[i] * vec4(xs, 1.0);
    bool local = u_light_type[i] != 2 && u_light_lambert[i] == 0;
    if (c.w <= 0.0) return local ? voxel_visibility(xs, u_light_pos[i]) : 1.0;
    vec3 ndc = c.xyz / c.w;
    vec3 sc = ndc * 0.5 + 0.5;
    if (any(lessThan(sc.xy, vec2(0.0))) || any(greaterThan(sc.xy, vec2(1.0))))
        return local ? voxel_visibility(xs, u_light_pos[i]) : 1.0;
    vec2 texel = 1.0 / vec2(textureSize(u_shadow0, 0));
    if (i == 1) texel = 1.0 / vec2(textureSize(u_shadow1, 0));
    if (i == 2) texel = 1.0 / vec2(textureSize(u_shadow2, 0));
    if (i == 3) texel = 1.0 / vec2(textureSize(u_shadow3, 0));
    // a texel's width in world units at this depth: the map's x row is P00 (perspective) or
    // 2 / width (orthographic) times the view's unit x axis
    float sx = length(vec3(u_shadow_vp[i][0][0], u_shadow_vp[i][1][0], u_shadow_vp[i][2][0]));
    float texel_world = 2.0 * texel.x / sx * (u_shadow_range[i].z > 0.5 ? c.w : 1.0);
    float offset = NORMAL_OFFSET_TEXELS * texel_world;
    if (offset > u_voxel_size) {
        c = u_shadow_vp[i] * vec4(x + nd * offset, 1.0);
        sc = clamp(c.xyz / c.w * 0.5 + 0.5, 0.0, 1.0);
    }
    float lit = 0.0, dist = map_distance(i, sc.z) - u_shadow_bias;
    INJECT_COUNT(9);
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            lit += dist <= map_distance(i, shadow_depth(i, sc.xy + vec2(dx, dy) * texel)) ? 1.0 : 0.0;
    return lit / 9.0;
}

float visibility(int i, vec3 x, vec3 nd)
{
    if (u_light_shadow[i] == 0) return 1.0;
    float lit = lit_fraction(i, x, nd);
    return lit + (1.0 - lit) * u_shadow_ambient;
}

vec3 irradiance(int i, vec3 x, vec3 n)
{
    if (u_light_type[i] == 2) return u_light_radiant[i] * max(dot(n, -u_light_dir[i]), 0.0);
    vec3 L = u_light_pos[i] - x;
    float d2 = max(dot(L, L), 1e-8);
    L *= inversesqrt(d2);
    float cos_emit = dot(-L, u_light_dir[i]);
    float f = 1.0;
    if (u_light_type[i] == 1) {
        float a = clamp(cos_emit * u_light_spot[i].x + u_light_spot[i].y, 0.0, 1.0);
        f = a * a;
    }
    if (u_light_lambert[i] != 0) f *= max(cos_emit, 0.0);
    return u_light_radiant[i] * f * max(dot(n, L), 0.0) / d2;
}

void main()
{
    ivec3 g = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(g, u_region_size))) return;
    ivec3 c = u_region_lo + g;
    vec3 alb, nrm, frac, emi;
    if (!vct_voxel_read(c, alb, nrm, frac, emi)) {
        // empty, or solid behind a surface (vct_thick): opaque, no radiance of its own
        imageStore(u_out, c, vct_voxel_occupied(c) ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(0.0));
        return;
    }
    // nrm is the MEAN of the fragments' unit normals, not renormalised: for fragments that all face
    // a light, the mean of their n.l is exactly mean(n).l, so a corner voxel (floor + wall) gets the
    // average of its faces' irradiance. Opposite faces in one voxel (a wall thinner than a voxel)
    // cancel to the net orientation; renormalising would light such a voxel fully from whichever
    // side happened to get a few more fragments, and its isotropic radiance would leak through.
    float nl = length(nrm);
    vec3 nd = nl > 1e-6 ? nrm / nl : vec3(0.0);
    vec3 x = u_grid_origin + (vec3(c) + frac) * u_voxel_size;
    vec3 E = vec3(0.0);
    for (int l = 0; l < MAX_LIGHTS; l++) {
        if (l >= u_n_lights) break;
        E += irradiance(l, x, nrm) * visibility(l, x, nd);   // looked up off the surface (lit_fraction)
    }
#ifdef INJECT_COUNT_FETCHES
    if (inject_fetches > 0u)
        atomicAdd(inject_counted.shadow_fetches, inject_fetches);
#endif
    vec3 Lo = alb * E * (1.0 / 3.14159265) + emi * u_emission_max;
    imageStore(u_out, c, vec4(Lo, 1.0));
}
