/* The SSLGV (seed 002 §4.3): caustic photons into a screen grid at reduced resolution
 * (lgv_sslgv knob: its width; height by the view's aspect), LGV_SSLGV_ITERS depth-aware gathering
 * iterations, then the RGBA16F images the lookup reads; and the lookup itself (eq. 7 and the
 * SSLGV's footprint normalisation), added to the HDR image. */
#include <math.h>
#include <string.h>

#include "lgv_internal.h"

typedef struct inject_uniforms {
    GLint u_gb_depth, u_gb_normal, u_viewproj, u_inv_viewproj, u_size, u_h, u_fixed, u_cap;
} inject_uniforms;
static const gk_uniform_field inject_fields[] = {
    GK_UNIFORM(inject_uniforms, u_gb_depth), GK_UNIFORM(inject_uniforms, u_gb_normal),
    GK_UNIFORM(inject_uniforms, u_viewproj), GK_UNIFORM(inject_uniforms, u_inv_viewproj),
    GK_UNIFORM(inject_uniforms, u_size),     GK_UNIFORM(inject_uniforms, u_h),
    GK_UNIFORM(inject_uniforms, u_fixed),    GK_UNIFORM(inject_uniforms, u_cap),
};
typedef struct ss_gather_uniforms {
    GLint u_gb_depth, u_inv_viewproj, u_size, u_h, u_fixed, u_from_ints;
} ss_gather_uniforms;
static const gk_uniform_field ss_gather_fields[] = {
    GK_UNIFORM(ss_gather_uniforms, u_gb_depth), GK_UNIFORM(ss_gather_uniforms, u_inv_viewproj),
    GK_UNIFORM(ss_gather_uniforms, u_size),     GK_UNIFORM(ss_gather_uniforms, u_h),
    GK_UNIFORM(ss_gather_uniforms, u_fixed),    GK_UNIFORM(ss_gather_uniforms, u_from_ints),
};
typedef struct ss_image_uniforms {
    GLint u_size;
} ss_image_uniforms;
static const gk_uniform_field ss_image_fields[] = {GK_UNIFORM(ss_image_uniforms, u_size)};

static int ensure_screen(lgv_state *s, const gk_gi_frame *f)
{
    int w = s->ss_width, h = (int)lroundf((float)w * (float)f->height / (float)(f->width > 0 ? f->width : 1));
    h = h < 1 ? 1 : h;
    if (s->ss_grid && s->ss_w == w && s->ss_h == h)
        return 0;
    s->ss_w = w, s->ss_h = h;
    long bytes = (long)w * h * 48;
    s->ss_grid = lgv_buffer(s->ss_grid, bytes, true);
    s->ss_a = lgv_buffer(s->ss_a, bytes, false);
    s->ss_b = lgv_buffer(s->ss_b, bytes, false);
    glDeleteTextures(3, s->ss_img);
    glGenTextures(3, s->ss_img);
    for (int i = 0; i < 3; i++) {
        glBindTexture(GL_TEXTURE_2D, s->ss_img[i]);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA16F, w, h);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    return 0;
}

static void bind_depth(const gk_gi_frame *f, GLint loc, int unit, GLuint tex)
{
    (void)f;
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(loc, unit);
}

