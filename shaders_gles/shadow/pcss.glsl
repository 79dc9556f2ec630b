// Brute-force PCSS (Fernando 2005; dong-001.md §1.2, the framework reference):
//  1. blocker search over the light's footprint on the near plane,
//     w_i = ((d - Z_n) / d) * S / (2 Z_n tan(theta))   (texture units; ortho: (d - Z_n) S / (2 half_extent)),
//  2. penumbra w_b = ((d - d_b) / d) * S / (2 d_b tan(theta))   (ortho: (d - d_b) S / (2 half_extent)),
//  3. PCF of the depth test over w_b.
// Separate u and v sizes serve rectangular lights (map u, v follow the light's X, Y).
// Samples: stratified PCSS_BLOCKER_N^2 and PCSS_PCF_N^2 grids, jittered per pixel.
#ifndef PCSS_BLOCKER_N
#define PCSS_BLOCKER_N 6
#endif
#ifndef PCSS_PCF_N
#define PCSS_PCF_N 12
#endif
// PCSS_ADAPTIVE 1 (default, #21): the PCF grid shrinks to the kernel's width in texels + 1 a side
// (at most PCSS_PCF_N); 0: always PCSS_PCF_N^2 samples, the brute-force reference as 001 §2.4.
#ifndef PCSS_ADAPTIVE
#define PCSS_ADAPTIVE 1
#endif

// Kernel size (texture units, u and v) of a light seen from depth d through a plane at depth z.
highp vec2 gk_pcss_kernel(highp float d, highp float z)
{
    highp vec2 size = u_shadow_light.xy;
    if (u_shadow_proj.z > 0.5)
        return (d - z) * size / (2.0 * u_shadow_light.z);
    return ((d - z) / d) * size / (2.0 * max(z, 1e-4) * u_shadow_light.z);
}

highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal)
{
    highp vec3 p = gk_shadow_offset(world_pos, world_normal);
    gk_shadow_coord c = gk_shadow_project(p);
    if (!c.inside)
        return 1.0;
    highp vec2 grad = gk_shadow_receiver_gradient(c, p, world_normal);
    highp float bias = 0.5 * gk_shadow_texel_world(c.d);
    highp float texel = 1.0 / u_shadow_light.w;
    // The search area is limited to a quarter of the map: past that the near plane is too close
    // for the sample count to find thin blockers anyway (and the map edge clamps).
    highp vec2 wi = min(gk_pcss_kernel(c.d, u_shadow_proj.x), vec2(0.25));
    wi = max(wi, vec2(texel));
    highp float jitter = gk_shadow_noise();
    highp float sum = 0.0;
    highp float count = 0.0;
    for (int j = 0; j < PCSS_BLOCKER_N; j++) {
        for (int i = 0; i < PCSS_BLOCKER_N; i++) {
            highp vec2 g = (vec2(float(i), float(j)) + fract(jitter + vec2(0.0, 0.5))) / float(PCSS_BLOCKER_N) - 0.5;
            highp float z = gk_shadow_fetch(c.uv + g * wi, c.layer);
            if (z + bias < c.d + dot(grad, g * wi)) {
                sum += z;
                count += 1.0;
            }
        }
    }
    if (count == 0.0)
        return 1.0;
    highp float db = sum / count;
    highp vec2 wb = max(gk_pcss_kernel(c.d, db), vec2(texel));
    // PCF grid: PCSS_PCF_N^2 samples, fewer where the kernel spans fewer texels (#21): n samples
    // a side with n >= the kernel's width in texels + 1 already put a sample within every texel
    // it covers (spacing <= 1 texel), so more only repeat texels; small penumbrae (most pixels of
    // a small light's shadows) then cost n^2 = 4..16 fetches instead of 144.
#if PCSS_ADAPTIVE
    int n = clamp(int(ceil(max(wb.x, wb.y) * u_shadow_light.w)) + 1, 2, PCSS_PCF_N);
#else
    int n = PCSS_PCF_N;
#endif
    highp float lit = 0.0;
    for (int j = 0; j < PCSS_PCF_N; j++) {
        if (j >= n)
            break;
        for (int i = 0; i < PCSS_PCF_N; i++) {
            if (i >= n)
                break;
            highp vec2 g = (vec2(float(i), float(j)) + fract(jitter + vec2(0.5, 0.0))) / float(n) - 0.5;
            highp float z = gk_shadow_fetch(c.uv + g * wb, c.layer);
            lit += c.d + dot(grad, g * wb) <= z + bias ? 1.0 : 0.0;
        }
    }
    return lit / float(n * n);
}
