#include "scene_gpu.h"

#include <stdlib.h>
#include <string.h>

#include "gl/gl_program.h"
#include "gl/gl_target.h"

int gk_scene_gpu_upload(gk_scene_gpu *g, const gk_scene *s, gk_err *e)
{
    memset(g, 0, sizeof *g);
    while (glGetError() != GL_NO_ERROR) {
    }
    g->n_meshes = s->n_meshes;
    g->vao = calloc((size_t)s->n_meshes + 1, sizeof *g->vao);
    g->vbo = calloc((size_t)s->n_meshes * GK_MESH_ATTRIBS + 1, sizeof *g->vbo);
    g->ibo = calloc((size_t)s->n_meshes + 1, sizeof *g->ibo);
    g->index_count = calloc((size_t)s->n_meshes + 1, sizeof *g->index_count);
    g->tex = calloc((size_t)s->n_textures + 1, sizeof *g->tex);
    if (!g->vao || !g->vbo || !g->ibo || !g->index_count || !g->tex) {
        gk_scene_gpu_free(g);
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory uploading the scene", s->path);
    }
    if (s->n_meshes) {
        glGenVertexArrays(s->n_meshes, g->vao);
        glGenBuffers(s->n_meshes * GK_MESH_ATTRIBS, g->vbo);
        glGenBuffers(s->n_meshes, g->ibo);
    }
    for (int i = 0; i < s->n_meshes; i++) {
        const gk_mesh *m = &s->meshes[i];
        glBindVertexArray(g->vao[i]);
        const float *data[GK_MESH_ATTRIBS] = {m->positions, m->normals, m->uvs, m->colors, m->tangents,
                                              m->uvs1 ? m->uvs1 : m->uvs};
        const int comps[GK_MESH_ATTRIBS] = {3, 3, 2, 4, 4, 2};
        for (int a = 0; a < GK_MESH_ATTRIBS; a++) {
            if (!data[a]) { /* a constant attribute: no colour is white */
                glDisableVertexAttribArray((GLuint)a);
                if (a == 3)
                    glVertexAttrib4f((GLuint)a, 1, 1, 1, 1);
                else if (a == 4)
                    glVertexAttrib4f((GLuint)a, 1, 0, 0, 1);
                else
                    glVertexAttrib4f((GLuint)a, 0, 0, 1, 0);
                continue;
            }
            glBindBuffer(GL_ARRAY_BUFFER, g->vbo[i * GK_MESH_ATTRIBS + a]);
            glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * comps[a] * m->n_vertices), data[a], GL_STATIC_DRAW);
            glEnableVertexAttribArray((GLuint)a);
            glVertexAttribPointer((GLuint)a, comps[a], GL_FLOAT, GL_FALSE, 0, NULL);
        }
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->ibo[i]);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof(uint32_t) * 3 * m->n_triangles), m->indices,
                     GL_STATIC_DRAW);
        g->index_count[i] = (GLsizei)(3 * m->n_triangles);
        glBindVertexArray(0);
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    /* Textures: linear float RGBA from the loader, kept as RGBA16F (filterable in GLES 3.0 core).
       No mipmaps: generating them needs a renderable RGBA16F, and the path tracer samples
       without them (materials.c), so the two renderers see the same texels. */
    g->n_textures = s->n_textures;
    for (int i = 0; i < s->n_textures; i++) {
        const gk_texture *t = &s->textures[i];
        glGenTextures(1, &g->tex[i]);
        glBindTexture(GL_TEXTURE_2D, g->tex[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, t->width, t->height, 0, GL_RGBA, GL_FLOAT, t->rgba);
        /* the glTF sampler (gk_texture): one filter for both directions, as the tracer samples */
        static const GLint wrap[] = {[GK_WRAP_REPEAT] = GL_REPEAT, [GK_WRAP_CLAMP] = GL_CLAMP_TO_EDGE,
                                     [GK_WRAP_MIRROR] = GL_MIRRORED_REPEAT};
        GLint filter = t->nearest ? GL_NEAREST : GL_LINEAR;
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap[t->wrap_s]);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap[t->wrap_t]);
    }
    const float white[4] = {1, 1, 1, 1};
    glGenTextures(1, &g->white_tex);
    glBindTexture(GL_TEXTURE_2D, g->white_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, 1, 1, 0, GL_RGBA, GL_FLOAT, white);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        gk_scene_gpu_free(g);
        return gk_fail(e, GK_ERUNTIME, "%s: uploading the scene to the GPU failed: %s", s->path, gk_gl_error_name(err));
    }
    return 0;
}

void gk_scene_gpu_free(gk_scene_gpu *g)
{
    if (g->n_meshes && g->vao) {
        glDeleteVertexArrays(g->n_meshes, g->vao);
        glDeleteBuffers(g->n_meshes * GK_MESH_ATTRIBS, g->vbo);
        glDeleteBuffers(g->n_meshes, g->ibo);
    }
    if (g->n_textures && g->tex)
        glDeleteTextures(g->n_textures, g->tex);
    if (g->white_tex)
        glDeleteTextures(1, &g->white_tex);
    free(g->vao);
    free(g->vbo);
    free(g->ibo);
    free(g->index_count);
    free(g->tex);
    memset(g, 0, sizeof *g);
}

