/* Interleaved gather, geometry-aware blur and compose (thesis §6.5 steps 9–11); see the shaders in
 * shaders_gles/vpl/ for the formulas. */
#include <math.h>
#include <stdio.h>
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

void vpl_bind_tex(int unit, GLenum target, GLuint tex, GLint loc)
{
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(target, tex);
    glUniform1i(loc, unit);
}

static const gk_uniform_field gather_fields[] = {
    GK_GBUFFER_FIELDS(vpl_gather_uniforms, gb),
    GK_UNIFORM(vpl_gather_uniforms, u_ind_size),
    GK_UNIFORM(vpl_gather_uniforms, u_vpl),
    GK_UNIFORM(vpl_gather_uniforms, u_val),
    GK_UNIFORM(vpl_gather_uniforms, u_n),
    GK_UNIFORM(vpl_gather_uniforms, u_block),
    GK_UNIFORM(vpl_gather_uniforms, u_dmin2),
    GK_UNIFORM(vpl_gather_uniforms, u_origin),
    GK_UNIFORM(vpl_gather_uniforms, u_out_max),
    GK_UNIFORM(vpl_gather_uniforms, u_bcos),
    GK_UNIFORM(vpl_gather_uniforms, u_bsin),
    GK_UNIFORM(vpl_gather_uniforms, u_bzcos),
    GK_UNIFORM(vpl_gather_uniforms, u_bzsin),
    GK_UNIFORM(vpl_gather_uniforms, u_bz),
    GK_UNIFORM(vpl_gather_uniforms, u_bmom),
    GK_UNIFORM(vpl_gather_uniforms, u_bzmax),
    GK_UNIFORM(vpl_gather_uniforms, u_bplane),
    GK_UNIFORM(vpl_gather_uniforms, u_umbra),
    GK_UNIFORM(vpl_gather_uniforms, u_lift),
    GK_UNIFORM(vpl_gather_uniforms, u_n_val),
    GK_UNIFORM_AS(vpl_gather_uniforms, u_mr_t[0], "u_mr_t0"),
    GK_UNIFORM_AS(vpl_gather_uniforms, u_mr_t[1], "u_mr_t1"),
    GK_UNIFORM_AS(vpl_gather_uniforms, u_mr_t[2], "u_mr_t2"),
    GK_UNIFORM_AS(vpl_gather_uniforms, u_mr_t[3], "u_mr_t3"),
    GK_UNIFORM_AS(vpl_gather_uniforms, u_mr_p[0], "u_mr_p0"),
    GK_UNIFORM_AS(vpl_gather_uniforms, u_mr_p[1], "u_mr_p1"),
    GK_UNIFORM_AS(vpl_gather_uniforms, u_mr_p[2], "u_mr_p2"),
    GK_UNIFORM(vpl_gather_uniforms, u_mr_level),
    GK_UNIFORM(vpl_gather_uniforms, u_mr_top),
    GK_UNIFORM(vpl_gather_uniforms, u_tau_z),
    GK_UNIFORM(vpl_gather_uniforms, u_tau_n),
};

const vpl_gather_uniforms *vpl_gather_uniforms_of(vpl_state *s, GLuint prog, gk_err *e)
{
    return gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(gather_fields), sizeof(vpl_gather_uniforms), e);
}

/* vpl/blur.frag */
typedef struct blur_uniforms {
    GLint u_ind, u_pos, u_nrm, u_dir, u_radius, u_sigma, u_alpha, u_hist, u_fade;
} blur_uniforms;
static const gk_uniform_field blur_fields[] = {
    GK_UNIFORM(blur_uniforms, u_ind),    GK_UNIFORM(blur_uniforms, u_pos),   GK_UNIFORM(blur_uniforms, u_nrm),
    GK_UNIFORM(blur_uniforms, u_dir),    GK_UNIFORM(blur_uniforms, u_radius), GK_UNIFORM(blur_uniforms, u_sigma),
    GK_UNIFORM(blur_uniforms, u_alpha),  GK_UNIFORM(blur_uniforms, u_hist),  GK_UNIFORM(blur_uniforms, u_fade),
};

/* vpl/compose.frag */
typedef struct compose_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_ind, u_pos, u_nrm, u_sigma, u_origin;
} compose_uniforms;
static const gk_uniform_field compose_fields[] = {
    GK_GBUFFER_FIELDS(compose_uniforms, gb), GK_UNIFORM(compose_uniforms, u_ind),   GK_UNIFORM(compose_uniforms, u_pos),
    GK_UNIFORM(compose_uniforms, u_nrm),     GK_UNIFORM(compose_uniforms, u_sigma), GK_UNIFORM(compose_uniforms, u_origin),
};

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

