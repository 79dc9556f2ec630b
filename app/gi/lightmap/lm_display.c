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
    /* RGBA16F: filterable on the GLES 3.1 floor (32F needs OES_texture_float_linear) and a 3.1
       image format (the final gather's imageStore); the AIMs are stored divided by their largest
       value, so any scene's units fit; the IIMs hold E itself */
    GLuint *tex[5] = {&s->irr_tex, &s->full_tex, &s->iim_gathered, &s->iim_shown[0], &s->iim_shown[1]};
    float *zero = calloc((size_t)a->width * (size_t)a->height * 4, sizeof(float));
    for (int i = 0; i < 5; i++) {
        glGenTextures(1, tex[i]);
        glBindTexture(GL_TEXTURE_2D, *tex[i]);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA16F, a->width, a->height);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        if (zero)
            glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, a->width, a->height, GL_RGBA, GL_FLOAT, zero);
    }
    free(zero);
    s->irr_scale = s->full_scale = 0.0f;
    s->iim_cur = 0;
    s->iim_blend_started = false;
    int nc = a->n_charts > 0 ? a->n_charts : 1;
    s->queue_prio = calloc((size_t)nc, sizeof *s->queue_prio);
    s->queue_left = calloc((size_t)nc, sizeof *s->queue_left);
    s->queue_cursor = calloc((size_t)nc, sizeof *s->queue_cursor);
    s->order = calloc((size_t)nc, sizeof *s->order);
    if (!s->queue_prio || !s->queue_left || !s->queue_cursor || !s->order)
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory for the gather queue");
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "lightmap: GL error 0x%04x creating the %dx%d atlas", err, a->width, a->height);
    return 0;
}

static float upload_scaled(const lm_atlas *a, GLuint tex, const float *irr);

/* Called by lm_worker_take under the pool's lock with the newest atlases and gather queue. */
void lm_display_upload(void *state, const float *indirect, const float *full, const float *queue)
{
    lm_state *s = state;
    const lm_atlas *a = &s->atlas;
    float si = upload_scaled(a, s->irr_tex, indirect), sf = upload_scaled(a, s->full_tex, full);
    if (si >= 0.0f)
        s->irr_scale = si;
    if (sf >= 0.0f)
        s->full_scale = sf;
    for (int i = 0; i < a->n_charts; i++)
        if (queue[i] > 0.0f) {
            s->queue_prio[i] = s->queue_prio[i] > queue[i] ? s->queue_prio[i] : queue[i];
            s->queue_left[i] = a->charts[i].w * a->charts[i].h; /* all of it again, round robin on */
        }
    s->st.uploads++;
}

static float upload_scaled(const lm_atlas *a, GLuint tex, const float *irr)
{
    size_t n = (size_t)a->width * (size_t)a->height;
    float top = 0.0f;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            top = fmaxf(top, irr[4 * i + (size_t)c]);
    float *buf = malloc(sizeof(float) * 4 * n);
    if (!buf)
        return -1.0f; /* out of memory: the frame keeps the previous atlas */
    float inv = top > 0.0f ? 1.0f / top : 0.0f;
    for (size_t i = 0; i < 4 * n; i++)
        buf[i] = irr[i] * inv;
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, a->width, a->height, GL_RGBA, GL_FLOAT, buf);
    free(buf);
    return top;
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

/* lightmap/uv.vert + gather.frag */
typedef struct gather_uniforms { GLint u_model, u_viewproj, u_aim_full, u_scale, u_albedo, u_emission; } gather_uniforms;
static const gk_uniform_field gather_fields[] = {
    GK_UNIFORM(gather_uniforms, u_model),  GK_UNIFORM(gather_uniforms, u_viewproj), GK_UNIFORM(gather_uniforms, u_aim_full),
    GK_UNIFORM(gather_uniforms, u_scale),  GK_UNIFORM(gather_uniforms, u_albedo),   GK_UNIFORM(gather_uniforms, u_emission)};
/* lightmap/iim_blend.comp */
typedef struct blend_uniforms { GLint u_gathered, u_shown, u_alpha; } blend_uniforms;
static const gk_uniform_field blend_fields[] = {GK_UNIFORM(blend_uniforms, u_gathered), GK_UNIFORM(blend_uniforms, u_shown),
                                                GK_UNIFORM(blend_uniforms, u_alpha)};

