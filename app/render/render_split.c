/* The lighting pass's two draws for a shadow method that settles pixels early (gk_shadow_method.split,
 * #21). llvmpipe runs a fragment shader's every line for a SIMD block of pixels under lane masks:
 * an early return or a discard shortens no code but loops, so VSSM paid its whole lookup where the
 * HSM settles every pixel of a block, and where the block holds no lit surface at all. What skips a
 * block is the early stencil test (the fragment function checks the mask after it). So:
 *   draw 1 (SHADOW_SPLIT 1, cheap): pixels with no light (background, no radiance) and those the
 *          lookup's HSM tests settle (shadow_settle) are added and marked 1 in a stencil buffer
 *          beside the HDR target; the others are discarded, left 0;
 *   draw 2 (SHADOW_SPLIT 2): the one-draw shader with early fragment tests, stencil == 0 only.
 * Each pixel is added once per light, in the same order of lights: the image is bit-identical to the
 * one-draw pass (tests/gpu/test_shadow_split.c). The stencil is cleared per light. A tiled GPU
 * pays a second full-screen draw and the stencil (tile memory) per light; GK_SHADOW_ONE_DRAW=1 in the
 * environment turns the split off (the before/after of the README's numbers). */
#include <stdlib.h>

#include "base/log.h"

#include "renderer_internal.h"

bool gk_render_split_enabled(void)
{
    const char *v = getenv("GK_SHADOW_ONE_DRAW");
    return !(v && v[0] && v[0] != '0');
}

/* The HDR target's colour with a stencil renderbuffer of its size (re-made with the target). */
static int ensure(gk_renderer *r, gk_err *e)
{
    gk_light_split *s = &r->split;
    if (s->fbo && s->color == r->hdr.color[0] && s->w == r->hdr.width && s->h == r->hdr.height)
        return 0;
    gk_render_split_destroy(r);
    glGenRenderbuffers(1, &s->stencil);
    glBindRenderbuffer(GL_RENDERBUFFER, s->stencil);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_STENCIL_INDEX8, r->hdr.width, r->hdr.height);
    glGenFramebuffers(1, &s->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->hdr.color[0], 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, s->stencil);
    if (gk_fbo_check("lighting split", e) != 0) {
        gk_render_split_destroy(r);
        return -1;
    }
    s->color = r->hdr.color[0];
    s->w = r->hdr.width;
    s->h = r->hdr.height;
    return 0;
}

/* Binds the split's framebuffer for draw 1; false (the light is then drawn in one draw, the same
   image) where the driver refuses a colour + stencil-only framebuffer: STENCIL_INDEX8 renderbuffers are
   core GLES 3.0, but a driver may still report the combination incomplete. Said once, not per frame. */
bool gk_render_split_first(gk_renderer *r)
{
    if (r->split.unavailable)
        return false;
    gk_err e = {0};
    if (ensure(r, &e) != 0) {
        gk_log("lighting pass: %s; the shadow lookup's two draws are off, one draw from now on", e.msg);
        r->split.unavailable = true;
        glBindFramebuffer(GL_FRAMEBUFFER, r->hdr.fbo);
        return false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, r->split.fbo);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    const GLint zero = 0;
    glClearBufferiv(GL_STENCIL, 0, &zero);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE); /* depth test off: a surviving fragment writes 1 */
    return true;
}

void gk_render_split_second(void)
{
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glStencilMask(0);
}

void gk_render_split_end(gk_renderer *r)
{
    glStencilMask(0xff);
    glDisable(GL_STENCIL_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, r->hdr.fbo);
}

void gk_render_split_destroy(gk_renderer *r)
{
    gk_light_split *s = &r->split;
    if (s->fbo)
        glDeleteFramebuffers(1, &s->fbo);
    if (s->stencil)
        glDeleteRenderbuffers(1, &s->stencil);
    *s = (gk_light_split){0};
}
