/* Interleaved gather, geometry-aware blur and compose (thesis §6.5 steps 9–11); see the shaders in
 * shaders_gles/vpl/ for the formulas. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_target.h"
#include "vpl_internal.h"

static void free_ind(vpl_state *s)
{
    if (!s->ind_fbo)
        return;
    glDeleteFramebuffers(1, &s->ind_fbo);
    glDeleteFramebuffers(1, &s->blur_fbo);
    glDeleteFramebuffers(2, s->out_fbo);
    GLuint t[6] = {s->ind_tex, s->pos_tex, s->nrm_tex, s->blur_tex, s->out_tex[0], s->out_tex[1]};
    glDeleteTextures(6, t);
    s->ind_fbo = 0;
    s->have_hist = false;
    vpl_free_multires(s); /* its level 0 shares pos_tex/nrm_tex */
}

static int single_fbo(GLuint *fbo, GLuint tex, gk_err *e)
{
    glGenFramebuffers(1, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "vpl: indirect framebuffer incomplete");
    return 0;
}

static int ensure_ind(vpl_state *s, int w, int h, gk_err *e)
{
    if (s->ind_fbo && s->iw == w && s->ih == h)
        return 0;
    free_ind(s);
    s->iw = w, s->ih = h;
    /* RGBA32F, or RGBA16F without EXT_color_buffer_float: positions are stored relative to the
       bounds centre and irradiance is capped at vpl_target_max, so both fit fp16. */
    GLenum fmt = s->tgt_fmt;
    s->ind_tex = gk_texture_2d(fmt, w, h, GL_NEAREST);
    s->pos_tex = gk_texture_2d(fmt, w, h, GL_NEAREST);
    s->nrm_tex = gk_texture_2d(fmt, w, h, GL_NEAREST); /* also level 0 of the multires normal minimum */
    s->blur_tex = gk_texture_2d(fmt, w, h, GL_NEAREST);
    s->out_tex[0] = gk_texture_2d(fmt, w, h, GL_NEAREST);
    s->out_tex[1] = gk_texture_2d(fmt, w, h, GL_NEAREST);
    glGenFramebuffers(1, &s->ind_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->ind_fbo);
    GLuint t[3] = {s->ind_tex, s->pos_tex, s->nrm_tex};
    for (int i = 0; i < 3; i++)
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, t[i], 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "vpl: gather framebuffer %dx%d incomplete", w, h);
    if (single_fbo(&s->blur_fbo, s->blur_tex, e) || single_fbo(&s->out_fbo[0], s->out_tex[0], e) ||
        single_fbo(&s->out_fbo[1], s->out_tex[1], e))
        return -1;
    return 0;
}

void vpl_bind_tex(int unit, GLenum target, GLuint tex, GLuint prog, const char *name)
{
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(target, tex);
    gk_uniform_1i(prog, name, unit);
}

static void set_2i(GLuint prog, const char *name, int x, int y)
{
    GLint loc = glGetUniformLocation(prog, name);
    if (loc >= 0)
        glUniform2i(loc, x, y);
}

static void set_1i(GLuint prog, const char *name, int x)
{
    GLint loc = glGetUniformLocation(prog, name);
    if (loc >= 0)
        glUniform1i(loc, x);
}

/* Mean over pixels of gathered and removed luminance -> stats.clamp_removed (tests only). */
static void measure(vpl_state *s)
{
    float *px = malloc((size_t)s->iw * s->ih * 4 * sizeof(float));
    if (!px)
        return;
    glBindFramebuffer(GL_FRAMEBUFFER, s->ind_fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, s->iw, s->ih, GL_RGBA, GL_FLOAT, px);
    double kept = 0.0, removed = 0.0;
    for (int i = 0; i < s->iw * s->ih; i++) {
        kept += 0.2126 * px[i * 4] + 0.7152 * px[i * 4 + 1] + 0.0722 * px[i * 4 + 2];
        removed += px[i * 4 + 3];
    }
    s->st.clamp_removed = kept + removed > 0.0 ? removed / (kept + removed) : 0.0;
    free(px);
}

