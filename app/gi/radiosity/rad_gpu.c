/* The radiosity method's GPU side (radiosity.h): buffers, bounces, display. */
#include <stdlib.h>
#include <string.h>

#include "rad_internal.h"

static float *staging(rad_gpu *g, size_t floats)
{
    if (g->scratch_cap < floats) {
        float *p = realloc(g->scratch, sizeof *p * floats);
        if (!p)
            return NULL;
        g->scratch = p, g->scratch_cap = floats;
    }
    return g->scratch;
}

static GLuint ssbo(GLuint old, const void *data, size_t bytes)
{
    GLuint b = old;
    if (!b)
        glGenBuffers(1, &b);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(bytes ? bytes : 16), data, GL_DYNAMIC_DRAW);
    return b;
}

static void upload_geometry(rad_gpu *gpu, const rad_geometry *g)
{
    const rad_tree *t = &g->tree;
    const rad_links *L = &g->links;
    int nl = t->n_leaves, nn = t->n_nodes;
    size_t nlinks = L->offset[nl];
    /* links: (node, weight bits) */
    uint32_t *lk = malloc(sizeof *lk * 2 * (nlinks + 1));
    /* leaves: first, end, -, -, albedo (vec4), irradiance (vec4): 12 words */
    uint32_t *lv = calloc((size_t)nl * 12 + 1, sizeof *lv);
    uint32_t *nd = calloc((size_t)nn * 4 + 1, sizeof *nd);
    uint32_t *idx = malloc(sizeof *idx * 3 * (size_t)(g->mesh.n_tris + 1));
    float *pos = malloc(sizeof *pos * 3 * (size_t)(g->mesh.n_verts + 1));
    if (!lk || !lv || !nd || !idx || !pos) {
        free(lk), free(lv), free(nd), free(idx), free(pos);
        gpu->out_of_memory = true;
        return;
    }
    for (size_t k = 0; k < nlinks; k++) {
        lk[2 * k] = L->target[k];
        memcpy(&lk[2 * k + 1], &L->weight[k], 4);
    }
    for (int i = 0; i < nl; i++) {
        lv[12 * i] = L->offset[i], lv[12 * i + 1] = L->offset[i + 1];
        memcpy(&lv[12 * i + 4], &g->albedo[3 * i], 12);
    }
    for (int i = 0; i < nn; i++) {
        int first, k = rad_tree_children(t, i, &first);
        nd[4 * i] = (uint32_t)(k ? first : 0), nd[4 * i + 1] = (uint32_t)k;
        memcpy(&nd[4 * i + 2], &t->area[i], 4);
    }
    gpu->links = ssbo(gpu->links, lk, sizeof *lk * 2 * nlinks);
    gpu->leaves = ssbo(gpu->leaves, lv, sizeof *lv * 12 * (size_t)nl);
    gpu->nodes = ssbo(gpu->nodes, nd, sizeof *nd * 4 * (size_t)nn);
    size_t vec4s = sizeof(float) * 4 * (size_t)nn;
    gpu->b0 = ssbo(gpu->b0, NULL, vec4s);
    gpu->unshot[0] = ssbo(gpu->unshot[0], NULL, vec4s);
    gpu->unshot[1] = ssbo(gpu->unshot[1], NULL, vec4s);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    /* the display mesh: vertex i is leaf i */
    for (int i = 0; i < g->mesh.n_verts; i++)
        pos[3 * i] = g->mesh.pos[i].x, pos[3 * i + 1] = g->mesh.pos[i].y, pos[3 * i + 2] = g->mesh.pos[i].z;
    memcpy(idx, g->mesh.tris, sizeof *idx * 3 * (size_t)g->mesh.n_tris);
    if (!gpu->vao) {
        glGenVertexArrays(1, &gpu->vao);
        glGenBuffers(1, &gpu->vbo);
        glGenBuffers(1, &gpu->ibo);
    }
    glBindVertexArray(gpu->vao);
    glBindBuffer(GL_ARRAY_BUFFER, gpu->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof *pos * 3 * (size_t)g->mesh.n_verts), pos, GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), (void *)0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu->ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof *idx * 3 * (size_t)g->mesh.n_tris), idx, GL_STATIC_DRAW);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    /* the irradiance texture the vertex shader reads */
    int h = (nl + RAD_TEX_WIDTH - 1) / RAD_TEX_WIDTH;
    if (gpu->irr_tex)
        glDeleteTextures(1, &gpu->irr_tex);
    glGenTextures(1, &gpu->irr_tex);
    glBindTexture(GL_TEXTURE_2D, gpu->irr_tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, RAD_TEX_WIDTH, h > 0 ? h : 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    gpu->tex_h = h > 0 ? h : 1;
    gpu->n_leaves = nl, gpu->n_nodes = nn, gpu->n_levels = t->n_levels;
    memcpy(gpu->level_first, t->level_first, sizeof gpu->level_first);
    gpu->n_indices = 3 * g->mesh.n_tris;
    gpu->link_count = (long)nlinks;
    free(lk), free(lv), free(nd), free(idx), free(pos);
}

