/* Cross-fade of the GI result when the method or a budget level changes (issue: "no pops").
 *
 * A scheduler step (vct_mips aniso -> iso cut the bounce light to 30% in one frame) or a method
 * switch would otherwise show as a jump. Every frame that runs the gi pass keeps a copy of the HDR
 * image before GI (`pre`, one blit). When a frame starts with a different method or knob levels
 * than the last one, the GI contribution that last frame SHOWED (shown - pre) is held; for the next
 * gi_blend - 1 frames the composed image is
 *     out = pre + mix(held, hdr - pre, t),   t = 1/N, 2/N, ... (N = gi_blend)
 * and from the N-th frame on it is the new result alone. Only the GI's contribution is faded, so
 * direct light (shadows included) is never mixed with an older frame; the held contribution is from
 * a few frames ago, which on a moving camera shows as a short ghost of the indirect light only.
 * Cost: one HDR blit per frame with GI, plus one full-screen pass during a transition -- both timed
 * inside the `gi` pass (gi.blend_hold, gi.blend), so the frame report and the scheduler see them.
 * The hold itself (a full-screen pass at a transition's first frame) runs before the targets may be
 * resized, at the frame's start: it is timed there as gi.blend_hold too (a pass begun twice under
 * the same parent accumulates, app/gl/gl_timing.h), so the frame's passes still sum to the frame. */
#include <stdio.h>
#include <string.h>

#include "base/log.h"
#include "renderer_internal.h"

/* compose/gi_hold.frag */
typedef struct hold_uniforms {
    GLint u_shown, u_pre;
} hold_uniforms;
static const gk_uniform_field hold_fields[] = {GK_UNIFORM(hold_uniforms, u_shown), GK_UNIFORM(hold_uniforms, u_pre)};

/* compose/gi_blend.frag */
typedef struct blend_uniforms {
    GLint u_pre, u_cur, u_held, u_t;
} blend_uniforms;
static const gk_uniform_field blend_fields[] = {GK_UNIFORM(blend_uniforms, u_pre), GK_UNIFORM(blend_uniforms, u_cur),
                                                GK_UNIFORM(blend_uniforms, u_held), GK_UNIFORM(blend_uniforms, u_t)};

static int ensure_rgba16f(gk_target *t, const char *what, int w, int h, gk_err *e)
{
    if (t->fbo && t->width == w && t->height == h)
        return 0;
    gk_target_destroy(t);
    const GLenum fmt[1] = {GL_RGBA16F};
    return gk_target_create(t, what, w, h, 1, fmt, GL_LINEAR, false, e);
}

static void bind_unit(int unit, GLuint tex, GLint location)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(location, unit);
}

/* held = shown - pre of the last frame, or zero when the last frame showed no GI. */
static int hold_last_contribution(gk_renderer *r, gk_err *e)
{
    gk_gi_blend *g = &r->blend;
    if (!g->pre_valid) {
        /* 1x1 zero: sampled anywhere it is "no GI" */
        if (ensure_rgba16f(&g->held, "gi blend (held)", 1, 1, e) != 0)
            return -1;
        glBindFramebuffer(GL_FRAMEBUFFER, g->held.fbo);
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
        return 0;
    }
    GLuint prog = gk_program_get(r->progs, "common/fullscreen.vert", "compose/gi_hold.frag", NULL, e);
    const hold_uniforms *u = prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(hold_fields), sizeof *u, e) : NULL;
    if (!u || ensure_rgba16f(&g->held, "gi blend (held)", g->pre.width, g->pre.height, e) != 0)
        return -1;
    if (r->count_work) /* gi_hold.frag: shown and pre, one bilinear lookup each a texel of the last frame's size */
        g->work_capture = 2.0 * g->held.width * g->held.height;
    glBindFramebuffer(GL_FRAMEBUFFER, g->held.fbo);
    glViewport(0, 0, g->held.width, g->held.height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(prog);
    bind_unit(0, r->shown ? r->shown : r->hdr.color[0], u->u_shown);
    bind_unit(1, g->pre.color[0], u->u_pre);
    gk_render_fullscreen(r);
    return 0;
}

