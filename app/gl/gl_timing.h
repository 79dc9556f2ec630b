/* The renderer's one clock (DESIGN §6): every pass of a frame -- shadow maps, G-buffer, direct
 * light, a GI method's own passes, compose, HUD -- is timed here through the pass context
 * (app/gl/pass.h), and nothing else keeps a clock. Which clock is decided once, at creation:
 *
 *  - GPU mode (EXT_disjoint_timer_query, where the driver's queries are trustworthy): one
 *    TIME_ELAPSED query open at a time (GL allows no nesting), so a nested pass closes its
 *    parent's query and the parent resumes in a new one when the child ends; a pass's time is its
 *    own segments plus its children's. Results are read GK_TIMER_LAG frames late, so the CPU never
 *    waits, and a frame's results are dropped when the GPU reports a disjoint event.
 *  - CPU mode (llvmpipe, where timer queries are meaningless; or no extension): wall clock around
 *    a fence at each pass boundary -- exact for a software rasterizer, where the "GPU" is the CPU.
 *
 * Passes nest (a GI method's passes inside `gi`); a pass begun twice in one frame under the same
 * parent (one per light) accumulates into one entry. */
#ifndef GK_GL_TIMING_H
#define GK_GL_TIMING_H

#include <stdbool.h>

#include "frame_report.h"
#include "gl.h"

#define GK_TIMER_LAG 3
#define GK_TIMER_MAX_DEPTH 8
#define GK_TIMER_MAX_QUERIES 64   /* query segments per frame (GPU mode) */

typedef struct gk_timer gk_timer;

/* The query entry points of GPU mode; gk_timer_create loads EXT_disjoint_timer_query's. Tests
 * pass a fake to check the segment bookkeeping without a GPU that has the extension. */
typedef struct gk_timer_queries {
    void (*gen)(GLsizei n, GLuint *ids);
    void (*del)(GLsizei n, const GLuint *ids);
    void (*begin)(GLenum target, GLuint id);
    void (*end)(GLenum target);
    void (*get_u)(GLuint id, GLenum pname, GLuint *v);
    void (*get_u64)(GLuint id, GLenum pname, GLuint64 *v);
    bool (*disjoint)(void);   /* GL_GPU_DISJOINT_EXT since the last call */
} gk_timer_queries;

gk_timer *gk_timer_create(bool use_gpu_queries);
gk_timer *gk_timer_create_with_queries(const gk_timer_queries *q);
void gk_timer_destroy(gk_timer *t);
bool gk_timer_uses_gpu(const gk_timer *t);

void gk_timer_frame_begin(gk_timer *t);
void gk_timer_pass_begin(gk_timer *t, const char *name);  /* name: a string literal */
void gk_timer_pass_end(gk_timer *t);
/* Fills out with the newest complete frame (CPU: this frame; GPU: GK_TIMER_LAG frames ago, with
 * an empty report until the first results arrive). Unbalanced passes are closed here. */
void gk_timer_frame_end(gk_timer *t, gk_frame_report *out);

#endif
