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
//          in shadow (0.07 in the thesis code's faithful mode, 0 calibrated);
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
uniform float u_shadow_ambient;
uniform float u_shadow_bias;
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

float visibility(int i, vec3 x)
{
    if (u_light_shadow[i] == 0) return 1.0;
    vec4 c = u_shadow_vp[i] * vec4(x, 1.0);
    if (c.w <= 0.0) return 1.0;
    vec3 ndc = c.xyz / c.w;
    vec3 sc = ndc * 0.5 + 0.5;
    if (any(lessThan(sc.xy, vec2(0.0))) || any(greaterThan(sc.xy, vec2(1.0)))) return 1.0;
    vec2 texel = 1.0 / vec2(textureSize(u_shadow0, 0));
    if (i == 1) texel = 1.0 / vec2(textureSize(u_shadow1, 0));
    if (i == 2) texel = 1.0 / vec2(textureSize(u_shadow2, 0));
    if (i == 3) texel = 1.0 / vec2(textureSize(u_shadow3, 0));
    float lit = 0.0;
    INJECT_COUNT(9);
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            lit += (sc.z - u_shadow_bias <= shadow_depth(i, sc.xy + vec2(dx, dy) * texel)) ? 1.0 : 0.0;
    lit /= 9.0;
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
    if (!vct_voxel_read(c, alb, nrm, frac, emi)) { imageStore(u_out, c, vec4(0.0)); return; }
    // nrm is the MEAN of the fragments' unit normals, not renormalised: for fragments that all face
    // a light, the mean of their n.l is exactly mean(n).l, so a corner voxel (floor + wall) gets the
    // average of its faces' irradiance. Opposite faces in one voxel (a wall thinner than a voxel)
    // cancel to the net orientation; renormalising would light such a voxel fully from whichever
    // side happened to get a few more fragments, and its isotropic radiance would leak through.
    float nl = length(nrm);
    vec3 nd = nl > 1e-6 ? nrm / nl : vec3(0.0);
    vec3 x = u_grid_origin + (vec3(c) + frac) * u_voxel_size;
    vec3 xs = x + nd * u_voxel_size;   // shadow lookups one voxel off the surface (no self-shadowing)
    vec3 E = vec3(0.0);
    for (int l = 0; l < MAX_LIGHTS; l++) {
        if (l >= u_n_lights) break;
        E += irradiance(l, x, nrm) * visibility(l, xs);
    }
#ifdef INJECT_COUNT_FETCHES
    if (inject_fetches > 0u)
        atomicAdd(inject_counted.shadow_fetches, inject_fetches);
#endif
    vec3 Lo = alb * E * (1.0 / 3.14159265) + emi * u_emission_max;
    imageStore(u_out, c, vec4(Lo, 1.0));
}
