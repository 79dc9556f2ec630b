/* Prefiltered shadow data shared by VSSM (shadow_vssm.c) and CSSM (shadow_cssm.c), derived by
 * compute from the shared depth maps (shadow_depth.c), all as 2D arrays with one layer per face:
 *   - normalised linear depth z = (lin - near) / (far - near) in R32F (level 0), and with it the
 *     min-max hierarchical shadow map (HSM, dong-001.md §5.3) as two R32F mip chains;
 *   - summed-area tables with exact modular uint sums (dong-001.md §1.3): (z, z^2) in two R32UI
 *     arrays, the CSSM Fourier bases in RGBA32UI arrays;
 *   - the CSSM bases in RGBA16F with mipmaps (the mipmap prefilter).
 * GLES 3.1 core only: compute shaders, r32f/r32ui/rgba32ui/rgba16f images, texelFetch. */
#ifndef GK_SHADOW_PREFILTER_H
#define GK_SHADOW_PREFILTER_H

#include "shadow.h"

/* Widest kernel the soft-shadow lookups use, as a fraction of the map side (the same quarter-map
 * limit as PCSS's blocker search). It bounds the box area, hence the SAT's fixed-point bits. */
#define GK_SOFT_MAX_KERNEL 0.25f

/* Fixed-point bits per texel for a SAT of a size^2 map: 32 - ceil(log2(A_max)), A_max the area of
 * the widest kernel (+1 texel of the interpolated box lookups) -- 17 bits at 512, 16 at 1024. */
int gk_sat_bits(int size);

/* A 2D array texture with `levels` mip levels (levels 0: the full chain), NEAREST filtering
 * (integer and R32F textures are read with texelFetch) unless `linear`. Returns 0 on GL error. */
GLuint gk_pf_array_create(GLenum format, int size, int layers, int levels, bool linear, gk_err *e);
int gk_pf_levels(int size);

/* Depth map -> normalised linear depth in level 0 of zmin (and of zmax when zmax != 0). */
int gk_pf_linearize(gk_program_cache *progs, GLuint depth, const gk_shadow_view *v, GLuint zmin, GLuint zmax,
                    gk_err *e);
/* Levels 1.. of the min-max pyramid from level 0 (both R32F arrays with gk_pf_levels(size) levels). */
int gk_pf_hsm(gk_program_cache *progs, GLuint zmin, GLuint zmax, int size, int layers, gk_err *e);

/* SAT of one basis pair (vssm_sat.comp): basis 0 = (z, z^2) into R32UI out0/out1 (in place, tmp
 * unused); basis 1 = CSSM (cos, sin), 2 = CSM-Z (z cos, z sin) into RGBA32UI out0/out1 through the
 * RGBA32UI scratch pair tmp0/tmp1. q = 2^bits - 1; range = CSSM depth scale. */
int gk_pf_sat(gk_program_cache *progs, int basis, GLuint z, int size, int layers, float q, float range, GLuint out0,
              GLuint out1, GLuint tmp0, GLuint tmp1, gk_err *e);

/* Binds a 2D array texture on a unit and sets the sampler uniform at location loc. */
void gk_pf_bind(GLint loc, GLuint tex, int unit);

#endif
