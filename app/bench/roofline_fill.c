/* The roofline's raster kind (roofline_internal.h): how fast this GPU fills, for the passes that
 * rasterize rather than fetch (vpl's VAL maps: a flat R16F value and a depth test per fragment).
 * One draw of o->fetches viewport-covering triangles, each nearer than the last so every fragment
 * passes the depth test (LESS, as the VAL maps draw) and writes colour and depth, into a target of
 * o->invocations pixels: invocations x fetches fragments per run, as the fetch kinds do that many
 * fetches. The count is checked by a counting variant of the fragment shader (FILL_COUNT: one
 * atomic add per fragment) in one more, untimed run, so the atomics do not weigh on the timed ones. */
#include <stdio.h>

#include "gl/gl_counters.h"
#include "roofline_internal.h"

struct fill {
    const gk_roofline_opts *o;
    GLuint vao;
};

static void fill_run(void *ctx)
{
    const struct fill *f = ctx;
    glClear(GL_DEPTH_BUFFER_BIT);
    glBindVertexArray(f->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3 * f->o->fetches);
}

/* The program for the fill, with the uniforms set; 0 with e filled. */
static GLuint fill_program(gk_program_cache *programs, const gk_roofline_opts *o, bool count, gk_err *e)
{
    GLuint prog = gk_program_get(programs, "bench/roofline_fill.vert", "bench/roofline_fill.frag",
                                 count ? "#define FILL_COUNT 1\n" : NULL, e);
    if (prog) {
        glUseProgram(prog);
        gk_uniform_1i(prog, "u_layers", o->fetches);
    }
    return prog;
}

int gk_roofline_fill(gk_program_cache *programs, const gk_roofline_opts *o, const char *name, const char *format,
                     gk_roofline_result *r, gk_err *e)
{
    /* a square 512² for the default 64³ pixels, else 64 wide (a multiple of llvmpipe's tiles) */
    int w = o->invocations % 512 == 0 && o->invocations / 512 <= 512 ? 512 : 64, h = o->invocations / w;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    if (h > max_size)
        return gk_fail(e, GK_EINPUT, "roofline: a %dx%d fill target is past this GPU's %d", w, h, (int)max_size);
    GLuint prog = fill_program(programs, o, false, e);
    if (!prog)
        return -1;
    GLuint fbo, color, depth, vao;
    glGenTextures(1, &color);
    glBindTexture(GL_TEXTURE_2D, color);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_R16F, w, h);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    glGenVertexArrays(1, &vao);
    int rc = 0;
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        rc = gk_fail(e, GK_ERUNTIME, "roofline: the R16F + depth fill framebuffer is incomplete");
    } else {
        glViewport(0, 0, w, h);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        struct fill f = {o, vao};
        double median = gk_roofline_time(o, fill_run, NULL, &f);
        gk_roofline_result_set(r, name, format, w, o, median);
        r->counted = 0;
        r->expected = r->fetches; /* one counting run */
        r->unit = "fragments";
        gk_counters c = {.n = 1, .binding = 0};
        if (gk_counters_begin(&c, true)) {
            if (fill_program(programs, o, true, e)) {
                fill_run(&f);
                gk_counters_end(&c);
                r->counted = c.counted ? (uint64_t)c.value[0] : 0;
            } else {
                rc = -1;
            }
            gk_counters_free(&c);
        }
        glDisable(GL_DEPTH_TEST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &depth);
    glDeleteTextures(1, &color);
    glDeleteVertexArrays(1, &vao);
    GLenum err = glGetError();
    if (rc == 0 && err != GL_NO_ERROR)
        rc = gk_fail(e, GK_ERUNTIME, "roofline: %s: GL error 0x%04x", name, err);
    return rc;
}
