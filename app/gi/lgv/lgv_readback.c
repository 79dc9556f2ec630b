/* The lgv method's grids read back for tests (lgv.h): the LGV the lookup reads and the geometry volume. */
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
