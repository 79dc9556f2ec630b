/* Voxel cone tracing (DESIGN §5 `vct`; Dinse 2015, seed 003; engineering summary
 * research/vct-003-grid-photon-002.md Part A). The method itself is `gk_gi_vct` (gi.h); this header
 * adds what tests and the lead need beyond the interface: the switches between the thesis-faithful
 * behaviour and the improvements, work counters, and the memory formula.
 *
 * Passes per frame (names as in the thesis, timing names in gk_pass_times):
 *   vct_voxelize  compute voxelizer over the triangle SSBO -> scratch ("voxel G-buffer": albedo,
 *                 normal, position, emission sums + count). Static geometry once; moving (animated)
 *                 nodes re-voxelized in their dirty region.
 *   vct_inject    direct light from the lights (with their shadow maps; a ray through the voxels where
 *                 a point or spot light's map does not reach) -> level 0 radiance RGBA16F.
 *                 Runs when geometry or lights change.
 *   vct_mips      six-direction anisotropic pre-integration (eq. 3.1/3.2) or glGenerateMipmap (iso);
 *                 with vct_level0=aniso first the six views of level 0 (not in the thesis).
 *   vct_bounce    with vct_bounces=2 (not in the thesis): the diffuse cones from every voxel add its
 *                 once-bounced light to level 0, and the mips are rebuilt (after injection only).
 *   vct_trace     diffuse cones (+AO) and the specular cone at trace_scale resolution.
 *   vct_compose   joint bilateral upsampling + additive composition into frame->hdr_fbo. */
#ifndef GK_VCT_H
#define GK_VCT_H

#include <stdbool.h>

#include "../gi.h"

extern const gk_gi_method gk_gi_vct;

typedef struct gk_vct_options {
    bool conservative;        /* true (default): 26-separating voxelization; false: thin, as the thesis's rasterizer */
    bool average_cas;         /* false (default): fixed-point sums, bit-exact; true: thesis CAS moving average */
    bool faithful_weights;    /* thesis code cone weights (1 / 0.607) and composition (alpha_GI 0.75, AO);
                                 false (default): calibrated weights W_k/pi, rho/pi composition */
    bool axis_weight_sq;      /* d^2 axis weights (calibrated) instead of the thesis's |d| */
    bool opacity_correction;  /* step-length opacity correction (not in the thesis) */
    bool directional_injection; /* level-1 views show a voxel's radiance by how its normal faces their viewer:
                                   none from behind, 0.26 edge-on (not in the thesis; mip_aniso.comp).
                                   true (default, one bounce only); false (thesis): lit from every side. */
    bool projected_coverage;  /* true: a level-0 voxel enters a directional view of level 1 with its
                                 surface's projected area, |n.axis| of its mean normal n, as opacity and
                                 radiance weight (a wall seen edge-on covers nothing; not in the thesis).
                                 false (default): every occupied voxel is opaque from every side. Measured
                                 with isotropic views at 64^3: cornell vs one bounce 0.080 -> 0.070,
                                 cornell-spot 0.486 -> 0.410, but cones crossing a wall obliquely see it
                                 partly transparent: test_vct_leak's partition 3.9% -> 12.0%, so off */
    bool clip_cones;          /* true (default): stop every cone at the volume border; false (thesis code):
                                 only cones narrower than 0.3 stop, wide ones sample clamped edge texels */
    float footprint_clamp;    /* c > 0 (default 1/3): a sample's diameter is at most c x its height above
                                 the receiver's tangent plane, so coarse samples never reach the receiver's
                                 own surface (not in the thesis); 0: off (thesis) */
    int specular;             /* -1 (default): when the scene has specular materials; 0 off; 1 on */
    float apex_offset;        /* voxels along the normal, thesis code 2.5 */
    float max_dist;           /* voxel-space units, thesis code sqrt(3) */
    float ao_lambda;          /* AO falloff, thesis code 725 */
    float spec_aperture;      /* thesis code 0.158 (9 degrees) */
    float shadow_ambient;     /* in-shadow factor during injection: 0 (default), thesis code 0.07 */
    float grid_offset[3];     /* shift of the grid against the scene, in voxels (flicker tests) */
} gk_vct_options;

void gk_vct_default_options(gk_vct_options *o);
/* The thesis as published (code defaults): thin voxelization, CAS moving average, cone weights
   1 / 0.607 with alpha_GI 0.75 and AO in the composition, |d| axis weights, isotropic radiance in
   every view, in-shadow factor 0.07. */
void gk_vct_thesis_options(gk_vct_options *o);
/* Applies options; the next render re-voxelizes. self: what gk_gi_vct.create returned. */
void gk_vct_set_options(void *self, const gk_vct_options *o);

