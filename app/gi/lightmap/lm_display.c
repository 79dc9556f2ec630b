/* The lightmap method's GPU side: the atlas's vertices, the irradiance texture, the light-map UV
 * pass and the compose pass (shaders_gles/lightmap/). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lm_internal.h"

int lm_display_setup(lm_state *s, gk_err *e)
{
    const lm_atlas *a = &s->atlas;
    glGenVertexArrays(1, &s->vao);
    glBindVertexArray(s->vao);
    glGenBuffers(1, &s->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, s->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * LM_VERT_FLOATS * (size_t)a->n_verts), a->verts,
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, LM_VERT_FLOATS * sizeof(float), (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, LM_VERT_FLOATS * sizeof(float), (void *)(3 * sizeof(float)));
    glBindVertexArray(0);
    glGenVertexArrays(1, &s->empty_vao);
    /* RGBA16F: filterable on the GLES 3.1 floor (32F needs OES_texture_float_linear); the values are
       stored divided by the atlas's largest, so any scene's units fit */
    glGenTextures(1, &s->irr_tex);
    glBindTexture(GL_TEXTURE_2D, s->irr_tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA16F, a->width, a->height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    s->irr_scale = 0.0f;
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "lightmap: GL error 0x%04x creating the %dx%d atlas", err, a->width, a->height);
    return 0;
}

/* Called by lm_worker_take under the pool's lock with the newest atlas. */
void lm_display_upload(void *state, const float *irr)
{
    lm_state *s = state;
    const lm_atlas *a = &s->atlas;
    size_t n = (size_t)a->width * (size_t)a->height;
    float top = 0.0f;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            top = fmaxf(top, irr[4 * i + (size_t)c]);
    float *buf = malloc(sizeof(float) * 4 * n);
    if (!buf)
        return; /* the frame keeps the previous atlas */
    float inv = top > 0.0f ? 1.0f / top : 0.0f;
    for (size_t i = 0; i < 4 * n; i++)
        buf[i] = irr[i] * inv;
    glBindTexture(GL_TEXTURE_2D, s->irr_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, a->width, a->height, GL_RGBA, GL_FLOAT, buf);
    free(buf);
    s->irr_scale = top;
    s->st.uploads++;
}

static int ensure_uv_target(lm_state *s, int w, int h, gk_err *e)
{
    if (s->uv_fbo && s->uv_w == w && s->uv_h == h)
        return 0;
    if (s->uv_fbo) {
        glDeleteFramebuffers(1, &s->uv_fbo);
        glDeleteTextures(1, &s->uv_tex);
        glDeleteRenderbuffers(1, &s->uv_depth);
    }
    s->uv_w = w, s->uv_h = h;
    glGenTextures(1, &s->uv_tex);
    glBindTexture(GL_TEXTURE_2D, s->uv_tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RG32UI, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenRenderbuffers(1, &s->uv_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, s->uv_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
    glGenFramebuffers(1, &s->uv_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->uv_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s->uv_tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s->uv_depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "lightmap: light-map UV framebuffer incomplete (%dx%d)", w, h);
    return 0;
}

/* lightmap/uv.vert + uv.frag */
typedef struct uv_uniforms { GLint u_model, u_viewproj; } uv_uniforms;
static const gk_uniform_field uv_fields[] = {GK_UNIFORM(uv_uniforms, u_model), GK_UNIFORM(uv_uniforms, u_viewproj)};
/* lightmap/compose.frag */
typedef struct compose_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_lightmap_uv, u_irradiance, u_scale;
} compose_uniforms;
static const gk_uniform_field compose_fields[] = {
    GK_GBUFFER_FIELDS(compose_uniforms, gb), GK_UNIFORM(compose_uniforms, u_lightmap_uv),
    GK_UNIFORM(compose_uniforms, u_irradiance), GK_UNIFORM(compose_uniforms, u_scale)};

int lm_display_draw(lm_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint up = gk_program_get(s->ctx.programs, "lightmap/uv.vert", "lightmap/uv.frag", NULL, e);
    const uv_uniforms *uu = up ? gk_program_uniforms(s->ctx.programs, up, GK_FIELDS(uv_fields), sizeof *uu, e) : NULL;
    GLuint cp = uu ? gk_program_get(s->ctx.programs, "common/fullscreen.vert", "lightmap/compose.frag", NULL, e) : 0;
    const compose_uniforms *uc =
        cp ? gk_program_uniforms(s->ctx.programs, cp, GK_FIELDS(compose_fields), sizeof *uc, e) : NULL;
    if (!uc || ensure_uv_target(s, f->width, f->height, e))
        return -1;

    gk_pass_begin(f->pass, "lightmap_uv");
    glBindFramebuffer(GL_FRAMEBUFFER, s->uv_fbo);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, b1);
    glViewport(0, 0, f->width, f->height);
    /* clears obey the masks: the frame's earlier passes may have left them off */
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    const GLuint none[4] = {0xFFFFFFFFu, 0xFFFFFFFFu, 0, 0};
    glClearBufferuiv(GL_COLOR, 0, none);
    const GLfloat far = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &far);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glUseProgram(up);
    glUniformMatrix4fv(uu->u_viewproj, 1, GL_FALSE, f->view_proj.m);
    glBindVertexArray(s->vao);
    const lm_atlas *a = &s->atlas;
    for (int i = 0; i < a->n_draws; i++) {
        const lm_draw *d = &a->draws[i];
        if (d->node >= f->scene->n_nodes)
            continue;
        glUniformMatrix4fv(uu->u_model, 1, GL_FALSE, f->scene->nodes[d->node].world.m);
        glDrawArrays(GL_TRIANGLES, d->first_vert, d->n_verts);
    }
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    gk_pass_end(f->pass);

    gk_pass_begin(f->pass, "lightmap_compose");
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr_fbo);
    glDrawBuffers(1, b1);
    glViewport(0, 0, f->width, f->height);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(cp);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, s->uv_tex);
    glUniform1i(uc->u_lightmap_uv, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, s->irr_tex);
    glUniform1i(uc->u_irradiance, 1);
    glUniform1f(uc->u_scale, s->irr_scale);
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gb, &uc->gb, 2, 0);
    glBindVertexArray(s->empty_vao); /* the full-screen triangle reads no attribute */
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
    gk_pass_end(f->pass);
    return 0;
}

void lm_display_free(lm_state *s)
{
    if (s->vao)
        glDeleteVertexArrays(1, &s->vao);
    if (s->vbo)
        glDeleteBuffers(1, &s->vbo);
    if (s->empty_vao)
        glDeleteVertexArrays(1, &s->empty_vao);
    if (s->irr_tex)
        glDeleteTextures(1, &s->irr_tex);
    if (s->uv_fbo) {
        glDeleteFramebuffers(1, &s->uv_fbo);
        glDeleteTextures(1, &s->uv_tex);
        glDeleteRenderbuffers(1, &s->uv_depth);
    }
    s->vao = s->vbo = s->empty_vao = s->irr_tex = s->uv_fbo = s->uv_tex = s->uv_depth = 0;
    s->uv_w = s->uv_h = 0;
}