static void upload_positions(rad_gpu *gpu, const rad_geometry *g)
{
    float *pos = staging(gpu, 3 * (size_t)g->mesh.n_verts);
    if (!pos) {
        gpu->out_of_memory = true;
        return;
    }
    for (int i = 0; i < g->mesh.n_verts; i++)
        pos[3 * i] = g->mesh.pos[i].x, pos[3 * i + 1] = g->mesh.pos[i].y, pos[3 * i + 2] = g->mesh.pos[i].z;
    glBindBuffer(GL_ARRAY_BUFFER, gpu->vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof *pos * 3 * (size_t)g->mesh.n_verts), pos);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

/* rad_take_fn: called under the worker's lock with its newest publication. */
void rad_gpu_take(void *state, const rad_geometry *g, uint64_t geometry_id, const float *b0)
{
    rad_state *s = state;
    rad_gpu *gpu = &s->gpu;
    if (geometry_id != gpu->geometry_id) {
        if (gpu->geometry_id && g->links_id == gpu->links_id && g->tree.n_nodes == gpu->n_nodes)
            upload_positions(gpu, g); /* a refit between link rebuilds: the vertices moved */
        else
            upload_geometry(gpu, g);
        if (gpu->out_of_memory)
            return; /* the frame keeps what it had */
        gpu->geometry_id = geometry_id;
        gpu->links_id = g->links_id;
    }
    float *v = staging(gpu, 4 * (size_t)gpu->n_nodes);
    if (!v)
        return;
    for (int i = 0; i < gpu->n_nodes; i++)
        v[4 * i] = b0[3 * i], v[4 * i + 1] = b0[3 * i + 1], v[4 * i + 2] = b0[3 * i + 2], v[4 * i + 3] = 0.0f;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, gpu->b0);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(sizeof *v * 4 * (size_t)gpu->n_nodes), v);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    gpu->have_b0 = true;
    s->st.uploads++;
}

typedef struct gather_uniforms { GLint u_leaves, u_first_bounce; } gather_uniforms;
static const gk_uniform_field gather_fields[] = {GK_UNIFORM(gather_uniforms, u_leaves),
                                                 GK_UNIFORM(gather_uniforms, u_first_bounce)};
typedef struct pullup_uniforms { GLint u_first, u_count; } pullup_uniforms;
static const gk_uniform_field pullup_fields[] = {GK_UNIFORM(pullup_uniforms, u_first), GK_UNIFORM(pullup_uniforms, u_count)};
typedef struct publish_uniforms { GLint u_leaves, u_width; } publish_uniforms;
static const gk_uniform_field publish_fields[] = {GK_UNIFORM(publish_uniforms, u_leaves), GK_UNIFORM(publish_uniforms, u_width)};
typedef struct display_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_viewproj, u_irradiance, u_width, u_tolerance;
} display_uniforms;
static const gk_uniform_field display_fields[] = {
    GK_GBUFFER_FIELDS(display_uniforms, gb), GK_UNIFORM(display_uniforms, u_viewproj),
    GK_UNIFORM(display_uniforms, u_irradiance), GK_UNIFORM(display_uniforms, u_width),
    GK_UNIFORM(display_uniforms, u_tolerance)};

static GLuint groups(int n) { return (GLuint)((n + 63) / 64); }