int lgv_sslgv(lgv_state *s, const gk_gi_frame *f, gk_err *e)
{
    ensure_screen(s, f);
    gk_program_cache *pc = s->ctx.programs;
    GLuint inj = gk_program_get_compute(pc, "lgv/sslgv_inject.comp", NULL, e);
    const inject_uniforms *iu = inj ? gk_program_uniforms(pc, inj, GK_FIELDS(inject_fields), sizeof *iu, e) : NULL;
    const char *count = lgv_work_begin(s, LGV_WORK_SSLGV);
    GLuint gat = iu ? gk_program_get_compute(pc, "lgv/sslgv_gather.comp", count, e) : 0;
    const ss_gather_uniforms *gu = gat ? gk_program_uniforms(pc, gat, GK_FIELDS(ss_gather_fields), sizeof *gu, e) : NULL;
    GLuint img = gu ? gk_program_get_compute(pc, "lgv/sslgv_image.comp", NULL, e) : 0;
    const ss_image_uniforms *mu = img ? gk_program_uniforms(pc, img, GK_FIELDS(ss_image_fields), sizeof *mu, e) : NULL;
    if (!mu)
        return -1;
    long bytes = (long)s->ss_w * s->ss_h * 48;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->ss_grid);
    void *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, bytes, GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
    if (p) {
        memset(p, 0, (size_t)bytes);
        glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    }
    /* h = C0 sqrt(A / (p N)): A the scene's surface area, N the photons cast, p = 1 */
    s->h = s->dbg.c0 * sqrtf(s->area / (float)(s->photons > 0 ? s->photons : 1));
    glUseProgram(inj);
    bind_depth(f, iu->u_gb_depth, 0, f->gbuf_depth);
    bind_depth(f, iu->u_gb_normal, 1, f->gbuf_normal);
    glUniformMatrix4fv(iu->u_viewproj, 1, GL_FALSE, f->view_proj.m);
    glUniformMatrix4fv(iu->u_inv_viewproj, 1, GL_FALSE, f->inv_view_proj.m);
    glUniform2i(iu->u_size, s->ss_w, s->ss_h);
    glUniform1f(iu->u_h, s->h);
    glUniform1f(iu->u_fixed, s->fixed_scale);
    glUniform1i(iu->u_cap, s->caustic_cap);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s->caustic_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s->stats_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, s->ss_grid);
    glDispatchCompute((GLuint)(s->caustic_cap + 63) / 64, 1, 1);
    glUseProgram(gat);
    bind_depth(f, gu->u_gb_depth, 0, f->gbuf_depth);
    glUniformMatrix4fv(gu->u_inv_viewproj, 1, GL_FALSE, f->inv_view_proj.m);
    glUniform2i(gu->u_size, s->ss_w, s->ss_h);
    glUniform1f(gu->u_h, s->h);
    glUniform1f(gu->u_fixed, s->fixed_scale);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, s->ss_grid);
    GLuint a = s->ss_a, b = s->ss_b;
    int iters = s->dbg.sslgv_iters > 0 ? s->dbg.sslgv_iters : LGV_SSLGV_ITERS;
    for (int it = 0; it < iters; it++) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUniform1i(gu->u_from_ints, it == 0 ? 1 : 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, a);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, b);
        glDispatchCompute((GLuint)(s->ss_w + 7) / 8, (GLuint)(s->ss_h + 7) / 8, 1);
        GLuint t = a;
        a = b, b = t;
    }
    lgv_work_end(s, LGV_WORK_SSLGV);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(img);
    glUniform2i(mu->u_size, s->ss_w, s->ss_h);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, a);
    for (int i = 0; i < 3; i++)
        glBindImageTexture((GLuint)i, s->ss_img[i], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute((GLuint)(s->ss_w + 7) / 8, (GLuint)(s->ss_h + 7) / 8, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    return 0;
}

/* lgv/lookup.frag */
typedef struct lookup_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_vol_r, u_vol_g, u_vol_b, u_ss_r, u_ss_g, u_ss_b, u_grid_min, u_grid_size, u_cell, u_ss_size, u_tan_half,
        u_forward, u_parts, u_offset, u_own_cell;
} lookup_uniforms;
static const gk_uniform_field lookup_fields[] = {
    GK_GBUFFER_FIELDS(lookup_uniforms, gb),
    GK_UNIFORM(lookup_uniforms, u_vol_r),     GK_UNIFORM(lookup_uniforms, u_vol_g),
    GK_UNIFORM(lookup_uniforms, u_vol_b),     GK_UNIFORM(lookup_uniforms, u_ss_r),
    GK_UNIFORM(lookup_uniforms, u_ss_g),      GK_UNIFORM(lookup_uniforms, u_ss_b),
    GK_UNIFORM(lookup_uniforms, u_grid_min),  GK_UNIFORM(lookup_uniforms, u_grid_size),
    GK_UNIFORM(lookup_uniforms, u_cell),      GK_UNIFORM(lookup_uniforms, u_ss_size),
    GK_UNIFORM(lookup_uniforms, u_tan_half),  GK_UNIFORM(lookup_uniforms, u_forward),
    GK_UNIFORM(lookup_uniforms, u_parts),     GK_UNIFORM(lookup_uniforms, u_offset),
    GK_UNIFORM(lookup_uniforms, u_own_cell),
};

int lgv_lookup(lgv_state *s, const gk_gi_frame *f, gk_err *e)
{
    const char *count = lgv_work_begin(s, LGV_WORK_LOOKUP);
    GLuint prog = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "lgv/lookup.frag", count, e);
    const lookup_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(lookup_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr_fbo);
    glViewport(0, 0, f->width, f->height);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(prog);
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gb, &u->gb, 0, 0);
    const int unit = GK_GBUFFER_UNITS;
    for (int i = 0; i < 3; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)(unit + i));
        glBindTexture(GL_TEXTURE_3D, s->vol[i]);
        glActiveTexture(GL_TEXTURE0 + (GLenum)(unit + 3 + i));
        glBindTexture(GL_TEXTURE_2D, s->ss_img[i]);
    }
    glUniform1i(u->u_vol_r, unit), glUniform1i(u->u_vol_g, unit + 1), glUniform1i(u->u_vol_b, unit + 2);
    glUniform1i(u->u_ss_r, unit + 3), glUniform1i(u->u_ss_g, unit + 4), glUniform1i(u->u_ss_b, unit + 5);
    glUniform3f(u->u_grid_min, s->grid_min.x, s->grid_min.y, s->grid_min.z);
    glUniform3f(u->u_grid_size, s->cell * (float)s->dims[0], s->cell * (float)s->dims[1], s->cell * (float)s->dims[2]);
    glUniform1f(u->u_cell, s->cell);
    glUniform1f(u->u_offset, s->dbg.lookup_offset);
    glUniform1i(u->u_own_cell, s->dbg.lookup_own_cell ? 1 : 0);
    glUniform2f(u->u_ss_size, (float)s->ss_w, (float)s->ss_h);
    /* proj[0][0] = 1 / tan(fov_x / 2), proj[1][1] = 1 / tan(fov_y / 2) */
    glUniform2f(u->u_tan_half, 1.0f / f->proj.m[0], 1.0f / f->proj.m[5]);
    /* camera forward: -z of the view, the third row of its rotation */
    vec3 fw = v3_norm(v3(-f->view.m[2], -f->view.m[6], -f->view.m[10]));
    glUniform3f(u->u_forward, fw.x, fw.y, fw.z);
    glUniform1i(u->u_parts, s->dbg.parts);
    if (!s->empty_vao)
        glGenVertexArrays(1, &s->empty_vao);
    glBindVertexArray(s->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    lgv_work_end(s, LGV_WORK_LOOKUP);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    return 0;
}