#define VPL_STR_(x) #x
#define VPL_STR(x) VPL_STR_(x)
const char *vpl_per_val_define(vpl_state *s, bool multires)
{
    int bb = s->block * s->block;
    int per_receiver = multires ? s->n : (s->n + bb - 1) / bb;
    s->st.vis_per_val = (s->vis == GK_VPL_VIS_CSSM || s->vis == GK_VPL_VIS_VSM) && !s->dbg.vis_per_vpl &&
                        s->st.m > 0 && s->st.m <= GK_VPL_MAX_M && s->st.m < per_receiver;
    return s->st.vis_per_val ? "#define VIS_PER_VAL " VPL_STR(GK_VPL_MAX_M) "\n" : "";
}

/* Interleaved gather at the indirect resolution into ind_tex (+ pos, nrm for the blur). */
static int interleaved(vpl_state *s, const gk_gi_frame *f, gk_err *e)
{
    int iw = s->iw, ih = s->ih;
    char defines[160];
    snprintf(defines, sizeof defines, "%s%s%s", vpl_vis_define(s->vis), vpl_per_val_define(s, false), vpl_work_begin(s, f));
    GLuint g = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/gather.frag", defines, e);
    const vpl_gather_uniforms *u = g ? vpl_gather_uniforms_of(s, g, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->ind_fbo);
    const GLenum b3[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDrawBuffers(3, b3);
    glViewport(0, 0, iw, ih);
    glUseProgram(g);
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gb, &u->gb, VPL_GATHER_GBUFFER_UNIT, 0);
    vpl_bind_visibility(s, u);
    glUniform2i(u->u_ind_size, iw, ih);
    glUniform1i(u->u_n, s->n);
    glUniform1i(u->u_block, s->block);
    glUniform1f(u->u_dmin2, s->clamp ? s->st.dmin * s->st.dmin : 0.0f);
    glUniform3f(u->u_origin, s->origin[0], s->origin[1], s->origin[2]);
    glUniform1f(u->u_out_max, vpl_target_max(s));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    vpl_work_end(s);
    if (s->dbg.measure)
        measure(s);
    return 0;
}

void vpl_bind_visibility(vpl_state *s, const vpl_gather_uniforms *u)
{
    vpl_bind_tex(3, GL_TEXTURE_2D, s->vpl_tex, u->u_vpl);
    vpl_bind_tex(4, GL_TEXTURE_2D, s->val_tex, u->u_val);
    if (s->vis == GK_VPL_VIS_CSSM) {
        vpl_bind_tex(5, GL_TEXTURE_2D_ARRAY, s->bcos, u->u_bcos);
        vpl_bind_tex(6, GL_TEXTURE_2D_ARRAY, s->bsin, u->u_bsin);
        vpl_bind_tex(7, GL_TEXTURE_2D_ARRAY, s->bzcos, u->u_bzcos);
        vpl_bind_tex(8, GL_TEXTURE_2D_ARRAY, s->bzsin, u->u_bzsin);
        vpl_bind_tex(9, GL_TEXTURE_2D_ARRAY, s->z_arr, u->u_bz);
    } else if (s->vis == GK_VPL_VIS_VSM) {
        vpl_bind_tex(5, GL_TEXTURE_2D_ARRAY, s->bmom, u->u_bmom);
    } else if (s->vis == GK_VPL_VIS_EXACT) {
        vpl_bind_tex(9, GL_TEXTURE_2D_ARRAY, s->z_arr, u->u_bz);
    }
    /* Always on its own unit: left at unit 0 it would share it with a sampler2D of the multires
       gather. With vpl_umbra=off the chain is not built and the shader does not read it. */
    vpl_bind_tex(14, GL_TEXTURE_2D_ARRAY, s->zmax, u->u_bzmax);
    vpl_bind_tex(15, GL_TEXTURE_2D_ARRAY, s->zplane, u->u_bplane);
    glUniform1i(u->u_umbra, s->zmax != 0 && s->vis != GK_VPL_VIS_EXACT ? s->map_umbra : VPL_UMBRA_OFF);
    glUniform1f(u->u_lift, vpl_lift(s));
    glUniform1i(u->u_n_val, s->st.m); /* VIS_PER_VAL's loop (absent from the other variants: -1, ignored) */
}

