/* Seed 000 pass 10: every fragment of the camera frustum at the trace resolution, as per-pixel
 * linked lists (tier A: fragment-shader SSBO atomics, Algorithm 3.4) or as K depth-peeled layers
 * turned into the same lists (tier B: core GLES 3.0 rendering, for GPUs without fragment storage
 * blocks, which GLES 3.1 does not guarantee). shaders_gles/ispm/ll_*.{vert,frag,comp}, peel*. */
#include <string.h>

#include "ispm_internal.h"

/* Tier A needs 3 fragment-stage storage blocks (nodes, pixels, counter); the research's probe asks
 * for 4 (photon-mapping-000-004.md A.5), and so do we. GLES 3.1 guarantees 0. */
bool ispm_probe_lists(int gles_version)
{
    (void)gles_version;
    GLint frag_blocks = 0, block_size = 0;
    glGetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &frag_blocks);
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block_size);
    return frag_blocks >= 4 && block_size >= (1 << 20);
}

typedef struct clear_uniforms { GLint u_pixels; } clear_uniforms;
static const gk_uniform_field clear_fields[] = {GK_UNIFORM(clear_uniforms, u_pixels)};
typedef struct build_uniforms { GLint u_viewproj, u_width; } build_uniforms;
static const gk_uniform_field build_fields[] = {GK_UNIFORM(build_uniforms, u_viewproj), GK_UNIFORM(build_uniforms, u_width)};
typedef struct peel_uniforms { GLint u_viewproj, u_prev, u_layer; } peel_uniforms;
static const gk_uniform_field peel_fields[] = {GK_UNIFORM(peel_uniforms, u_viewproj), GK_UNIFORM(peel_uniforms, u_prev),
                                               GK_UNIFORM(peel_uniforms, u_layer)};
typedef struct pl_uniforms { GLint u_layers, u_width, u_height, u_k; } pl_uniforms;
static const gk_uniform_field pl_fields[] = {GK_UNIFORM_AS(pl_uniforms, u_layers, "u_layers[0]"), GK_UNIFORM(pl_uniforms, u_width),
                                             GK_UNIFORM(pl_uniforms, u_height), GK_UNIFORM(pl_uniforms, u_k)};

static void ensure_buffers(ispm_state *s)
{
    int res = s->trace_res;
    long nodes = s->tier == GK_ISPM_TIER_PEEL ? (long)res * res * ISPM_PEEL_LAYERS
                 : s->dbg.pool_nodes > 0 ? s->dbg.pool_nodes : s->pool_bytes / ISPM_NODE_BYTES;
    if (!s->nodes_ssbo || nodes != s->nodes_cap) {
        if (!s->nodes_ssbo)
            glGenBuffers(1, &s->nodes_ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->nodes_ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, nodes * ISPM_NODE_BYTES, NULL, GL_DYNAMIC_COPY);
        s->nodes_cap = nodes;
    }
    if (!s->pixels_ssbo || s->ll_res != res) {
        if (!s->pixels_ssbo)
            glGenBuffers(1, &s->pixels_ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->pixels_ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, (long)res * res * 16, NULL, GL_DYNAMIC_COPY);
        s->ll_res = res;
    }
    if (!s->ctr_ssbo) {
        glGenBuffers(1, &s->ctr_ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->ctr_ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, 16, NULL, GL_DYNAMIC_COPY);
    }
}

static int build_tier_a(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    int res = s->trace_res;
    GLuint cp = gk_program_get_compute(s->ctx.programs, "ispm/ll_clear.comp", NULL, e);
    const clear_uniforms *cu = cp ? gk_program_uniforms(s->ctx.programs, cp, GK_FIELDS(clear_fields), sizeof *cu, e) : NULL;
    GLuint bp = cu ? gk_program_get(s->ctx.programs, "ispm/ll_build.vert", "ispm/ll_build.frag", NULL, e) : 0;
    const build_uniforms *bu = bp ? gk_program_uniforms(s->ctx.programs, bp, GK_FIELDS(build_fields), sizeof *bu, e) : NULL;
    if (!bu)
        return -1;
    unsigned ctr[4] = {0, (unsigned)s->nodes_cap, 0, 0};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->ctr_ssbo);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof ctr, ctr);
    glUseProgram(cp);
    glUniform1i(cu->u_pixels, res * res);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s->pixels_ssbo);
    glDispatchCompute((GLuint)(res * res + 63) / 64, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (!s->ll_fbo) {
        /* attachment-less: the fragments only write storage buffers */
        glGenFramebuffers(1, &s->ll_fbo);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, s->ll_fbo);
    glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, res);
    glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, res);
    glViewport(0, 0, res, res);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(bp);
    glUniformMatrix4fv(bu->u_viewproj, 1, GL_FALSE, f->view_proj.m);
    glUniform1i(bu->u_width, res);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s->nodes_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s->pixels_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s->ctr_ssbo);
    int rc = f->draw_scene(f->draw_ctx, bp, e);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return rc;
}

