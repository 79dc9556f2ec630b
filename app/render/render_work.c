/* What the bench divides by a pass's time (#21, app/gl/pass_work.h): the renderer's own passes'
 * useful fetches, and the GI method's. The direct pass's shadow lookups depend on the data (PCSS
 * shrinks its PCF grid with the penumbra, VSSM subdivides kernels that straddle depths), so they
 * are counted: a counting variant of the lighting pass (SHADOW_COUNT_FETCHES, shaders_gles/shadow/
 * common.glsl) adds each pixel's fetches to a storage buffer, in frames the bench does not time. */
#include <string.h>

#include "render_gi.h"
#include "renderer_internal.h"

bool gk_renderer_count_shadow_fetches(gk_renderer *r, bool on)
{
    GLint blocks = 0;
    glGetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &blocks); /* GLES 3.1 allows 0 */
    r->count_shadow_fetches = on && blocks > 0;
    return r->count_shadow_fetches || !on;
}

const char *gk_render_work_begin(gk_renderer *r)
{
    r->shadow_counted = false;
    if (!r->count_shadow_fetches)
        return "";
    static const GLuint zero[2] = {0, 0};
    if (!r->shadow_count_ssbo) {
        glGenBuffers(1, &r->shadow_count_ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, r->shadow_count_ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof zero, zero, GL_DYNAMIC_READ);
    } else {
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, r->shadow_count_ssbo);
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, r->shadow_count_ssbo); /* direct/light.frag ShadowFetches */
    return "#define SHADOW_COUNT_FETCHES 1\n";
}

void gk_render_work_end(gk_renderer *r)
{
    if (!r->count_shadow_fetches)
        return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, r->shadow_count_ssbo);
    const GLuint *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, 2 * sizeof(GLuint), GL_MAP_READ_BIT);
    if (p) {
        r->shadow_fetches[0] = p[0];
        r->shadow_fetches[1] = p[1];
        r->shadow_counted = true;
        glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

void gk_render_work_destroy(gk_renderer *r)
{
    if (r->shadow_count_ssbo)
        glDeleteBuffers(1, &r->shadow_count_ssbo);
    r->shadow_count_ssbo = 0;
}

int gk_renderer_pass_work(const gk_renderer *r, const char *method, gk_pass_work *out, int max)
{
    int n = 0;
    /* the shadow maps are 32-bit depth and the SATs and min-max mips 32-bit integers, read
       unfiltered: the roofline's unfiltered 32-bit kind; CSSM's bases are mipmapped RGBA16F */
    static const char *const kinds[2] = {"tex2d_rgba32f_nearest", "tex2d_rgba16f_trilinear"};
    for (int k = 0; k < 2 && r->shadow_counted; k++)
        if (r->shadow_fetches[k] > 0.0 && n < max)
            out[n++] = (gk_pass_work){.pass = "direct", .kind = kinds[k], .fetches = r->shadow_fetches[k]};
    return n + gk_render_gi_pass_work(r->gi, method, out + n, max - n);
}
