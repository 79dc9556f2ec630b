/* GPU final gather into indirect illumination maps (seed 004 §4; photon-mapping-000-004.md B.1.5,
 * B.5, B.7 #1-2): per light-map texel, the scene (textured with the AIMs' full illumination) is
 * rendered from the texel's centre along its normal onto the hemicube's front face enlarged to
 * double side length (half-width a = 2 at distance 1: a 126.87 degree field of view), into one
 * res x res tile of a tile atlas; a compute pass then sums p F_h per tile,
 *     F_h(x, y) = ΔA / (π (x² + y² + 1)²),
 * and divides by the discrete Σ F_h of the pixels rendered -- the coverage, 0.8315 at 16², not the
 * seed's "about 86%" (errata #1) -- so the result is the cosine-weighted mean radiance E/π (errata
 * #2); it stores E = π Σ p F_h / Σ F_h into the IIM texel and its gutter copies (imageStore, no
 * read-back). Tiles are RGBA32UI holding the radiance's fp32 bits (integer targets are
 * colour-renderable on the GLES 3.1 floor; the seed's 8-bit mipmap summation was its M5 error),
 * summed in fp32 in shared memory. */
#ifndef GK_LM_GATHER_H
#define GK_LM_GATHER_H

#include "base/err.h"
#include "core/vecmath.h"
#include "gl/gl.h"
#include "gl/gl_counters.h"
#include "gl/gl_program.h"

#define LM_GATHER_HALF_WIDTH 2.0f   /* the enlarged face: double the hemicube's side */
#define LM_GATHER_MAX_TARGETS 9     /* a texel and its gutter copies (a 1x1 chart: 8) */

typedef struct lm_gather_job {
    vec3 eye, dir, up;               /* the texel's centre (lifted off the surface), normal, a tangent */
    int n_targets;
    int target[LM_GATHER_MAX_TARGETS][2];
} lm_gather_job;

typedef struct lm_gather {
    int res, max_tiles;
    GLuint fbo, tiles, depth, jobs_ssbo;
    bool count_work;             /* set before a run: the reduction runs its counting variant (#21) */
    gk_counters reduce_fetches;  /* its tile texel reads, when count_work */
} lm_gather;

/* Draws the scene's radiance into the bound tile for view_proj (the gather program is bound by
   the callback). Returns -1 with e filled on error. */
typedef int (*lm_gather_draw_fn)(void *ctx, const mat4 *view_proj, gk_err *e);

int lm_gather_setup(lm_gather *g, int res, int max_tiles, gk_err *e);
void lm_gather_free(lm_gather *g);
/* Gathers n jobs (n <= max_tiles) into iim (an immutable RGBA16F texture). near/far: the gather
   cameras' depth range. */
int lm_gather_run(lm_gather *g, gk_program_cache *pc, const lm_gather_job *jobs, int n, float near, float far,
                  lm_gather_draw_fn draw, void *ctx, GLuint iim, gk_err *e);
/* The gather camera's projection for a face of half-width LM_GATHER_HALF_WIDTH. */
mat4 lm_gather_proj(float near, float far);
/* Σ F_h over res x res pixel centres of the a = 2 face (the coverage the reduction divides by). */
double lm_gather_coverage(int res);

#endif
