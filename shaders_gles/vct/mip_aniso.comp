// Anisotropic pre-integration (thesis §3.2, equations 3.1/3.2 as corrected in summary A.2.2): one
// @variant CONSERVATIVE=1 AVERAGE_CAS=0 EMISSIVE=0 DIRECTIONAL_INJECTION=0 PROJECTED_COVERAGE=1
// @variant CONSERVATIVE=1 AVERAGE_CAS=1 EMISSIVE=1 DIRECTIONAL_INJECTION=1 PROJECTED_COVERAGE=0
// direction per dispatch (a minimum-spec GLES 3.1 has only 4 compute image units). For each of the
// 4 front/back voxel pairs along the direction's axis, composite with "over" on premultiplied
// colour,  C' = C1 + (1 - a1) C2,  a' = a1 + (1 - a1) a2  (front voxel 1), and average the 4.
// Direction index 0..5 = +X,-X,+Y,-Y,+Z,-Z; "+X" treats the child with the larger x as the front,
// i.e. it is the volume as seen from the +X side, sampled by cones travelling towards -X.
//
// DIRECTIONAL_INJECTION=1 (not in the thesis; option gk_vct_options.directional_injection, the
// default with one bounce): when level 1 is built from level 0, a level-0 voxel shows its radiance
// to a direction's view by how its mean surface normal faces that view's viewer, smoothstep(-0.1,
// 0.2, cos): all of it from the front, none from behind, 0.26 of it edge-on; its opacity to all
// views. Isotropic views (thesis) make a bright patch light what sees it edge-on or from behind
// through the layer of voxels it is: cornell-spot's box face (39 nits) over-lit the red wall 4x and
// the ceiling 1.5x (vct's indirect light 1.64x the one-bounce reference's, rel. RMSE 0.486 where
// direct light alone is 0.364). Dark edge-on (smoothstep(0, 0.2), the option before issue 11) over-
// corrects: a cone crossing a wall obliquely mixes its lit face-on view with the dark edge-on one
// and the Cornell box keeps 0.69 of its indirect light (0.085). Measured (160x120, 64^3, against
// the one-bounce references) with the edge-on share 0 / 0.26 / 0.5 / 1 (isotropic):
// cornell 0.085 / 0.074 / 0.069 / 0.080, cornell-spot 0.342 / 0.355 / 0.372 / 0.486; 0.26 is the
// largest share with which vct beats none on cornell-spot. A lone lit plane lights itself through
// isotropic coarse levels (74% of its direct light without the footprint clamp, tests/gpu/test_vct.c).
// Level 0 stays isotropic as in the thesis (§4, Fig. 16), unless vct_level0=aniso (not in the
// thesis): then the chains start at level 0, and its six views are made first (u_views_only: each
// voxel as fetch() shows it to the view, nothing composited), so the directional weighting above
// acts at level 0 as well. A wall thinner than a voxel whose lit and dark faces fall in neighbouring
// voxels then shows its lit voxel dark from the far side, where the isotropic level 0 showed a
// trilinear sample between the two voxels half the lit one's light (tests/e2e/vct_leak.sh).
#include "vct/common.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0, rgba16f) readonly uniform highp image3D u_src;
layout(binding = 1, rgba16f) writeonly uniform highp image3D u_dst;
layout(std430, binding = 1) readonly buffer Scratch { uint s[]; };
uniform int u_dir;
uniform int u_dst_res;
// The directional chains are packed two views per axis texture (vct_internal.h voxp): views +X, +Y,
// +Z in the lower half of each level's depth, views -X, -Y, -Z in the upper half mirrored in z, so
// the two halves meet at the grid's z = 1 edge in both (see dir_sample in vct/cone_lib.glsl).
uniform int u_half;
ivec3 packed_at(ivec3 c, int n)   // voxel c of a level with n voxels a side -> its texel
{
    return u_half == 0 ? c : ivec3(c.xy, 2 * n - 1 - c.z);
}
uniform bool u_from_level0;
uniform bool u_views_only;   // level 0's views: u_dst_res = u_res, one voxel to one texel
vec4 over(vec4 f, vec4 b) { return f + (1.0 - f.a) * b; }