typedef struct gk_vct_stats {
    int voxelize_runs, inject_runs, mip_runs, trace_runs;
    int bounce_runs;                /* vct_bounces=2 passes */
    long last_voxelized_region;     /* voxels in the last voxelized region */
    unsigned long last_trace_steps; /* cone samples of the last trace pass (all pixels, all cones) */
    unsigned long last_shadow_steps; /* shadow-cone samples of the last frame's masks (all lights, all pixels) */
    int shadow_runs;                /* shadow-cone passes (one per light and frame) */
    unsigned long last_trace_fine_steps; /* of those, the samples below lod 1 (aniso: 4 fetches, not 3) */
    unsigned long last_trace_pixels;     /* pixels that traced cones (not background) */
    bool aniso;                     /* the mips in use: vct_mips=aniso */
    bool aniso_level0;              /* vct_level0=aniso: six directional views at level 0 too */
    int res;                        /* level-0 resolution in use */
    float grid_origin[3], grid_size, voxel_size;  /* world */
    int trace_w, trace_h;
    int n_triangles, n_dynamic_triangles;
} gk_vct_stats;

void gk_vct_get_stats(const void *self, gk_vct_stats *s);

/* The trace's work (app/gi/vct/vct_work.c, #21). Fetches of a trace of `fine` samples below lod 1
 * and `coarse` ones from lod 1 on: aniso 4 and 3 a sample (level 0 blended with the three views a
 * direction sees, then the views alone), iso 1; aniso with aniso_level0 3 and 3 (the views alone
 * from level 0 on). */
double gk_vct_trace_fetches(bool aniso, bool aniso_level0, double fine, double coarse);
/* The anisotropic mips' image loads (vct/mip_aniso.comp): 8 per texel of each of the six views,
 * levels 1 .. levels-1 of a res³ map, and with aniso_level0 one per texel of each view at level 0
 * (the views made from the isotropic injection; the voxels' mean normals the views read from the
 * scratch buffer are not counted). */
double gk_vct_mip_fetches(int res, int levels, bool aniso_level0);
/* One cone in open space: only its length stops it (no opacity, no volume border), over the
 * receiver's own tangent plane (cos_n: the cone's cosine to its normal), as vct/cone_lib.glsl steps. */
typedef struct gk_vct_cone_model {
    int res;
    float aperture, step_mul, apex_offset, max_dist, footprint_clamp, cos_n;
} gk_vct_cone_model;
void gk_vct_cone_samples(const gk_vct_cone_model *m, bool aniso, int *fine, int *coarse);
/* The samples one traced pixel's diffuse cone set takes in open space (no specular cone): the sum
 * of gk_vct_cone_samples over the set of `cones` at options o. */
void gk_vct_trace_model(int cones, int res, float step_mul, bool aniso, const gk_vct_options *o, double *fine,
                        double *coarse);

/* Scratch channels per voxel: 10 (count, albedo, normal, position) + 3 with emissive surfaces. */
int gk_vct_channels(bool emissive);
/* GPU bytes held at a budget: scratch SSBO + level-0 RGBA16F (with its mip chain in iso mode) +
 * six directional RGBA16F chains from level 1 (aniso), from level 0 with aniso_level0 (vct_level0=aniso;
 * the isotropic level 0 stays: the injection's target) + two RGBA16F trace targets + triangles. */
long gk_vct_memory_formula(int res, bool aniso, bool aniso_level0, int channels, int trace_w, int trace_h,
                           int n_triangles);

/* GPU bytes the second bounce adds (vct_bounces=2): a second level 0 RGBA16F (with its mip chain in
 * iso mode), the one the bounce pass writes while it reads the first. */
long gk_vct_bounce_memory(int res, bool aniso);

/* GPU bytes the axis clamp adds (vct_axis_clamp): three uints per level-0 voxel, the distances to the
 * first occupied voxel along each axis's two directions (vct/axis_dist.comp). */
long gk_vct_axis_clamp_memory(int res);
/* GPU bytes vct_axis_clamp=thin adds to those: one uint per level-0 voxel, the ways its fragments face
 * and whether it is a thin wall's (vct/thin_flag.comp). */
long gk_vct_thin_flag_memory(int res);

/* GL names for tests that read the voxel data back. */
unsigned gk_vct_scratch_buffer(const void *self);
unsigned gk_vct_radiance_texture(const void *self);  /* level-0 radiance (RGBA16F 3D) */
unsigned gk_vct_axis_buffer(const void *self);       /* vct_axis_clamp's distances (0 until first used) */
unsigned gk_vct_thin_buffer(const void *self);       /* vct_axis_clamp=thin's flags (0 until first used) */

#endif