typedef struct gather_draw_ctx {
    lm_state *s;
    const gk_gi_frame *f;
    GLuint prog;
    const gather_uniforms *u;
} gather_draw_ctx;

/* The scene as the gathering texel sees it: the AIMs' full illumination on every charted surface. */
static int gather_draw(void *ctx, const mat4 *vp, gk_err *e)
{
    (void)e;
    gather_draw_ctx *c = ctx;
    const lm_atlas *a = &c->s->atlas;
    const gk_scene *sc = c->s->scene;
    glUseProgram(c->prog);
    glUniformMatrix4fv(c->u->u_viewproj, 1, GL_FALSE, vp->m);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, c->s->full_tex);
    glUniform1i(c->u->u_aim_full, 0);
    glUniform1f(c->u->u_scale, c->s->full_scale);
    glBindVertexArray(c->s->vao);
    for (int i = 0; i < a->n_draws; i++) {
        const lm_draw *d = &a->draws[i];
        if (d->node >= c->f->scene->n_nodes)
            continue;
        const gk_mesh *m = &sc->meshes[d->mesh];
        const gk_material *mt = &sc->materials[m->material >= 0 && m->material < sc->n_materials ? m->material : 0];
        float k = 1.0f - mt->metallic;
        glUniform3f(c->u->u_albedo, mt->base_color[0] * k, mt->base_color[1] * k, mt->base_color[2] * k);
        if (mt->light_proxy)
            glUniform3f(c->u->u_emission, 0.0f, 0.0f, 0.0f);
        else
            glUniform3f(c->u->u_emission, mt->emissive[0], mt->emissive[1], mt->emissive[2]);
        glUniformMatrix4fv(c->u->u_model, 1, GL_FALSE, c->f->scene->nodes[d->node].world.m);
        glDrawArrays(GL_TRIANGLES, d->first_vert, d->n_verts);
    }
    glBindVertexArray(0);
    return 0;
}

static int cmp_prio_desc(const void *pa, const void *pb, void *ctx)
{
    const float *p = ctx;
    int a = *(const int *)pa, b = *(const int *)pb;
    if (p[a] != p[b])
        return p[a] > p[b] ? -1 : 1;
    return a - b;
}

/* One gather job for interior texel (i, j) of chart ci: its centre lifted off the surface, the
   normal and a tangent at the frame's node matrix, and the texel with its gutter copies. */
static void make_job(const lm_state *s, const gk_gi_frame *f, int ci, int i, int j, lm_gather_job *out)
{
    const lm_chart *c = &s->atlas.charts[ci];
    mat4 w = f->scene->nodes[c->node].world;
    vec3 n = v3_norm(m4_dir(m4_transpose(m4_inverse(w)), c->n));
    vec3 p = m4_point(w, lm_chart_point(c, i, j));
    /* M10: off the surface by a hundredth of a texel, so the near plane does not cut into it */
    out->eye = v3_add(p, v3_scale(n, 0.01f * s->atlas.texel_size));
    out->dir = n;
    out->up = v3_norm(m4_dir(w, c->tu));
    int x = c->x + i, y = c->y + j, k = 0;
    out->target[k][0] = x, out->target[k][1] = y, k++;
    bool l = i == 0, r = i == c->w - 1, b = j == 0, t = j == c->h - 1;
    if (l) out->target[k][0] = x - 1, out->target[k][1] = y, k++;
    if (r) out->target[k][0] = x + 1, out->target[k][1] = y, k++;
    if (b) out->target[k][0] = x, out->target[k][1] = y - 1, k++;
    if (t) out->target[k][0] = x, out->target[k][1] = y + 1, k++;
    if (l && b) out->target[k][0] = x - 1, out->target[k][1] = y - 1, k++;
    if (l && t) out->target[k][0] = x - 1, out->target[k][1] = y + 1, k++;
    if (r && b) out->target[k][0] = x + 1, out->target[k][1] = y - 1, k++;
    if (r && t) out->target[k][0] = x + 1, out->target[k][1] = y + 1, k++;
    out->n_targets = k;
}

