/* Caustic counting and filtering on the GPU (seed 004 §5; photon-mapping-000-004.md B.1.6, B.5,
 * B.6 #6, M12–M19), independent of the rest of the method (tests drive it with their own
 * G-buffer):
 *   count  the caustic photons drawn as points, additively, into an R8 target (1/255 a photon:
 *          the seed's 8-bit count, at most 255 a pixel) or R16F (count_format), hidden ones
 *          dropped against the G-buffer,
 *          each counted one incrementing the stencil (shaders_gles/lightmap/caustic_count.*);
 *   cull   the screen cut into tiles (about 10 across, the seed's 100 queries over 512²); per tile
 *          one GL_ANY_SAMPLES_PASSED query over the tile dilated by the kernel's k = 3 pixels with
 *          the stencil test "> 0" (the dilation is the research's M16 fix: without it a photon
 *          within 3 pixels of a tile border is cut off); the results are read in the same frame
 *          (a stall, M17, instead of filtering new caustics a frame late);
 *   filter the 7x7 kernel of eq. (4) in the non-empty tiles only (scissored), adding the caustic
 *          radiance to out_fbo (caustic_filter.frag). With cull false it filters the whole screen:
 *          the output is bit-identical (tests/gpu/test_lightmap_caustics.c). */
#ifndef GK_LM_CAUSTIC_GPU_H
#define GK_LM_CAUSTIC_GPU_H

#include <stdbool.h>

#include "gl/gbuffer_bind.h"
#include "gl/gl.h"
#include "gl/gl_counters.h"
#include "gl/gl_program.h"
#include "gl/pass.h"

typedef struct lm_caustic_gpu {
    /* The count target: GL_R8 (the seed's 8-bit count, 1/255 a photon, at most 255 a pixel: M14)
       or GL_R16F (1 a photon, exact to 2,048; colour-renderable on GLES 3.2 or with
       EXT_color_buffer_half_float: the caller checks). Set before a draw; 0 means GL_R8. */
    GLenum count_format;
    bool count_work;         /* set before a draw: the count pass runs its counting variant (#21) */
    GLuint vao, vbo, empty_vao;
    int n_points, cap_points;
    GLuint fbo, count_tex, stencil_rb;
    GLenum made_format;      /* the count texture's */
    int w, h;
    int tile, tiles_x, tiles_y;
    GLuint *queries;
    /* the last draw */
    int tiles_filtered;      /* tiles whose query found a counted photon (all when not culling) */
    long pixels_filtered;    /* pixels the filter ran on */
    double filter_reads;     /* the count texels they read (#21: lm_caustic_filter_reads) */
    double cull_fragments;   /* the cull's fragments, Σ of the dilated tiles' areas (#21; 0: no cull) */
    gk_counters count_fragments; /* the count pass's point fragments, when count_work (#21) */
} lm_caustic_gpu;

/* The filter's work (#21, app/gl/pass_work.h): the count texels caustic_filter.frag reads for the
 * pixels of the rect r (x, y, width, height) on a w x h screen, each pixel its (2k+1)^2 neighbours
 * that lie on the screen (all of them, before it knows whether any photon is near). */
double lm_caustic_filter_reads(const int r[4], int w, int h);

/* The photons' world positions (n points, `stride` floats apart, xyz first). */
int lm_caustic_gpu_upload(lm_caustic_gpu *g, const float *points, int n, int stride, gk_err *e);
/* Counts, culls (when cull) and filters into out_fbo (colour attachment 0, blended ONE + ONE) at
 * the G-buffer's size. flux: the mean flux of a photon. pass: the timer (NULL: untimed). */
int lm_caustic_gpu_draw(lm_caustic_gpu *g, gk_program_cache *programs, const gk_gbuffer_view *gb, vec3 flux, bool cull,
                        GLuint out_fbo, const gk_pass_ctx *pass, gk_err *e);
void lm_caustic_gpu_free(lm_caustic_gpu *g);

#endif
