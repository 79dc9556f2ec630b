/* Caustic counting, tile culling and the 7x7 filter (lm_caustic_gpu.h). */
#include "lm_caustic_gpu.h"

#include <stdlib.h>
#include <string.h>

#include "lm_caustics.h"

/* lightmap/caustic_count.vert + caustic_count.frag */
typedef struct count_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_viewproj, u_count_scale;
} count_uniforms;
static const gk_uniform_field count_fields[] = {GK_GBUFFER_FIELDS(count_uniforms, gb),
                                                GK_UNIFORM(count_uniforms, u_viewproj),
                                                GK_UNIFORM(count_uniforms, u_count_scale)};
/* common/fullscreen.vert + lightmap/caustic_filter.frag */
typedef struct filter_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_count, u_photon_flux, u_count_scale;
} filter_uniforms;
static const gk_uniform_field filter_fields[] = {GK_GBUFFER_FIELDS(filter_uniforms, gb),
                                                 GK_UNIFORM(filter_uniforms, u_count),
                                                 GK_UNIFORM(filter_uniforms, u_photon_flux),
                                                 GK_UNIFORM(filter_uniforms, u_count_scale)};

static GLenum wanted_format(const lm_caustic_gpu *g) { return g->count_format == GL_R16F ? GL_R16F : GL_R8; }
/* What the target stores a photon as: 1/255 in R8 (a normalized byte), 1 in R16F. */
static float count_scale(GLenum fmt) { return fmt == GL_R16F ? 1.0f : 255.0f; }

int lm_caustic_gpu_upload(lm_caustic_gpu *g, const float *points, int n, int stride, gk_err *e)
{
    if (!g->vao) {
        glGenVertexArrays(1, &g->vao);
        glGenVertexArrays(1, &g->empty_vao);
        glGenBuffers(1, &g->vbo);
        glBindVertexArray(g->vao);
        glBindBuffer(GL_ARRAY_BUFFER, g->vbo);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), (void *)0);
        glBindVertexArray(0);
    }
    float *xyz = malloc(sizeof(float) * 3 * (size_t)(n > 0 ? n : 1));
    if (!xyz)
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory for %d caustic points", n);
    for (int i = 0; i < n; i++)
        memcpy(&xyz[3 * i], &points[(size_t)stride * (size_t)i], 3 * sizeof(float));
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo);
    if (n > g->cap_points) {
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 3 * (size_t)n), xyz, GL_DYNAMIC_DRAW);
        g->cap_points = n;
    } else if (n > 0) {
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(float) * 3 * (size_t)n), xyz);
    }
    free(xyz);
    g->n_points = n;
    return 0;
}

static void free_target(lm_caustic_gpu *g)
{
    if (g->fbo)
        glDeleteFramebuffers(1, &g->fbo);
    if (g->count_tex)
        glDeleteTextures(1, &g->count_tex);
    if (g->stencil_rb)
        glDeleteRenderbuffers(1, &g->stencil_rb);
    if (g->queries)
        glDeleteQueries(g->tiles_x * g->tiles_y, g->queries);
    free(g->queries);
    g->fbo = g->count_tex = g->stencil_rb = 0;
    g->made_format = 0;
    g->queries = NULL;
    g->w = g->h = 0;
}