const char *vpl_vis_define(int vis)
{
    switch (vis) {
    case GK_VPL_VIS_CSSM: return "#define VIS_CSSM 1\n";
    case GK_VPL_VIS_VSM: return "#define VIS_VSM 1\n";
    case GK_VPL_VIS_EXACT: return "#define VIS_HARD 1\n";
    default: return "#define VIS_NONE 1\n";
    }
}

/* Interleaved gather at the indirect resolution into ind_tex (+ pos, nrm for the blur). */
static int interleaved(vpl_state *s, const gk_gi_frame *f, gk_err *e)
{
    int iw = s->iw, ih = s->ih;
    GLuint g = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/gather.frag", vpl_vis_define(s->vis), e);
    if (!g)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->ind_fbo);
    const GLenum b3[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDrawBuffers(3, b3);
    glViewport(0, 0, iw, ih);
    glUseProgram(g);
    vpl_bind_tex(0, GL_TEXTURE_2D, f->gbuf_depth, g, "u_gb_depth");
    vpl_bind_tex(1, GL_TEXTURE_2D, f->gbuf_normal, g, "u_gb_normal");
    vpl_bind_visibility(s, g);
    gk_uniform_mat4(g, "u_inv_viewproj", f->inv_view_proj.m);
    set_2i(g, "u_full_size", f->width, f->height);
    set_2i(g, "u_ind_size", iw, ih);
    set_1i(g, "u_n", s->n);
    set_1i(g, "u_block", s->block);
    gk_uniform_1f(g, "u_dmin2", s->clamp ? s->st.dmin * s->st.dmin : 0.0f);
    gk_uniform_3f(g, "u_origin", s->origin[0], s->origin[1], s->origin[2]);
    gk_uniform_1f(g, "u_out_max", vpl_target_max(s));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (s->dbg.measure)
        measure(s);
    return 0;
}

void vpl_bind_visibility(vpl_state *s, GLuint g)
{
    vpl_bind_tex(3, GL_TEXTURE_2D, s->vpl_tex, g, "u_vpl");
    vpl_bind_tex(4, GL_TEXTURE_2D, s->val_tex, g, "u_val");
    if (s->vis == GK_VPL_VIS_CSSM) {
        vpl_bind_tex(5, GL_TEXTURE_2D_ARRAY, s->bcos, g, "u_bcos");
        vpl_bind_tex(6, GL_TEXTURE_2D_ARRAY, s->bsin, g, "u_bsin");
        vpl_bind_tex(7, GL_TEXTURE_2D_ARRAY, s->bzcos, g, "u_bzcos");
        vpl_bind_tex(8, GL_TEXTURE_2D_ARRAY, s->bzsin, g, "u_bzsin");
        vpl_bind_tex(9, GL_TEXTURE_2D_ARRAY, s->z_arr, g, "u_bz");
    } else if (s->vis == GK_VPL_VIS_VSM) {
        vpl_bind_tex(5, GL_TEXTURE_2D_ARRAY, s->bmom, g, "u_bmom");
    } else if (s->vis == GK_VPL_VIS_EXACT) {
        vpl_bind_tex(9, GL_TEXTURE_2D_ARRAY, s->z_arr, g, "u_bz");
    }
}