static void set_material(const gk_scene_gpu *g, const gk_scene *s, const gk_draw_uniforms *u, const gk_material *m)
{
    /* the texture slots by unit (gk_scene_gpu_draw's sampler units), white where a slot is empty */
    const struct { int tex, flag; } slots[] = {
        {m->base_color_tex, GK_MAT_BASE_TEX},      {m->metallic_roughness_tex, GK_MAT_MR_TEX},
        {m->specular_tex, GK_MAT_SPEC_TEX},        {m->specular_color_tex, GK_MAT_SPEC_COLOR_TEX},
        {m->emissive_tex, GK_MAT_EMISSIVE_TEX},    {m->normal_tex, GK_MAT_NORMAL_TEX},
        {m->occlusion_tex, GK_MAT_OCCLUSION_TEX},
    };
    int flags = 0;
    for (int k = 0; k < (int)(sizeof slots / sizeof slots[0]); k++) {
        GLuint tex = g->white_tex;
        if (slots[k].tex >= 0 && slots[k].tex < s->n_textures) {
            tex = g->tex[slots[k].tex];
            flags |= slots[k].flag;
        }
        glActiveTexture(GL_TEXTURE0 + (GLenum)k);
        glBindTexture(GL_TEXTURE_2D, tex);
    }
    if (m->light_proxy)
        flags |= GK_MAT_LIGHT_PROXY;
    if (m->double_sided)
        flags |= GK_MAT_DOUBLE_SIDED;
    if (m->alpha_mask)
        flags |= GK_MAT_ALPHA_MASK;
    glUniform1f(u->u_occlusion_strength, m->occlusion_strength);
    glUniform1f(u->u_normal_scale, m->normal_scale);
    glUniform4f(u->u_base_color, m->base_color[0], m->base_color[1], m->base_color[2], m->base_color[3]);
    glUniform2f(u->u_metallic_roughness, m->metallic, m->roughness);
    glUniform3f(u->u_emissive, m->emissive[0], m->emissive[1], m->emissive[2]);
    glUniform1i(u->u_mat_flags, flags);
    float r_ior = (m->ior - 1.0f) / (m->ior + 1.0f);
    float k = r_ior * r_ior;
    glUniform4f(u->u_specular, k * m->specular_color[0], k * m->specular_color[1], k * m->specular_color[2],
                m->specular);
    glUniform2f(u->u_glass, m->ior, m->transmission);
    _Static_assert(GK_TEX_SLOTS == 7, "gbuffer.frag declares u_tex_xf[14]: two rows per slot");
    float xf[GK_TEX_SLOTS * 6];
    int uv1 = 0;
    for (int k = 0; k < GK_TEX_SLOTS; k++) {
        static const float identity[6] = {1, 0, 0, 0, 1, 0};
        const gk_tex_uv *t = &m->tex_uv[k];
        memcpy(&xf[6 * k], t->transformed ? t->m : identity, sizeof identity);
        if (t->texcoord == 1)
            uv1 |= 1 << k;
    }
    glUniform3fv(u->u_tex_xf, 2 * GK_TEX_SLOTS, xf);
    glUniform1i(u->u_tex_uv1, uv1);
    glUniform1f(u->u_alpha_cutoff, m->alpha_cutoff);
}

void gk_draw_uniforms_lookup(GLuint prog, gk_draw_uniforms *u)
{
    u->u_model = glGetUniformLocation(prog, "u_model");
    u->u_normal_matrix = glGetUniformLocation(prog, "u_normal_matrix");
    u->u_base_color = glGetUniformLocation(prog, "u_base_color");
    u->u_metallic_roughness = glGetUniformLocation(prog, "u_metallic_roughness");
    u->u_emissive = glGetUniformLocation(prog, "u_emissive");
    u->u_mat_flags = glGetUniformLocation(prog, "u_mat_flags");
    u->u_base_tex = glGetUniformLocation(prog, "u_base_tex");
    u->u_mr_tex = glGetUniformLocation(prog, "u_mr_tex");
    u->u_specular = glGetUniformLocation(prog, "u_specular");
    u->u_spec_tex = glGetUniformLocation(prog, "u_spec_tex");
    u->u_spec_color_tex = glGetUniformLocation(prog, "u_spec_color_tex");
    u->u_emissive_tex = glGetUniformLocation(prog, "u_emissive_tex");
    u->u_normal_tex = glGetUniformLocation(prog, "u_normal_tex");
    u->u_normal_scale = glGetUniformLocation(prog, "u_normal_scale");
    u->u_occlusion_tex = glGetUniformLocation(prog, "u_occlusion_tex");
    u->u_occlusion_strength = glGetUniformLocation(prog, "u_occlusion_strength");
    u->u_glass = glGetUniformLocation(prog, "u_glass");
    u->u_tex_xf = glGetUniformLocation(prog, "u_tex_xf");
    u->u_tex_uv1 = glGetUniformLocation(prog, "u_tex_uv1");
    u->u_alpha_cutoff = glGetUniformLocation(prog, "u_alpha_cutoff");
    u->u_node_mesh = glGetUniformLocation(prog, "u_node_mesh");
}