static int ensure_target(lm_caustic_gpu *g, int w, int h, gk_err *e)
{
    if (g->fbo && g->w == w && g->h == h && g->made_format == wanted_format(g))
        return 0;
    free_target(g);
    g->w = w, g->h = h;
    /* about 10 tiles across, as the seed's 100 queries over 512²; at least 8 pixels */
    g->tile = (w > h ? w : h) / 10;
    g->tile = g->tile < 8 ? 8 : g->tile;
    g->tiles_x = (w + g->tile - 1) / g->tile, g->tiles_y = (h + g->tile - 1) / g->tile;
    g->queries = calloc((size_t)(g->tiles_x * g->tiles_y), sizeof *g->queries);
    if (!g->queries)
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory for the caustic tiles");
    glGenQueries(g->tiles_x * g->tiles_y, g->queries);
    glGenTextures(1, &g->count_tex);
    glBindTexture(GL_TEXTURE_2D, g->count_tex);
    g->made_format = wanted_format(g);
    glTexStorage2D(GL_TEXTURE_2D, 1, g->made_format, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenRenderbuffers(1, &g->stencil_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, g->stencil_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_STENCIL_INDEX8, w, h);
    glGenFramebuffers(1, &g->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, g->count_tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, g->stencil_rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "lightmap: caustic count framebuffer incomplete (%dx%d)", w, h);
    return 0;
}

/* The tile's rect grown by d pixels, clipped to the screen. */
static void tile_rect(const lm_caustic_gpu *g, int tx, int ty, int d, int r[4])
{
    int x0 = tx * g->tile - d, y0 = ty * g->tile - d;
    int x1 = (tx + 1) * g->tile + d, y1 = (ty + 1) * g->tile + d;
    x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > g->w ? g->w : x1, y1 = y1 > g->h ? g->h : y1;
    r[0] = x0, r[1] = y0, r[2] = x1 - x0, r[3] = y1 - y0;
}

/* Σ over the pixels lo .. lo+n-1 of an axis of size `size` of their neighbours within k on it */
static double axis_reads(int lo, int n, int size)
{
    double sum = 0.0;
    for (int x = lo; x < lo + n; x++) {
        int a = x - LM_CAUSTIC_K < 0 ? 0 : x - LM_CAUSTIC_K, b = x + LM_CAUSTIC_K >= size ? size - 1 : x + LM_CAUSTIC_K;
        sum += b - a + 1;
    }
    return sum;
}

/* the neighbourhood is a product of the two axes' ranges, so its sum over a rect is too */
double lm_caustic_filter_reads(const int r[4], int w, int h)
{
    return axis_reads(r[0], r[2], w) * axis_reads(r[1], r[3], h);
}

int lm_caustic_gpu_draw(lm_caustic_gpu *g, gk_program_cache *programs, const gk_gbuffer_view *gb, vec3 flux, bool cull,
                        GLuint out_fbo, const gk_pass_ctx *pass, gk_err *e)
{
    g->tiles_filtered = 0, g->pixels_filtered = 0, g->filter_reads = 0.0, g->cull_fragments = 0.0;
    g->count_fragments.counted = false;
    if (g->n_points <= 0 || !g->vao)
        return 0;
    /* lightmap/caustic_count.frag PointFragments */
    const char *count_define =
        gk_counters_variant(&g->count_fragments, g->count_work, 1, 6, "#define CAUSTIC_COUNT_FRAGMENTS 1\n");
    GLuint cp = gk_program_get(programs, "lightmap/caustic_count.vert", "lightmap/caustic_count.frag", count_define, e);
    const count_uniforms *cu = cp ? gk_program_uniforms(programs, cp, GK_FIELDS(count_fields), sizeof *cu, e) : NULL;
    GLuint qp = cu ? gk_program_get(programs, "common/fullscreen.vert", "lightmap/caustic_cull.frag", NULL, e) : 0;
    GLuint fp = qp ? gk_program_get(programs, "common/fullscreen.vert", "lightmap/caustic_filter.frag", NULL, e) : 0;
    const filter_uniforms *fu = fp ? gk_program_uniforms(programs, fp, GK_FIELDS(filter_fields), sizeof *fu, e) : NULL;
    if (!fu || ensure_target(g, gb->width, gb->height, e)) {
        gk_counters_end(&g->count_fragments);
        return -1;
    }

    gk_pass_begin(pass, "lightmap_caustic_count");
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, b1);
    glViewport(0, 0, g->w, g->h);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilMask(0xFF);
    const GLfloat zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    const GLint zero_stencil = 0;
    glClearBufferiv(GL_STENCIL, 0, &zero_stencil);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR); /* "increment on z-pass" */
    glUseProgram(cp);
    glUniformMatrix4fv(cu->u_viewproj, 1, GL_FALSE, gb->view_proj.m);
    glUniform1f(cu->u_count_scale, count_scale(g->made_format));
    gk_gbuffer_bind(gb, &cu->gb, 0, 0);
    glBindVertexArray(g->vao);
    glDrawArrays(GL_POINTS, 0, g->n_points);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    gk_counters_end(&g->count_fragments);
    gk_pass_end(pass);

    bool *on = calloc((size_t)(g->tiles_x * g->tiles_y), sizeof *on);
    if (!on) {
        glDisable(GL_STENCIL_TEST);
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory for the caustic tiles");
    }
    if (cull) {
        gk_pass_begin(pass, "lightmap_caustic_cull");
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glStencilFunc(GL_LESS, 0, 0xFF); /* passes where 0 < stencil */
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        glEnable(GL_SCISSOR_TEST);
        glUseProgram(qp);
        glBindVertexArray(g->empty_vao);
        for (int ty = 0; ty < g->tiles_y; ty++)
            for (int tx = 0; tx < g->tiles_x; tx++) {
                int r[4];
                tile_rect(g, tx, ty, LM_CAUSTIC_K, r);
                glScissor(r[0], r[1], r[2], r[3]);
                g->cull_fragments += (double)r[2] * r[3]; /* the triangle's fragments in the scissor */
                glBeginQuery(GL_ANY_SAMPLES_PASSED, g->queries[ty * g->tiles_x + tx]);
                glDrawArrays(GL_TRIANGLES, 0, 3);
                glEndQuery(GL_ANY_SAMPLES_PASSED);
            }
        for (int i = 0; i < g->tiles_x * g->tiles_y; i++) {
            GLuint any = 0;
            glGetQueryObjectuiv(g->queries[i], GL_QUERY_RESULT, &any); /* waits: M17 */
            on[i] = any != 0;
        }
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDisable(GL_SCISSOR_TEST);
        gk_pass_end(pass);
    } else {
        for (int i = 0; i < g->tiles_x * g->tiles_y; i++)
            on[i] = true;
    }
    glDisable(GL_STENCIL_TEST);

    gk_pass_begin(pass, "lightmap_caustic_filter");
    glBindFramebuffer(GL_FRAMEBUFFER, out_fbo);
    glDrawBuffers(1, b1);
    glViewport(0, 0, g->w, g->h);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(fp);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, g->count_tex);
    glUniform1i(fu->u_count, 0);
    glUniform3f(fu->u_photon_flux, flux.x, flux.y, flux.z);
    glUniform1f(fu->u_count_scale, count_scale(g->made_format));
    gk_gbuffer_bind(gb, &fu->gb, 1, 0);
    glBindVertexArray(g->empty_vao);
    if (!cull) {
        glDrawArrays(GL_TRIANGLES, 0, 3);
        g->tiles_filtered = g->tiles_x * g->tiles_y;
        g->pixels_filtered = (long)g->w * g->h;
        const int all[4] = {0, 0, g->w, g->h};
        g->filter_reads = lm_caustic_filter_reads(all, g->w, g->h);
    } else {
        glEnable(GL_SCISSOR_TEST);
        for (int ty = 0; ty < g->tiles_y; ty++)
            for (int tx = 0; tx < g->tiles_x; tx++) {
                if (!on[ty * g->tiles_x + tx])
                    continue;
                int r[4];
                tile_rect(g, tx, ty, 0, r);
                glScissor(r[0], r[1], r[2], r[3]);
                glDrawArrays(GL_TRIANGLES, 0, 3);
                g->tiles_filtered++;
                g->pixels_filtered += (long)r[2] * r[3];
                g->filter_reads += lm_caustic_filter_reads(r, g->w, g->h);
            }
        glDisable(GL_SCISSOR_TEST);
    }
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
    gk_pass_end(pass);
    free(on);
    return 0;
}

void lm_caustic_gpu_free(lm_caustic_gpu *g)
{
    GLenum keep = g->count_format; /* the caller's choice outlives the GL objects */
    free_target(g);
    gk_counters_free(&g->count_fragments);
    if (g->vao)
        glDeleteVertexArrays(1, &g->vao);
    if (g->empty_vao)
        glDeleteVertexArrays(1, &g->empty_vao);
    if (g->vbo)
        glDeleteBuffers(1, &g->vbo);
    memset(g, 0, sizeof *g);
    g->count_format = keep;
}