static int ensure_peel(ispm_state *s, gk_err *e)
{
    int res = s->trace_res;
    if (s->peel_fbo && s->peel_res == res)
        return 0;
    if (s->peel_fbo) {
        glDeleteFramebuffers(1, &s->peel_fbo);
        glDeleteTextures(ISPM_PEEL_LAYERS, s->peel_tex);
        glDeleteRenderbuffers(1, &s->peel_depth);
    }
    /* one texture per layer, not an array: sampling layer k-1 of an array while layer k of it is
       attached is a feedback loop by the letter of the spec */
    glGenTextures(ISPM_PEEL_LAYERS, s->peel_tex);
    for (int k = 0; k < ISPM_PEEL_LAYERS; k++) {
        glBindTexture(GL_TEXTURE_2D, s->peel_tex[k]);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32UI, res, res);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glGenRenderbuffers(1, &s->peel_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, s->peel_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, res, res);
    glGenFramebuffers(1, &s->peel_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->peel_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s->peel_depth);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s->peel_tex[0], 0);
    GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "ispm: depth-peeling target incomplete (0x%04x)", st);
    s->peel_res = res;
    return 0;
}

static int build_tier_b(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    int res = s->trace_res;
    if (ensure_peel(s, e))
        return -1;
    GLuint pp = gk_program_get(s->ctx.programs, "ispm/ll_build.vert", "ispm/peel.frag", NULL, e);
    const peel_uniforms *pu = pp ? gk_program_uniforms(s->ctx.programs, pp, GK_FIELDS(peel_fields), sizeof *pu, e) : NULL;
    GLuint lp = pu ? gk_program_get_compute(s->ctx.programs, "ispm/peel_lists.comp", NULL, e) : 0;
    const pl_uniforms *lu = lp ? gk_program_uniforms(s->ctx.programs, lp, GK_FIELDS(pl_fields), sizeof *lu, e) : NULL;
    if (!lu)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->peel_fbo);
    const GLenum b0 = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &b0);
    glViewport(0, 0, res, res);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(pp);
    glUniformMatrix4fv(pu->u_viewproj, 1, GL_FALSE, f->view_proj.m);
    glUniform1i(pu->u_prev, 0);
    const GLuint zero[4] = {0, 0, 0, 0};
    int rc = 0;
    for (int k = 0; k < ISPM_PEEL_LAYERS && !rc; k++) {
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s->peel_tex[k], 0);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, k > 0 ? s->peel_tex[k - 1] : 0);
        glClearBufferuiv(GL_COLOR, 0, zero);
        glClearDepthf(1.0f);
        glClear(GL_DEPTH_BUFFER_BIT);
        glUniform1i(pu->u_layer, k);
        rc = f->draw_scene(f->draw_ctx, pp, e);
    }
    glDisable(GL_DEPTH_TEST);
    if (rc)
        return -1;
    glUseProgram(lp);
    GLint units[ISPM_PEEL_LAYERS];
    for (int k = 0; k < ISPM_PEEL_LAYERS; k++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)k);
        glBindTexture(GL_TEXTURE_2D, s->peel_tex[k]);
        units[k] = k;
    }
    glUniform1iv(lu->u_layers, ISPM_PEEL_LAYERS, units);
    glUniform1i(lu->u_width, res);
    glUniform1i(lu->u_height, res);
    glUniform1i(lu->u_k, ISPM_PEEL_LAYERS);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s->nodes_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s->pixels_ssbo);
    glDispatchCompute((GLuint)(res + 7) / 8, (GLuint)(res + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    unsigned ctr[4] = {0, (unsigned)s->nodes_cap, 0, 0};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->ctr_ssbo);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof ctr, ctr);
    return 0;
}

int ispm_build_lists(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    ensure_buffers(s);
    s->view = f->view, s->proj = f->proj;
    return s->tier == GK_ISPM_TIER_LISTS ? build_tier_a(s, f, e) : build_tier_b(s, f, e);
}
