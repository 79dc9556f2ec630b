/* GPU final gather (lm_gather.h). */
#include "lm_gather.h"

#include <math.h>
#include <string.h>

mat4 lm_gather_proj(float near, float far)
{
    /* tan(half fov) = a: the face at distance 1 spans [-a, a] */
    return m4_perspective(2.0f * atanf(LM_GATHER_HALF_WIDTH), 1.0f, near, far);
}

double lm_gather_coverage(int res)
{
    double a = LM_GATHER_HALF_WIDTH, da = 2.0 * a / res, sum = 0.0;
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) {
            double x = -a + (i + 0.5) * da, y = -a + (j + 0.5) * da, r = x * x + y * y + 1.0;
            sum += da * da / (3.14159265358979323846 * r * r);
        }
    return sum;
}

int lm_gather_setup(lm_gather *g, int res, int max_tiles, gk_err *e)
{
    memset(g, 0, sizeof *g);
    g->res = res, g->max_tiles = max_tiles;
    glGenTextures(1, &g->tiles);
    glBindTexture(GL_TEXTURE_2D, g->tiles);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32UI, res * max_tiles, res);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenRenderbuffers(1, &g->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, g->depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, res * max_tiles, res);
    glGenFramebuffers(1, &g->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, g->tiles, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g->depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "lightmap: gather framebuffer incomplete (%d tiles of %d²)", max_tiles, res);
    glGenBuffers(1, &g->jobs_ssbo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, g->jobs_ssbo);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(sizeof(GLint) * 4 * (1 + LM_GATHER_MAX_TARGETS) * max_tiles),
                 NULL, GL_DYNAMIC_DRAW);
    return 0;
}

void lm_gather_free(lm_gather *g)
{
    if (g->fbo)
        glDeleteFramebuffers(1, &g->fbo);
    if (g->tiles)
        glDeleteTextures(1, &g->tiles);
    if (g->depth)
        glDeleteRenderbuffers(1, &g->depth);
    if (g->jobs_ssbo)
        glDeleteBuffers(1, &g->jobs_ssbo);
    gk_counters_free(&g->reduce_fetches);
    memset(g, 0, sizeof *g);
}

/* lightmap/gather_reduce.comp */
typedef struct reduce_uniforms { GLint u_tiles, u_res, u_half_width; } reduce_uniforms;
static const gk_uniform_field reduce_fields[] = {GK_UNIFORM(reduce_uniforms, u_tiles),
                                                 GK_UNIFORM(reduce_uniforms, u_res),
                                                 GK_UNIFORM(reduce_uniforms, u_half_width)};

int lm_gather_run(lm_gather *g, gk_program_cache *pc, const lm_gather_job *jobs, int n, float near, float far,
                  lm_gather_draw_fn draw, void *ctx, GLuint iim, gk_err *e)
{
    if (n <= 0)
        return 0;
    n = n < g->max_tiles ? n : g->max_tiles;
    g->reduce_fetches.counted = false;
    /* lightmap/gather_reduce.comp ReduceFetches, bound on 6 (the jobs on 0) */
    const char *count_define =
        gk_counters_variant(&g->reduce_fetches, g->count_work, 1, 6, "#define REDUCE_COUNT_FETCHES 1\n");
    GLuint rp = gk_program_get_compute(pc, "lightmap/gather_reduce.comp", count_define, e);
    const reduce_uniforms *ru = rp ? gk_program_uniforms(pc, rp, GK_FIELDS(reduce_fields), sizeof *ru, e) : NULL;
    if (!ru) {
        gk_counters_end(&g->reduce_fetches);
        return -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, b1);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glViewport(0, 0, g->res * n, g->res);
    const GLuint zero[4] = {0, 0, 0, 0};
    glClearBufferuiv(GL_COLOR, 0, zero);
    const GLfloat far1 = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &far1);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    mat4 proj = lm_gather_proj(near, far);
    GLint packed[4 * (1 + LM_GATHER_MAX_TARGETS) * 64];
    int per = 4 * (1 + LM_GATHER_MAX_TARGETS);
    for (int t = 0; t < n; t++) {
        const lm_gather_job *j = &jobs[t];
        glViewport(g->res * t, 0, g->res, g->res);
        mat4 vp = m4_mul(proj, m4_look_at(j->eye, v3_add(j->eye, j->dir), j->up));
        if (draw(ctx, &vp, e)) {
            glDisable(GL_DEPTH_TEST);
            gk_counters_end(&g->reduce_fetches);
            return -1;
        }
    }
    glDisable(GL_DEPTH_TEST);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, g->jobs_ssbo);
    for (int base = 0; base < n; base += 64) {
        int m = n - base < 64 ? n - base : 64;
        memset(packed, 0, sizeof(GLint) * (size_t)(per * m));
        for (int t = 0; t < m; t++) {
            const lm_gather_job *j = &jobs[base + t];
            packed[per * t] = j->n_targets;
            for (int k = 0; k < j->n_targets; k++)
                packed[per * t + 4 * (k + 1)] = j->target[k][0], packed[per * t + 4 * (k + 1) + 1] = j->target[k][1];
        }
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, (GLintptr)(sizeof(GLint) * (size_t)(per * base)),
                        (GLsizeiptr)(sizeof(GLint) * (size_t)(per * m)), packed);
    }
    glUseProgram(rp);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, g->tiles);
    glUniform1i(ru->u_tiles, 0);
    glBindImageTexture(0, iim, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F); /* binding 0 in the shader */
    glUniform1i(ru->u_res, g->res);
    glUniform1f(ru->u_half_width, LM_GATHER_HALF_WIDTH);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, g->jobs_ssbo);
    glDispatchCompute((GLuint)n, 1, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    gk_counters_end(&g->reduce_fetches);
    return 0;
}