int vpl_gather(vpl_state *s, const gk_gi_frame *f, float fade, gk_err *e)
{
    int iw = (int)lrintf((float)f->width * s->res_scale), ih = (int)lrintf((float)f->height * s->res_scale);
    iw = iw < 1 ? 1 : iw, ih = ih < 1 ? 1 : ih;
    if (ensure_ind(s, iw, ih, e))
        return -1;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(s->empty_vao);
    if (s->multires ? vpl_gather_multires(s, f, e) : interleaved(s, f, e))
        return -1;
    glBindVertexArray(s->empty_vao);
    glViewport(0, 0, s->iw, s->ih);

    /* Geometry-aware blur, horizontal into blur_tex, vertical into out_tex[cur]. */
    GLuint b = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/blur.frag", NULL, e);
    if (!b)
        return -1;
    glUseProgram(b);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    vpl_bind_tex(1, GL_TEXTURE_2D, s->pos_tex, b, "u_pos");
    vpl_bind_tex(2, GL_TEXTURE_2D, s->nrm_tex, b, "u_nrm");
    set_1i(b, "u_radius", s->blur_radius);
    gk_uniform_1f(b, "u_sigma", 0.1f * s->diam);  /* σ = 10% of the scene extent (§6.5) */
    gk_uniform_1f(b, "u_alpha", 0.8f);            /* α = 0.8 */
    int cur = s->cur;
    for (int pass = 0; pass < 2; pass++) {
        glBindFramebuffer(GL_FRAMEBUFFER, pass == 0 ? s->blur_fbo : s->out_fbo[cur]);
        glDrawBuffers(1, b1);
        vpl_bind_tex(0, GL_TEXTURE_2D, pass == 0 ? s->ind_tex : s->blur_tex, b, "u_ind");
        set_2i(b, "u_dir", pass == 0, pass == 1);
        vpl_bind_tex(3, GL_TEXTURE_2D, s->out_tex[1 - cur], b, "u_hist");
        gk_uniform_1f(b, "u_fade", pass == 1 && s->have_hist ? fade : 1.0f);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

    /* Compose: L += ρ_d/π · E into the renderer's HDR image. */
    GLuint c = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/compose.frag", NULL, e);
    if (!c)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr_fbo);
    glDrawBuffers(1, b1);
    glViewport(0, 0, f->width, f->height);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(c);
    vpl_bind_tex(0, GL_TEXTURE_2D, s->out_tex[cur], c, "u_ind");
    vpl_bind_tex(2, GL_TEXTURE_2D, s->pos_tex, c, "u_pos");
    vpl_bind_tex(3, GL_TEXTURE_2D, s->nrm_tex, c, "u_nrm");
    vpl_bind_tex(4, GL_TEXTURE_2D, f->gbuf_depth, c, "u_gb_depth");
    vpl_bind_tex(5, GL_TEXTURE_2D, f->gbuf_normal, c, "u_gb_normal");
    vpl_bind_tex(6, GL_TEXTURE_2D, f->gbuf_albedo, c, "u_gb_albedo");
    gk_uniform_mat4(c, "u_inv_viewproj", f->inv_view_proj.m);
    set_2i(c, "u_full_size", f->width, f->height);
    gk_uniform_1f(c, "u_sigma", 0.05f * s->diam);
    gk_uniform_3f(c, "u_origin", s->origin[0], s->origin[1], s->origin[2]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glBindVertexArray(0);
    glActiveTexture(GL_TEXTURE0);
    /* out_tex[cur] holds what was shown (the crossfade already mixed in): next frame's history. */
    s->cur = 1 - cur;
    s->have_hist = true;
    return 0;
}

void vpl_free_gpu(vpl_state *s)
{
    free_ind(s);
    vpl_free_multires(s);
    vpl_free_maps(s);
    if (s->rsm_fbo) {
        glDeleteFramebuffers(1, &s->rsm_fbo);
        glDeleteTextures(3, s->rsm_tex);
        glDeleteRenderbuffers(1, &s->rsm_depth);
    }
    if (s->gen_fbo) {
        glDeleteFramebuffers(1, &s->gen_fbo);
        glDeleteTextures(3, s->gen_tex);
    }
    GLuint t[2] = {s->vpl_tex, s->val_tex};
    glDeleteTextures(2, t);
    GLuint f[2] = {s->map_fbo, s->basis_fbo};
    glDeleteFramebuffers(2, f);
    if (s->empty_vao)
        glDeleteVertexArrays(1, &s->empty_vao);
    if (s->have_proxy)
        vpl_proxy_free(&s->proxy);
}