/* The gather (interleaved, or multires) at the indirect resolution into ind_tex, pos_tex, nrm_tex. */
static int gather(vpl_state *s, const gk_gi_frame *f, gk_err *e)
{
    int iw = (int)lrintf((float)f->width * s->res_scale), ih = (int)lrintf((float)f->height * s->res_scale);
    iw = iw < 1 ? 1 : iw, ih = ih < 1 ? 1 : ih;
    if (ensure_ind(s, iw, ih, e))
        return -1;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(s->empty_vao);
    return s->multires ? vpl_gather_multires(s, f, e) : interleaved(s, f, e);
}

/* Geometry-aware blur, horizontal into blur_tex, vertical into out_tex[cur]. */
static int blur(vpl_state *s, const gk_gi_frame *f, float fade, gk_err *e)
{
    glBindVertexArray(s->empty_vao);
    glViewport(0, 0, s->iw, s->ih);
    GLuint b = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/blur.frag", vpl_work_blur_begin(s, f), e);
    const blur_uniforms *ub = b ? gk_program_uniforms(s->ctx.programs, b, GK_FIELDS(blur_fields), sizeof *ub, e) : NULL;
    if (!ub) {
        vpl_work_blur_end(s);
        return -1;
    }
    glUseProgram(b);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    vpl_bind_tex(1, GL_TEXTURE_2D, s->pos_tex, ub->u_pos);
    vpl_bind_tex(2, GL_TEXTURE_2D, s->nrm_tex, ub->u_nrm);
    glUniform1i(ub->u_radius, s->blur_radius);
    glUniform1f(ub->u_sigma, 0.1f * s->diam);  /* σ = 10% of the scene extent (§6.5) */
    glUniform1f(ub->u_alpha, 0.8f);            /* α = 0.8 */
    int cur = s->cur;
    for (int pass = 0; pass < 2; pass++) {
        glBindFramebuffer(GL_FRAMEBUFFER, pass == 0 ? s->blur_fbo : s->out_fbo[cur]);
        glDrawBuffers(1, b1);
        vpl_bind_tex(0, GL_TEXTURE_2D, pass == 0 ? s->ind_tex : s->blur_tex, ub->u_ind);
        glUniform2i(ub->u_dir, pass == 0, pass == 1);
        vpl_bind_tex(3, GL_TEXTURE_2D, s->out_tex[1 - cur], ub->u_hist);
        glUniform1f(ub->u_fade, pass == 1 && s->have_hist ? fade : 1.0f);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    vpl_work_blur_end(s);
    return 0;
}

/* Compose: L += ρ_d/π · E into the renderer's HDR image. */
static int compose(vpl_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint c = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/compose.frag", vpl_work_compose_begin(s, f),
                              e);
    const compose_uniforms *uc = c ? gk_program_uniforms(s->ctx.programs, c, GK_FIELDS(compose_fields), sizeof *uc, e) : NULL;
    if (!uc) {
        vpl_work_compose_end(s);
        return -1;
    }
    int cur = s->cur;
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr_fbo);
    glDrawBuffers(1, b1);
    glViewport(0, 0, f->width, f->height);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(c);
    vpl_bind_tex(0, GL_TEXTURE_2D, s->out_tex[cur], uc->u_ind);
    vpl_bind_tex(2, GL_TEXTURE_2D, s->pos_tex, uc->u_pos);
    vpl_bind_tex(3, GL_TEXTURE_2D, s->nrm_tex, uc->u_nrm);
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gb, &uc->gb, 4, 0);
    glUniform1f(uc->u_sigma, 0.05f * s->diam);
    glUniform3f(uc->u_origin, s->origin[0], s->origin[1], s->origin[2]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    vpl_work_compose_end(s);
    glDisable(GL_BLEND);
    glBindVertexArray(0);
    glActiveTexture(GL_TEXTURE0);
    /* out_tex[cur] holds what was shown (the crossfade already mixed in): next frame's history. */
    s->cur = 1 - cur;
    s->have_hist = true;
    return 0;
}

/* Steps 9-11, each a pass of the renderer's clock (nested under `gi`), so that each has its own
   time beside its own work model (vpl_work.c). */
int vpl_gather(vpl_state *s, const gk_gi_frame *f, float fade, gk_err *e)
{
    gk_pass_begin(f->pass, "vpl_gather");
    int rc = gather(s, f, e);
    gk_pass_end(f->pass);
    if (rc == 0) {
        gk_pass_begin(f->pass, "vpl_blur");
        rc = blur(s, f, fade, e);
        gk_pass_end(f->pass);
    }
    if (rc == 0) {
        gk_pass_begin(f->pass, "vpl_compose");
        rc = compose(s, f, e);
        gk_pass_end(f->pass);
    }
    return rc;
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
