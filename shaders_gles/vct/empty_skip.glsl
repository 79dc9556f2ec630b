// Algorithm 1 of the thesis (§3.3; summary A.2.7), empty-space skipping for narrow cones, with the
// summary's errata fixed: the samples are taken at apex + dst d (not at a position that grows by dst
// every step), accumulation is cone_lib.glsl's premultiplied front-to-back one, and the minimum step
// is one voxel. When a sample is empty (alpha < SKIP_EPS) the largest empty voxel of the mip pyramid
// that holds the sample point is found top-down (thesis code: from level depth - 3 down, "appears to
// be faster" than bottom-up), and the cone jumps to that voxel's back planes (a ray/AABB slab test,
// half a voxel past them, thesis code): dst += max(step, skip). Only cones narrower than
// SKIP_MAX_APERTURE skip (the thesis: the specular cone, where it pays, and the shadow cone; the
// diffuse cones were slower with it, Table 3). EMPTY_SKIP=0: off (knob vct_skip).
// Known artefact (Fig. 18a): an empty voxel can still give non-empty trilinear samples near its
// faces, which a skip jumps over, so reflections and shadow edges may show the grid.
#ifndef EMPTY_SKIP
#define EMPTY_SKIP 0
#endif
#if EMPTY_SKIP
#define SKIP_EPS 0.01          // thesis code's epsilon
#define SKIP_MAX_APERTURE 0.3  // thesis code: apertures below 0.3 only
uniform int u_skip_top;        // the map level the search starts at: log2(res) - 3 (thesis code), within the map

// Opacity of cell c of map level L: level 0 is the isotropic u_vox0 (also with ANISO_LEVEL0, where
// every view has its opacity); above it, the +X directional view (any view is empty exactly where its
// children all are), the lower half of u_voxp0's level L - DIR_FIRST_LOD.
float skip_cell_alpha(ivec3 c, int L)
{
#if ISO_MIPS
    return texelFetch(u_vox0, c, L).a;
#else
    if (L == 0) return texelFetch(u_vox0, c, 0).a;
    return texelFetch(u_voxp0, c, L - int(DIR_FIRST_LOD)).a;
#endif
}

// findLargestEmptyParentVoxel + distanceToBackPlanes: the distance along d from p (voxel space) past
// the back planes of the largest empty voxel holding p; 0 when even the level-0 voxel is occupied.
float empty_skip(vec3 p, vec3 d)
{
    for (int L = u_skip_top; L >= 0; L--) {
        float n = u_res_f * exp2(-float(L));                 // cells per axis at level L
        vec3 cell = clamp(floor(p * n), vec3(0.0), vec3(n - 1.0));
        if (skip_cell_alpha(ivec3(cell), L) >= SKIP_EPS) continue;
        vec3 lo = cell / n, hi = (cell + 1.0) / n;
        vec3 back = mix(lo, hi, step(0.0, d));              // the planes the ray leaves through
        vec3 t = vec3(1e30);
        if (abs(d.x) > 1e-6) t.x = (back.x - p.x) / d.x;
        if (abs(d.y) > 1e-6) t.y = (back.y - p.y) / d.y;
        if (abs(d.z) > 1e-6) t.z = (back.z - p.z) / d.z;
        float t_far = min(t.x, min(t.y, t.z));
        return max(t_far + 0.5 / u_res_f, 1.0 / u_res_f);
    }
    return 0.0;
}
#endif