int rad_gpu_bounce(rad_state *s, const gk_gi_frame *f, int bounces, gk_err *e)
{
    rad_gpu *g = &s->gpu;
    gk_program_cache *pc = s->ctx.programs;
    GLuint gp = gk_program_get_compute(pc, "radiosity/gather.comp", NULL, e);
    const gather_uniforms *gu = gp ? gk_program_uniforms(pc, gp, GK_FIELDS(gather_fields), sizeof *gu, e) : NULL;
    GLuint pp = gu ? gk_program_get_compute(pc, "radiosity/pullup.comp", NULL, e) : 0;
    const pullup_uniforms *pu = pp ? gk_program_uniforms(pc, pp, GK_FIELDS(pullup_fields), sizeof *pu, e) : NULL;
    GLuint sp = pu ? gk_program_get_compute(pc, "radiosity/publish.comp", NULL, e) : 0;
    const publish_uniforms *su = sp ? gk_program_uniforms(pc, sp, GK_FIELDS(publish_fields), sizeof *su, e) : NULL;
    if (!su)
        return -1;
    gk_pass_begin(f->pass, "radiosity_bounce");
    GLuint in = g->b0;
    for (int b = 0; b < bounces; b++) {
        GLuint out = g->unshot[b & 1];
        glUseProgram(gp);
        glUniform1ui(gu->u_leaves, (GLuint)g->n_leaves);
        glUniform1i(gu->u_first_bounce, b == 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, g->links);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, g->leaves);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, in);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, out);
        glDispatchCompute(groups(g->n_leaves), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUseProgram(pp);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, g->nodes);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out);
        for (int l = 1; l < g->n_levels; l++) {
            int count = g->level_first[l + 1] - g->level_first[l];
            glUniform1ui(pu->u_first, (GLuint)g->level_first[l]);
            glUniform1ui(pu->u_count, (GLuint)count);
            glDispatchCompute(groups(count), 1, 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        in = out;
    }
    glUseProgram(sp);
    glUniform1ui(su->u_leaves, (GLuint)g->n_leaves);
    glUniform1i(su->u_width, RAD_TEX_WIDTH);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, g->leaves);
    glBindImageTexture(0, g->irr_tex, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groups(g->n_leaves), 1, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    for (int i = 0; i < 4; i++)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)i, 0);
    gk_pass_end(f->pass);
    s->st.bounces = bounces;
    return 0;
}

int rad_gpu_display(rad_state *s, const gk_gi_frame *f, gk_err *e)
{
    rad_gpu *g = &s->gpu;
    gk_program_cache *pc = s->ctx.programs;
    GLuint dp = gk_program_get(pc, "radiosity/display.vert", "radiosity/display.frag", rad_work_display_begin(s, f), e);
    const display_uniforms *du = dp ? gk_program_uniforms(pc, dp, GK_FIELDS(display_fields), sizeof *du, e) : NULL;
    if (!du) {
        rad_work_display_end(s);
        return -1;
    }
    gk_pass_begin(f->pass, "radiosity_display");
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr_fbo);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, b1);
    glViewport(0, 0, f->width, f->height);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(dp);
    glUniformMatrix4fv(du->u_viewproj, 1, GL_FALSE, f->view_proj.m);
    glUniform1i(du->u_width, RAD_TEX_WIDTH);
    /* 2 mm a metre: far above the 32-bit depth's error, far below any surface's separation */
    glUniform1f(du->u_tolerance, 2e-3f);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, g->irr_tex);
    glUniform1i(du->u_irradiance, 0);
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gb, &du->gb, 1, 0);
    glBindVertexArray(g->vao);
    glDrawElements(GL_TRIANGLES, g->n_indices, GL_UNSIGNED_INT, (void *)0);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
    rad_work_display_end(s);
    gk_pass_end(f->pass);
    return 0;
}

long rad_gpu_memory(const rad_gpu *g)
{
    long b = g->link_count * 8 + (long)g->n_leaves * 48 + (long)g->n_nodes * (16 + 3 * 16);
    b += (long)RAD_TEX_WIDTH * g->tex_h * 16;
    b += (long)g->n_leaves * 12 + (long)g->n_indices * 4;
    return g->geometry_id ? b : 0;
}

void rad_gpu_free(rad_gpu *g)
{
    GLuint bufs[8] = {g->links, g->leaves, g->nodes, g->b0, g->unshot[0], g->unshot[1], g->vbo, g->ibo};
    for (int i = 0; i < 8; i++)
        if (bufs[i])
            glDeleteBuffers(1, &bufs[i]);
    if (g->vao)
        glDeleteVertexArrays(1, &g->vao);
    if (g->irr_tex)
        glDeleteTextures(1, &g->irr_tex);
    free(g->scratch);
    memset(g, 0, sizeof *g);
}