int lm_display_gather(lm_state *s, const gk_gi_frame *f, int texels, int res, gk_err *e)
{
    const lm_atlas *a = &s->atlas;
    if (!s->gather.fbo || s->gather.res != res || s->gather.max_tiles < texels) {
        lm_gather_free(&s->gather);
        free(s->jobs);
        s->jobs = malloc(sizeof *s->jobs * (size_t)texels);
        if (!s->jobs)
            return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory for %d gather jobs", texels);
        if (lm_gather_setup(&s->gather, res, texels, e))
            return -1;
    }
    /* the texels to gather: surfaces in the order of their Δ_i, each round robin over its texels */
    int nq = 0;
    long queued = 0;
    for (int i = 0; i < a->n_charts; i++)
        if (s->queue_left[i] > 0)
            s->order[nq++] = i, queued += s->queue_left[i];
    qsort_r(s->order, (size_t)nq, sizeof *s->order, cmp_prio_desc, s->queue_prio);
    int n = 0;
    for (int q = 0; q < nq && n < texels; q++) {
        int ci = s->order[q];
        const lm_chart *c = &a->charts[ci];
        while (s->queue_left[ci] > 0 && n < texels) {
            int t = s->queue_cursor[ci];
            make_job(s, f, ci, t % c->w, t / c->w, &s->jobs[n++]);
            s->queue_cursor[ci] = (t + 1) % (c->w * c->h);
            if (--s->queue_left[ci] == 0)
                s->queue_prio[ci] = 0.0f;
        }
    }
    s->st.gathered = n;
    s->st.gathered_total += (uint64_t)n;
    s->st.queued = queued - n;
    if (n > 0) {
        GLuint gp = gk_program_get(s->ctx.programs, "lightmap/uv.vert", "lightmap/gather.frag", lm_work_gather_begin(s), e);
        const gather_uniforms *gu =
            gp ? gk_program_uniforms(s->ctx.programs, gp, GK_FIELDS(gather_fields), sizeof *gu, e) : NULL;
        if (!gu) {
            lm_work_gather_end(s);
            return -1;
        }
        gather_draw_ctx dc = {s, f, gp, gu};
        vec3 ext = v3_sub(f->scene->bmax, f->scene->bmin);
        float diam = v3_len(ext) > 0.0f ? v3_len(ext) : 1.0f;
        s->gather.count_work = s->counting;
        gk_pass_begin(f->pass, "lightmap_gather");
        int rc = lm_gather_run(&s->gather, s->ctx.programs, s->jobs, n, 0.005f * a->texel_size, 4.0f * diam,
                               gather_draw, &dc, s->iim_gathered, e);
        gk_pass_end(f->pass);
        lm_work_gather_end(s);
        if (rc)
            return -1;
    }
    /* the shown IIM follows the gathered one: 1 - exp(-dt / τ) a frame, at once on a scene's first */
    GLuint bp = gk_program_get_compute(s->ctx.programs, "lightmap/iim_blend.comp", lm_work_blend_begin(s), e);
    const blend_uniforms *bu = bp ? gk_program_uniforms(s->ctx.programs, bp, GK_FIELDS(blend_fields), sizeof *bu, e) : NULL;
    if (!bu) {
        lm_work_blend_end(s);
        return -1;
    }
    double dt = f->time_s - s->last_time;
    float alpha = !s->iim_blend_started || dt <= 0.0 ? 1.0f : (float)(1.0 - exp(-dt / LM_IIM_TAU_S));
    s->iim_blend_started = true;
    s->last_time = f->time_s;
    gk_pass_begin(f->pass, "lightmap_blend");
    glUseProgram(bp);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, s->iim_gathered);
    glUniform1i(bu->u_gathered, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, s->iim_shown[s->iim_cur]);
    glUniform1i(bu->u_shown, 1);
    glUniform1f(bu->u_alpha, alpha);
    glBindImageTexture(0, s->iim_shown[1 - s->iim_cur], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute((GLuint)(a->width + 7) / 8, (GLuint)(a->height + 7) / 8, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glActiveTexture(GL_TEXTURE0);
    s->iim_cur = 1 - s->iim_cur;
    lm_work_blend_end(s);
    gk_pass_end(f->pass);
    return 0;
}

int lm_display_draw(lm_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint up = gk_program_get(s->ctx.programs, "lightmap/uv.vert", "lightmap/uv.frag", lm_work_uv_begin(s), e);
    const uv_uniforms *uu = up ? gk_program_uniforms(s->ctx.programs, up, GK_FIELDS(uv_fields), sizeof *uu, e) : NULL;
    GLuint cp = uu ? gk_program_get(s->ctx.programs, "common/fullscreen.vert", "lightmap/compose.frag",
                                    lm_work_compose_begin(s), e) : 0;
    const compose_uniforms *uc =
        cp ? gk_program_uniforms(s->ctx.programs, cp, GK_FIELDS(compose_fields), sizeof *uc, e) : NULL;
    if (!uc || ensure_uv_target(s, f->width, f->height, e)) {
        lm_work_uv_end(s);
        return -1;
    }

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
    lm_work_uv_end(s);
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
    /* the final gather's IIM (E itself), or without it the AIM's indirect part (scaled) */
    glBindTexture(GL_TEXTURE_2D, s->iim_on ? s->iim_shown[s->iim_cur] : s->irr_tex);
    glUniform1i(uc->u_irradiance, 1);
    glUniform1f(uc->u_scale, s->iim_on ? 1.0f : s->irr_scale);
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gb, &uc->gb, 2, 0);
    glBindVertexArray(s->empty_vao); /* the full-screen triangle reads no attribute */
    glDrawArrays(GL_TRIANGLES, 0, 3);
    lm_work_compose_end(s);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
    gk_pass_end(f->pass);
    return 0;
}

