/* Depth maps shared by the shadow methods: the scene (light proxies left out: the light itself
 * stands in their place) rendered from each face of a light into a DEPTH_COMPONENT32F array
 * layer. 32F depth is core GLES 3.0 (no extension) and keeps linear-depth reconstruction exact
 * enough for PCSS's blocker averages. */
#include "shadow.h"

#include <stdio.h>

#include "gl/gl_target.h"

static int ensure_texture(gk_shadow_maps *m, int slot, int size, int layers, gk_err *e)
{
    if (m->tex[slot] && m->size[slot] == size && m->layers[slot] == layers)
        return 0;
    if (m->tex[slot])
        glDeleteTextures(1, &m->tex[slot]);
    while (glGetError() != GL_NO_ERROR) {
    }
    glGenTextures(1, &m->tex[slot]);
    glBindTexture(GL_TEXTURE_2D_ARRAY, m->tex[slot]);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        glDeleteTextures(1, &m->tex[slot]);
        m->tex[slot] = 0;
        return gk_fail(e, GK_ERUNTIME, "shadow map %dx%dx%d (DEPTH_COMPONENT32F): %s", size, size, layers,
                       gk_gl_error_name(err));
    }
    m->size[slot] = size;
    m->layers[slot] = layers;
    return 0;
}

/* shadow/depth.{vert,frag} */
typedef struct depth_uniforms {
    GLint u_viewproj;
    gk_draw_uniforms draw;
} depth_uniforms;
static const gk_uniform_field depth_fields[] = {GK_UNIFORM(depth_uniforms, u_viewproj),
                                                GK_UNIFORM_AS(depth_uniforms, draw.u_model, "u_model"),
                                                GK_ALPHA_MASK_FIELDS(depth_uniforms, draw)};

/* shaders_gles/shadow/common.glsl, in the lighting program */
typedef struct maps_uniforms {
    GLint u_shadow_map, u_shadow_viewproj, u_shadow_inv_viewproj, u_shadow_pos, u_shadow_axis, u_shadow_basis,
        u_shadow_proj, u_shadow_light;
} maps_uniforms;
static const gk_uniform_field maps_fields[] = {
    GK_UNIFORM(maps_uniforms, u_shadow_map),   GK_UNIFORM(maps_uniforms, u_shadow_viewproj),
    GK_UNIFORM(maps_uniforms, u_shadow_inv_viewproj), GK_UNIFORM(maps_uniforms, u_shadow_pos),
    GK_UNIFORM(maps_uniforms, u_shadow_axis),  GK_UNIFORM(maps_uniforms, u_shadow_basis),
    GK_UNIFORM(maps_uniforms, u_shadow_proj),  GK_UNIFORM(maps_uniforms, u_shadow_light),
};

static int render_maps(gk_shadow_maps *m, const gk_shadow_ctx *ctx, int slot, const gk_shadow_view *v, gk_err *e)
{
    if (slot < 0 || slot >= GK_SHADOW_MAX_LIGHTS)
        return gk_fail(e, GK_ERUNTIME, "shadow slot %d out of range", slot);
    if (ensure_texture(m, slot, v->map_size, v->n_faces, e) != 0)
        return -1;
    const char *mask = gk_scene_gpu_depth_defines(ctx->scene), *count = ctx->count_define;
    char defines[96];
    snprintf(defines, sizeof defines, "%s%s", mask ? mask : "", count ? count : "");
    GLuint prog = gk_program_get(ctx->progs, "shadow/depth.vert", "shadow/depth.frag", defines[0] ? defines : NULL, e);
    const depth_uniforms *u = prog ? gk_program_uniforms(ctx->progs, prog, GK_FIELDS(depth_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    if (!m->fbo)
        glGenFramebuffers(1, &m->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    GLenum none = GL_NONE;
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
    glUseProgram(prog);
    glViewport(0, 0, v->map_size, v->map_size);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    /* A small slope-scaled offset; the lookups add a normal offset and a half-texel bias. */
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    for (int f = 0; f < v->n_faces; f++) {
        if (f == v->skip_face)
            continue;
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, m->tex[slot], 0, f);
        if (f == 0 && gk_fbo_check("shadow map", e) != 0) {
            glDisable(GL_POLYGON_OFFSET_FILL);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            return -1;
        }
        glClear(GL_DEPTH_BUFFER_BIT);
        glUniformMatrix4fv(u->u_viewproj, 1, GL_FALSE, v->viewproj[f].m);
        /* with materials when some are alpha-masked: they discard their cut-outs (shadow/depth.frag) */
        gk_scene_gpu_draw(ctx->gpu, ctx->scene, &u->draw, gk_scene_gpu_depth_flags(ctx->scene) | GK_DRAW_SKIP_PROXIES);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return 0;
}

/* The depth maps every method starts from, as the sub-pass `shadow.shadow_depth`: what a method's
   own prefilter adds is then its own sub-pass beside it. */
int gk_shadow_maps_render(gk_shadow_maps *m, const gk_shadow_ctx *ctx, int slot, const gk_shadow_view *v, gk_err *e)
{
    gk_pass_begin(ctx->pass, "shadow_depth");
    int rc = render_maps(m, ctx, slot, v, e);
    gk_pass_end(ctx->pass);
    return rc;
}

int gk_shadow_maps_bind(const gk_shadow_maps *m, gk_program_cache *progs, int slot, const gk_shadow_view *v,
                        GLuint prog, int unit, gk_err *e)
{
    const maps_uniforms *u = gk_program_uniforms(progs, prog, GK_FIELDS(maps_fields), sizeof *u, e);
    if (!u)
        return -1;
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, m->tex[slot]);
    glUniform1i(u->u_shadow_map, unit);
    glUniformMatrix4fv(u->u_shadow_viewproj, v->n_faces, GL_FALSE, v->viewproj[0].m);
    mat4 inv[GK_SHADOW_MAX_FACES];
    for (int f = 0; f < v->n_faces; f++)
        inv[f] = m4_inverse(v->viewproj[f]);
    glUniformMatrix4fv(u->u_shadow_inv_viewproj, v->n_faces, GL_FALSE, inv[0].m);
    glUniform3f(u->u_shadow_pos, v->pos.x, v->pos.y, v->pos.z);
    glUniform3f(u->u_shadow_axis, v->axis.x, v->axis.y, v->axis.z);
    const float basis[9] = {v->basis[0].x, v->basis[0].y, v->basis[0].z, v->basis[1].x, v->basis[1].y,
                            v->basis[1].z, v->basis[2].x, v->basis[2].y, v->basis[2].z};
    glUniformMatrix3fv(u->u_shadow_basis, 1, GL_FALSE, basis);
    glUniform4f(u->u_shadow_proj, v->znear, v->zfar, v->ortho ? 1.0f : 0.0f, (float)v->n_faces);
    glUniform4f(u->u_shadow_light, v->size_u, v->size_v, v->tan_half_fov, (float)v->map_size);
    return 0;
}

void gk_shadow_maps_free(gk_shadow_maps *m)
{
    for (int i = 0; i < GK_SHADOW_MAX_LIGHTS; i++)
        if (m->tex[i])
            glDeleteTextures(1, &m->tex[i]);
    if (m->fbo)
        glDeleteFramebuffers(1, &m->fbo);
}