vec3 view_dir(int dir)   // where the viewer of this view stands
{
    vec3 v = vec3(dir / 2 == 0 ? 1.0 : 0.0, dir / 2 == 1 ? 1.0 : 0.0, dir / 2 == 2 ? 1.0 : 0.0);
    return (dir % 2) == 0 ? v : -v;
}

// The mean of the fragments' unit normals in level-0 voxel c (length < 1 where they disagree).
vec3 mean_normal(ivec3 c)
{
    int i = vox_index(c), N = vox_count();
#if AVERAGE_CAS
    uint q = s[CH_NRM * N + i];
    return vec3(float(q & 0xFEu), float((q >> 8) & 0xFEu), float((q >> 16) & 0xFEu)) / 255.0 * 2.0 - 1.0;
#else
    uint cnt = max(s[CH_COUNT * N + i] & ~SOLID_BIT, 1u);   // a solid-only voxel: no normal
    return vec3(float(int(s[(CH_NRM + 0) * N + i])), float(int(s[(CH_NRM + 1) * N + i])),
                float(int(s[(CH_NRM + 2) * N + i]))) / (127.0 * float(cnt));
#endif
}

vec4 fetch(ivec3 c)
{
    vec4 v = imageLoad(u_src, u_from_level0 ? c : packed_at(c, 2 * u_dst_res));
#if !AVERAGE_CAS
    // vct_thick's solid voxels (no fragment, only the mark) are opaque at level 0 alone: the coarse
    // levels are made as if they were empty. In them the solid layer behind every single-sided wall
    // made the views along the wall opaque over two voxels, not one, and cones grazing the walls lost
    // light: cornell 0.0743 -> 0.0822, furnace 0.328 -> 0.354 against the one-bounce references
    // (1.5 voxels thick, 64^3; level 0 alone 0.0744, 0.328). voxelize.comp says why level 0 has them.
    if (u_from_level0 && !u_views_only && s[CH_COUNT * vox_count() + vox_index(c)] == SOLID_BIT) return vec4(0.0);
#endif
#if DIRECTIONAL_INJECTION || PROJECTED_COVERAGE
    if (u_from_level0 && v.a > 0.0) {
        vec3 n = mean_normal(c);
        float l = length(n);
        if (l > 1e-6) {
            float cos_view = dot(n / l, view_dir(u_dir));
#if DIRECTIONAL_INJECTION
            v.rgb *= smoothstep(-0.1, 0.2, cos_view);  // behind: dark; edge-on (cos 0): 0.26
#endif
#if PROJECTED_COVERAGE
            v *= mix(1.0, abs(cos_view), min(l, 1.0));
#endif
        }
    }
#endif
    return v;
}
void main()
{
    ivec3 d = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(d, ivec3(u_dst_res)))) return;
    if (u_views_only) {
        imageStore(u_dst, packed_at(d, u_dst_res), fetch(d));
        return;
    }
    ivec3 s = 2 * d;
    int axis = u_dir / 2;
    bool pos = (u_dir % 2) == 0;
    ivec3 step_ax = ivec3(axis == 0 ? 1 : 0, axis == 1 ? 1 : 0, axis == 2 ? 1 : 0);
    vec4 acc = vec4(0.0);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            ivec3 a = axis == 0 ? s + ivec3(0, i, j) : (axis == 1 ? s + ivec3(i, 0, j) : s + ivec3(i, j, 0));
            vec4 lo = fetch(a), hi = fetch(a + step_ax);
            acc += pos ? over(hi, lo) : over(lo, hi);
        }
    imageStore(u_dst, packed_at(d, u_dst_res), acc * 0.25);
}
