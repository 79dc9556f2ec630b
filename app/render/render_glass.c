/* Transmissive surfaces in the real-time image (the `glass` pass; what it shows is said in
 * shaders_gles/glass/refract.frag and the README): the G-buffer leaves glass out (GK_DRAW_SKIP_GLASS),
 * so direct light and GI shade the opaque scene behind it; after the GI pass, the image shown so far
 * is copied into the glass target and the glass meshes are drawn over it with a screen-space
 * refraction lookup into that image. The glass target then becomes the image compose shows. Scenes
 * without transmissive materials skip the pass (no column in their stats). */
#include "render_glass.h"

#include "renderer_internal.h"

/* glass/refract.frag with gbuffer/gbuffer.vert */
typedef struct glass_uniforms {
    GLint u_behind, u_depth, u_viewproj, u_inv_viewproj, u_eye, u_glass, u_size;
    gk_draw_uniforms draw;
} glass_uniforms;
static const gk_uniform_field glass_fields[] = {
    GK_UNIFORM(glass_uniforms, u_behind),
    GK_UNIFORM(glass_uniforms, u_depth),
    GK_UNIFORM(glass_uniforms, u_viewproj),
    GK_UNIFORM(glass_uniforms, u_inv_viewproj),
    GK_UNIFORM(glass_uniforms, u_eye),
    GK_UNIFORM(glass_uniforms, u_glass),
    GK_UNIFORM(glass_uniforms, u_size),
    GK_UNIFORM_AS(glass_uniforms, draw.u_model, "u_model"),
    GK_UNIFORM_AS(glass_uniforms, draw.u_normal_matrix, "u_normal_matrix"),
    GK_UNIFORM_AS(glass_uniforms, draw.u_base_color, "u_base_color"),
    GK_UNIFORM_AS(glass_uniforms, draw.u_glass, "u_glass"),
};

/* compose/compose.frag, linear: a plain copy of the shown image */
typedef struct copy_uniforms {
    GLint u_hdr, u_exposure;
} copy_uniforms;
static const gk_uniform_field copy_fields[] = {GK_UNIFORM(copy_uniforms, u_hdr), GK_UNIFORM(copy_uniforms, u_exposure)};

/* Units above the seven gk_scene_gpu_draw binds material textures to (0..6). */
enum { UNIT_GLASS_BEHIND = 7, UNIT_GLASS_DEPTH = 8 };

bool gk_render_glass_needed(const gk_renderer *r) { return r->scene && r->scene->features.has_transmission; }

static int ensure_target(gk_renderer *r, gk_err *e)
{
    gk_target *t = &r->glass;
    if (t->fbo && t->width == r->render_w && t->height == r->render_h)
        return 0;
    gk_target_destroy(t);
    const GLenum fmt[1] = {GL_RGBA16F};
    return gk_target_create(t, "glass", r->render_w, r->render_h, 1, fmt, GL_LINEAR, true, e);
}

int gk_render_glass(gk_renderer *r, const gk_gbuffer_view *gb, gk_err *e)
{
    if (ensure_target(r, e) != 0)
        return -1;
    GLuint copy = gk_program_get(r->progs, "common/fullscreen.vert", "compose/compose.frag", "#define GK_LINEAR_OUT 1\n", e);
    const copy_uniforms *cu = copy ? gk_program_uniforms(r->progs, copy, GK_FIELDS(copy_fields), sizeof *cu, e) : NULL;
    const char *count_define = gk_render_work_glass_begin(r);
    GLuint prog = gk_program_get(r->progs, "gbuffer/gbuffer.vert", "glass/refract.frag",
                                 count_define[0] ? count_define : NULL, e);
    const glass_uniforms *u = prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(glass_fields), sizeof *u, e) : NULL;
    if (!cu || !u) {
        gk_render_work_glass_end(r, 0);
        return -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, r->glass.fbo);
    glViewport(0, 0, r->render_w, r->render_h);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(copy);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->shown);
    glUniform1i(cu->u_hdr, 0);
    glUniform1f(cu->u_exposure, 1.0f);
    gk_render_fullscreen(r);

    /* Glass over glass: the nearest glass surface wins (its own depth buffer); the opaque scene's
       depth is tested in the shader, which samples the G-buffer's depth. */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClear(GL_DEPTH_BUFFER_BIT);
    glUseProgram(prog);
    glActiveTexture(GL_TEXTURE0 + UNIT_GLASS_BEHIND);
    glBindTexture(GL_TEXTURE_2D, r->shown);
    glUniform1i(u->u_behind, UNIT_GLASS_BEHIND);
    glActiveTexture(GL_TEXTURE0 + UNIT_GLASS_DEPTH);
    glBindTexture(GL_TEXTURE_2D, gb->depth);
    glUniform1i(u->u_depth, UNIT_GLASS_DEPTH);
    glUniformMatrix4fv(u->u_viewproj, 1, GL_FALSE, gb->view_proj.m);
    glUniformMatrix4fv(u->u_inv_viewproj, 1, GL_FALSE, gb->inv_view_proj.m);
    glUniform3f(u->u_eye, gb->eye.x, gb->eye.y, gb->eye.z);
    glUniform2f(u->u_size, (float)r->render_w, (float)r->render_h);
    gk_scene_gpu_draw(&r->gpu, r->scene, &u->draw, GK_DRAW_MATERIALS | GK_DRAW_ONLY_GLASS);
    gk_render_work_glass_end(r, (long)r->render_w * r->render_h); /* the copy: one lookup a pixel */
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    r->shown = r->glass.color[0];
    return 0;
}