void gk_gi_blend_begin_frame(gk_renderer *r, const char *method, const gk_budget *b, int blend_frames)
{
    gk_gi_blend *g = &r->blend;
    g->work_hold = g->work_blend = g->work_capture = 0.0;
    const char *m = method ? method : "none";
    int n = b ? b->n : 0;
    bool changed = g->have_last &&
                   (strcmp(g->method, m) != 0 || g->n_levels != n ||
                    (n > 0 && memcmp(g->levels, b->level, sizeof(int) * (size_t)n) != 0));
    bool gi_now = strcmp(m, "none") != 0;
    if (changed) {
        g->frames_left = 0;
        /* nothing to fade when neither side has GI, or when fading is off */
        if (blend_frames > 1 && r->have_frame && (g->pre_valid || gi_now)) {
            gk_err he = {0}; /* a fade that cannot start is no frame error: logged, the switch shows at once */
            /* timed as the gi pass's blend_hold (the renderer's frame has begun on its timer) */
            const gk_pass_ctx hold_ctx = {.timer = r->timer};
            gk_pass_begin(&hold_ctx, "gi");
            gk_pass_begin(&hold_ctx, "blend_hold");
            int held = hold_last_contribution(r, &he);
            gk_pass_end(&hold_ctx);
            gk_pass_end(&hold_ctx);
            if (held == 0) {
                g->frames = blend_frames;
                g->frames_left = blend_frames - 1;
            } else {
                gk_log("renderer: GI cross-fade skipped: %s", he.msg);
            }
        }
    }
    snprintf(g->method, sizeof g->method, "%s", m);
    g->n_levels = n;
    if (n > 0)
        memcpy(g->levels, b->level, sizeof(int) * (size_t)n);
    g->have_last = true;
    g->pre_valid = false;  /* set again by this frame's gi pass */
}

bool gk_gi_blend_active(const gk_renderer *r)
{
    return r->blend.frames_left > 0;
}

int gk_gi_blend_before_method(gk_renderer *r, const gk_pass_ctx *ctx, int blend_frames, gk_err *e)
{
    gk_gi_blend *g = &r->blend;
    if (blend_frames <= 1 && g->frames_left == 0 && !gk_gi_occlusion_needed(r))
        return 0;
    gk_pass_begin(ctx, "blend_hold");
    int rc = ensure_rgba16f(&g->pre, "gi blend (before GI)", r->render_w, r->render_h, e);
    if (rc == 0) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, r->hdr.fbo);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, g->pre.fbo);
        glBlitFramebuffer(0, 0, r->render_w, r->render_h, 0, 0, r->render_w, r->render_h, GL_COLOR_BUFFER_BIT,
                          GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        g->pre_valid = true;
        if (r->count_work) /* the blit: one texel a pixel */
            g->work_hold = (double)r->render_w * r->render_h;
    }
    gk_pass_end(ctx);
    return rc;
}

int gk_gi_blend_after_method(gk_renderer *r, const gk_pass_ctx *ctx, gk_err *e)
{
    gk_gi_blend *g = &r->blend;
    if (g->frames_left <= 0 || !g->pre_valid)
        return 0;
    gk_pass_begin(ctx, "blend");
    GLuint prog = gk_program_get(r->progs, "common/fullscreen.vert", "compose/gi_blend.frag", NULL, e);
    const blend_uniforms *u = prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(blend_fields), sizeof *u, e) : NULL;
    int rc = u ? ensure_rgba16f(&g->out, "gi blend (out)", r->render_w, r->render_h, e) : -1;
    if (rc == 0) {
        glBindFramebuffer(GL_FRAMEBUFFER, g->out.fbo);
        glViewport(0, 0, r->render_w, r->render_h);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glUseProgram(prog);
        bind_unit(0, g->pre.color[0], u->u_pre);
        bind_unit(1, r->hdr.color[0], u->u_cur);
        bind_unit(2, g->held.color[0], u->u_held);
        glUniform1f(u->u_t, (float)(g->frames - g->frames_left) / (float)g->frames);
        gk_render_fullscreen(r);
        glActiveTexture(GL_TEXTURE0);
        r->shown = g->out.color[0];
        if (r->count_work) /* gi_blend.frag: pre, cur and held, one bilinear lookup each a pixel */
            g->work_blend = 3.0 * r->render_w * r->render_h;
        g->frames_left--;
    }
    gk_pass_end(ctx);
    return rc;
}

void gk_gi_blend_reset(gk_renderer *r)
{
    gk_gi_blend *g = &r->blend;
    g->have_last = false;
    g->pre_valid = false;
    g->frames_left = 0;
}

void gk_gi_blend_destroy(gk_renderer *r)
{
    gk_target_destroy(&r->blend.pre);
    gk_target_destroy(&r->blend.held);
    gk_target_destroy(&r->blend.out);
}