/* Called by lm_worker_take_caustics under the pool's lock. */
static void take_caustics(void *ctx, const float *points, int n)
{
    lm_state *s = ctx;
    gk_err e = {0};
    if (lm_caustic_gpu_upload(&s->caustic, points, n, 6, &e)) {
        s->caustic.n_points = 0; /* out of memory: no caustics this time (the frame goes on) */
        return;
    }
    /* the seed counts photons of one colour: their mean flux */
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            sum[c] += points[6 * i + 3 + c];
    s->caustic_flux = n > 0 ? v3((float)(sum[0] / n), (float)(sum[1] / n), (float)(sum[2] / n)) : v3(0, 0, 0);
}

int lm_display_caustics(lm_state *s, const gk_gi_frame *f, gk_err *e)
{
    lm_worker_take_caustics(s->worker, &s->caustic_seen, take_caustics, s);
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    if (lm_caustic_gpu_draw(&s->caustic, s->ctx.programs, &gb, s->caustic_flux, s->caustic_cull, f->hdr_fbo, f->pass, e))
        return -1;
    s->st.caustic_points = s->caustic.n_points;
    s->st.caustic_tiles = s->caustic.tiles_filtered;
    s->st.caustic_tiles_total = s->caustic.tiles_x * s->caustic.tiles_y;
    s->st.caustic_pixels = s->caustic.pixels_filtered;
    lm_work_caustics(s);
    return 0;
}

void lm_display_free(lm_state *s)
{
    lm_caustic_gpu_free(&s->caustic);
    if (s->vao)
        glDeleteVertexArrays(1, &s->vao);
    if (s->vbo)
        glDeleteBuffers(1, &s->vbo);
    if (s->empty_vao)
        glDeleteVertexArrays(1, &s->empty_vao);
    GLuint tex[5] = {s->irr_tex, s->full_tex, s->iim_gathered, s->iim_shown[0], s->iim_shown[1]};
    for (int i = 0; i < 5; i++)
        if (tex[i])
            glDeleteTextures(1, &tex[i]);
    s->full_tex = s->iim_gathered = s->iim_shown[0] = s->iim_shown[1] = 0;
    lm_gather_free(&s->gather);
    free(s->queue_prio), free(s->queue_left), free(s->queue_cursor), free(s->order), free(s->jobs);
    s->queue_prio = NULL, s->queue_left = NULL, s->queue_cursor = NULL, s->order = NULL, s->jobs = NULL;
    if (s->uv_fbo) {
        glDeleteFramebuffers(1, &s->uv_fbo);
        glDeleteTextures(1, &s->uv_tex);
        glDeleteRenderbuffers(1, &s->uv_depth);
    }
    s->vao = s->vbo = s->empty_vao = s->irr_tex = s->uv_fbo = s->uv_tex = s->uv_depth = 0;
    s->uv_w = s->uv_h = 0;
}
