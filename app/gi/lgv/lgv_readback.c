/* The lgv method's grids read back for tests (lgv.h): the LGV the lookup reads, the geometry volume,
 * the distance maps and their material codes, and the caustic photons. */
#include <stdlib.h>
#include <string.h>

#include "lgv_internal.h"

/* Copies the first `count` values of buffer b (uints when as_uint, scaled by 1 / scale) into out. */
static int read_floats(GLuint b, long count, bool as_uint, float scale, float *out, gk_err *e)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, b);
    const void *p = glMapBufferRange(GL_COPY_READ_BUFFER, 0, count * 4, GL_MAP_READ_BIT);
    if (p) {
        for (long i = 0; i < count; i++)
            out[i] = as_uint ? (float)((const GLuint *)p)[i] / scale : ((const float *)p)[i];
        glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    return p ? 0 : gk_fail(e, GK_ERUNTIME, "lgv: cannot read a grid back");
}

long gk_lgv_read_lgv(void *self, float *out, long cap, gk_err *e)
{
    lgv_state *s = self;
    long n = s->lgv_cells * 12;
    if (!s->out_ssbo || cap < n)
        return gk_fail(e, GK_ERUNTIME, "lgv: no LGV yet, or %ld values do not hold its %ld", cap, n);
    return read_floats(s->out_ssbo, n, false, 1.0f, out, e) ? -1 : n;
}

long gk_lgv_read_geometry(void *self, float *out, long cap, int dims[3], gk_err *e)
{
    lgv_state *s = self;
    long n = 3L * s->geo_dims[0] * s->geo_dims[1] * s->geo_dims[2];
    if (!s->geo_ssbo || cap < n)
        return gk_fail(e, GK_ERUNTIME, "lgv: no geometry volume yet, or %ld values do not hold its %ld", cap, n);
    memcpy(dims, s->geo_dims, sizeof s->geo_dims);
    return read_floats(s->geo_ssbo, n, true, LGV_GEO_FIXED, out, e) ? -1 : n;
}

long gk_lgv_read_maps(void *self, uint32_t *out, long cap, gk_lgv_maps_info *info, gk_err *e)
{
    lgv_state *s = self;
    int layers = 6 * (s->n_maps + s->n_refractors);
    long n = 0;
    for (int l = 0; l < s->levels; l++)
        n += (long)layers * (s->maps_res >> l) * (s->maps_res >> l);
    if (!s->maps_valid || cap < n)
        return gk_fail(e, GK_ERUNTIME, "lgv: no maps yet, or %ld texels do not hold their %ld", cap, n);
    *info = (gk_lgv_maps_info){.res = s->maps_res, .levels = s->levels, .layers = layers, .n_maps = s->n_maps,
                               .bmin = s->bmin, .bmax = s->bmax, .itp_eps = LGV_ITP_EPS_REL * s->diag,
                               .q = LGV_Q, .loops = LGV_LOOPS, .secant_steps = LGV_SECANT_STEPS};
    GLuint fbo, *texel = malloc(sizeof(GLuint) * 4 * (size_t)s->maps_res * (size_t)s->maps_res);
    if (!texel)
        return gk_fail(e, GK_ERUNTIME, "lgv: out of memory");
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    long at = 0;
    for (int l = 0; l < s->levels; l++) {
        int r = s->maps_res >> l;
        for (int layer = 0; layer < layers; layer++, at += (long)r * r) {
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s->dist_tex, l, layer);
            glReadPixels(0, 0, r, r, GL_RGBA_INTEGER, GL_UNSIGNED_INT, texel);
            for (long i = 0; i < (long)r * r; i++)
                out[at + i] = texel[4 * i];
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    free(texel);
    GLenum err = glGetError();
    return err == GL_NO_ERROR ? n : gk_fail(e, GK_ERUNTIME, "lgv: reading the maps back: GL error 0x%04x", err);
}

long gk_lgv_read_codes(void *self, uint8_t *out, long cap, gk_err *e)
{
    lgv_state *s = self;
    int layers = 6 * (s->n_maps + s->n_refractors), r = s->maps_res;
    long n = (long)layers * r * r;
    if (!s->maps_valid || cap < n)
        return gk_fail(e, GK_ERUNTIME, "lgv: no maps yet, or %ld codes do not hold their %ld", cap, n);
    uint8_t *texel = malloc(4 * (size_t)r * (size_t)r);
    if (!texel)
        return gk_fail(e, GK_ERUNTIME, "lgv: out of memory");
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    for (int layer = 0; layer < layers; layer++) {
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s->alb_tex, 0, layer);
        glReadPixels(0, 0, r, r, GL_RGBA, GL_UNSIGNED_BYTE, texel);
        for (long i = 0; i < (long)r * r; i++)
            out[(long)layer * r * r + i] = texel[4 * i + 3]; /* cubemap.frag: code / 255 in alpha */
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    free(texel);
    GLenum err = glGetError();
    return err == GL_NO_ERROR ? n : gk_fail(e, GK_ERUNTIME, "lgv: reading the codes back: GL error 0x%04x", err);
}

long gk_lgv_read_caustics(void *self, float *out, long cap, gk_err *e)
{
    lgv_state *s = self;
    if (!s->caustic_ssbo)
        return gk_fail(e, GK_ERUNTIME, "lgv: no caustic photons yet");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, s->caustic_ssbo);
    long bytes = LGV_CAUSTIC_HEADER + (long)s->caustic_cap * LGV_CAUSTIC_BYTES, n = -1;
    const uint8_t *p = glMapBufferRange(GL_COPY_READ_BUFFER, 0, bytes, GL_MAP_READ_BIT);
    if (p) {
        uint32_t listed;
        memcpy(&listed, p, sizeof listed); /* the list's length, overflow included (trace.comp) */
        n = listed < (uint32_t)s->caustic_cap ? (long)listed : s->caustic_cap;
        n = n < cap / 6 ? n : cap / 6;
        for (long i = 0; i < n; i++) {
            const float *c = (const float *)(p + LGV_CAUSTIC_HEADER + i * LGV_CAUSTIC_BYTES); /* pos, dir, power */
            memcpy(out + 6 * i, c, 3 * sizeof(float));
            memcpy(out + 6 * i + 3, c + 8, 3 * sizeof(float));
        }
        glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    return n >= 0 ? n : gk_fail(e, GK_ERUNTIME, "lgv: cannot read the caustic photons back");
}
