/* The soft-shadow prefilters' work (#21, app/gl/pass_work.h): the fetches the compute passes of
 * shadow_prefilter.c do, from their parameters (a map's size and layers): every dispatch reads a
 * fixed number of texels per texel it writes, whatever the depths are, so no count is needed.
 *   linearize (vssm_linearize.comp): one depth texel per texel of level 0 of each layer;
 *   min-max pyramid (vssm_hsm.comp): per texel of each level 1.. 2 x 2 loads of the min chain and
 *     2 x 2 of the max chain (an odd level's last row and column: 3), i.e. each chain's texels of
 *     levels 0 to the one before 1x1 once;
 *   SAT (vssm_sat.comp), per basis pair: the rows pass reads each R32F depth texel once
 *     (texelFetch), the columns pass loads each texel of both tables once (imageLoad).
 *   CSSM's depth range (cssm_range.comp, unless cssm_thesis's fixed range): a layer's reduction loads
 *     each texel once, then the renormalisation loads each texel and the layer's two range texels;
 *   CSSM's bases by mipmaps (cssm_basis.comp): two passes each reading the R32F depth once a texel,
 *     then glGenerateMipmap of the 5 RGBA16F chains (cos, sin, z cos, z sin, z), one bilinear lookup
 *     of the level above per texel of levels 1..; by SATs (cssm_sat): the SAT above for each of its
 *     3 basis pairs (z and z², cos and sin, z cos and z sin).
 * Kinds: the depth map's reads as tex2d_depth32f_nearest, the R32F depth's as tex2d_r32f_nearest,
 * every imageLoad (R32F, R32UI, RGBA32UI) as image3d_rgba16f_load, the roofline's only image kind,
 * the mips' lookups as tex2d_rgba16f_trilinear. */
#ifndef GK_SHADOW_PREFILTER_WORK_H
#define GK_SHADOW_PREFILTER_WORK_H

#include <stdbool.h>

typedef struct gk_pf_work {
    double depth_reads;   /* tex2d_depth32f_nearest */
    double r32f_reads;    /* tex2d_r32f_nearest */
    double image_loads;   /* image3d_rgba16f_load */
    double mip_lookups;   /* tex2d_rgba16f_trilinear */
} gk_pf_work;

/* A frame's prefilters, by method family (the renderer's `shadow.vssm_prefilter`, `shadow.cssm_prefilter`). */
typedef struct gk_pf_frame_work {
    gk_pf_work vssm, cssm;
} gk_pf_frame_work;

/* Adds one VSSM prefilter of a size² map of `layers` layers (shadow_vssm.c): linearize with the max
   chain, the min-max pyramid, the (z, z²) SAT. */
void gk_pf_work_vssm(gk_pf_work *w, int size, int layers);
/* Adds one CSSM prefilter (shadow_cssm.c): linearize, the depth range unless `full_range`, the bases
   by SATs (`sat`) or by mipmaps. */
void gk_pf_work_cssm(gk_pf_work *w, int size, int layers, bool full_range, bool sat);

#endif