static void set_node(const gk_node *node, const gk_draw_uniforms *u)
{
    mat4 nm = m4_transpose(m4_inverse(node->world));
    glUniformMatrix4fv(u->u_model, 1, GL_FALSE, node->world.m);
    glUniformMatrix4fv(u->u_normal_matrix, 1, GL_FALSE, nm.m);
    /* a mirroring transform turns the winding: glTF's front faces are then clockwise (culling and
       gl_FrontFacing, which decides a single-sided emitter's lit side, follow it) */
    glFrontFace(gk_node_mirrored(node) ? GL_CW : GL_CCW);
}

static void draw_one(const gk_scene_gpu *g, const gk_scene *s, const gk_draw_uniforms *u, int flags, int n, int k)
{
    const gk_mesh *mesh = &s->meshes[k];
    const gk_material *mat = &s->materials[mesh->material >= 0 && mesh->material < s->n_materials ? mesh->material : 0];
    if ((flags & GK_DRAW_SKIP_PROXIES) && mat->light_proxy)
        return;
    bool glass = mat->transmission > 0.0f;
    if (((flags & GK_DRAW_SKIP_GLASS) && glass) || ((flags & GK_DRAW_ONLY_GLASS) && !glass) ||
        ((flags & GK_DRAW_SKIP_BLEND) && mat->alpha_blend))
        return;
    if (flags & GK_DRAW_MATERIALS)
        set_material(g, s, u, mat);
    if (flags & GK_DRAW_CULL_SINGLE_SIDED) {
        if (mat->double_sided)
            glDisable(GL_CULL_FACE);
        else
            glEnable(GL_CULL_FACE);
    }
    if (u->u_node_mesh >= 0)
        glUniform2i(u->u_node_mesh, n, k);
    glBindVertexArray(g->vao[k]);
    glDrawElements(GL_TRIANGLES, g->index_count[k], GL_UNSIGNED_INT, NULL);
}

static void set_sampler_units(const gk_draw_uniforms *u, int flags)
{
    if (!(flags & GK_DRAW_MATERIALS))
        return;
    glUniform1i(u->u_base_tex, 0);
    glUniform1i(u->u_mr_tex, 1);
    glUniform1i(u->u_spec_tex, 2);
    glUniform1i(u->u_spec_color_tex, 3);
    glUniform1i(u->u_emissive_tex, 4);
    glUniform1i(u->u_normal_tex, 5);
    glUniform1i(u->u_occlusion_tex, 6);
}

void gk_scene_gpu_draw(const gk_scene_gpu *g, const gk_scene *s, const gk_draw_uniforms *u, int flags)
{
    set_sampler_units(u, flags);
    for (int n = 0; n < s->n_nodes; n++) {
        const gk_node *node = &s->nodes[n];
        if (node->mesh_count <= 0)
            continue;
        set_node(node, u);
        for (int k = node->mesh_first; k < node->mesh_first + node->mesh_count && k < g->n_meshes; k++)
            if (k >= 0)
                draw_one(g, s, u, flags, n, k);
    }
    glBindVertexArray(0);
    glFrontFace(GL_CCW);
    if (flags & GK_DRAW_CULL_SINGLE_SIDED)
        glDisable(GL_CULL_FACE);
}

void gk_scene_gpu_draw_mesh(const gk_scene_gpu *g, const gk_scene *s, const gk_draw_uniforms *u, int flags, int n, int k)
{
    if (n < 0 || n >= s->n_nodes || k < 0 || k >= g->n_meshes)
        return;
    set_sampler_units(u, flags);
    set_node(&s->nodes[n], u);
    draw_one(g, s, u, flags, n, k);
    glBindVertexArray(0);
    glFrontFace(GL_CCW);
    if (flags & GK_DRAW_CULL_SINGLE_SIDED)
        glDisable(GL_CULL_FACE);
}

static bool any_alpha_mask(const gk_scene *s)
{
    for (int i = 0; i < s->n_materials; i++)
        if (s->materials[i].alpha_mask)
            return true;
    return false;
}

const char *gk_scene_gpu_depth_defines(const gk_scene *s)
{
    return any_alpha_mask(s) ? "#define GK_ALPHA_MASK 1\n" : NULL;
}

int gk_scene_gpu_depth_flags(const gk_scene *s)
{
    return any_alpha_mask(s) ? GK_DRAW_MATERIALS : 0;
}
