/* The pass context: what the renderer lends every pass of a frame -- its shadow method, the GI
 * method's passes, the HUD. One clock (the renderer's timer: a pass never times itself or calls
 * glFinish), the program cache, the capabilities, the frame's knob levels and scene, and the
 * G-buffer with the frame's view. A pass marks its work with gk_pass_begin/gk_pass_end; passes
 * begun inside another pass nest under it in the frame report (app/gl/frame_report.h). */
#ifndef GK_PASS_H
#define GK_PASS_H

#include "core/vecmath.h"
#include "gbuffer_bind.h"
#include "gl.h"
#include "gl_program.h"
#include "gl_timing.h"

struct gk_budget;
struct gk_scene;

typedef struct gk_pass_ctx {
    gk_timer *timer;                   /* NULL: passes are not timed (tests driving one method) */
    gk_program_cache *programs;
    const gk_gl_caps *caps;
    const struct gk_budget *budget;    /* this frame's knob levels */
    struct gk_budget *ran;             /* the levels that really ran: starts as a copy of budget; a
                                          pass that clamps a knob notes it (gk_knob_note_ran). NULL
                                          when there is no budget */
    const struct gk_scene *scene;      /* evaluated at this frame's time */
    const gk_gbuffer_view *gbuffer;    /* NULL before the gbuffer pass */
} gk_pass_ctx;

static inline void gk_pass_begin(const gk_pass_ctx *c, const char *name)
{
    if (c && c->timer)
        gk_timer_pass_begin(c->timer, name);
}

static inline void gk_pass_end(const gk_pass_ctx *c)
{
    if (c && c->timer)
        gk_timer_pass_end(c->timer);
}

#endif
