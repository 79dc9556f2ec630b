/* volcaustics surface caustics under (C) (research dong-001.md §6.1: "(C) surface illumination incl.
 * surface caustics"; the seed takes them from Hierarchical Caustic Maps [Wyman08b], a separate
 * module). Here from the same light rays the volume caustic draws, so the two caustics agree: each
 * caustic-buffer ray ends on a surface at p2 and is splatted there as a photon of flux
 * Phi T(p1, p2) with a normalised kernel whose radius follows the beam's footprint
 * (shaders_gles/volcaustics/surface.*), into a screen-resolution irradiance image E. The composite
 * adds (albedo / pi) E T(eye, p) to (C). Knob vc_surface (off | splat). */
#include <math.h>

#include "medium_uniforms.h"
#include "vc_internal.h"

typedef struct surface_uniforms {
    GLint u_p1, u_p2, u_flux, u_res, u_view_proj, u_px_per_rad, u_h_max, u_max_point, u_depth, u_normal,
        u_inv_view_proj, u_size;
    vc_medium_uniforms med;
} surface_uniforms;
static const gk_uniform_field surface_fields[] = {
    GK_UNIFORM(surface_uniforms, u_p1), GK_UNIFORM(surface_uniforms, u_p2), GK_UNIFORM(surface_uniforms, u_flux),
    GK_UNIFORM(surface_uniforms, u_res), GK_UNIFORM(surface_uniforms, u_view_proj),
    GK_UNIFORM(surface_uniforms, u_px_per_rad), GK_UNIFORM(surface_uniforms, u_h_max),
    GK_UNIFORM(surface_uniforms, u_max_point), GK_UNIFORM(surface_uniforms, u_depth),
    GK_UNIFORM(surface_uniforms, u_normal), GK_UNIFORM(surface_uniforms, u_inv_view_proj),
    GK_UNIFORM(surface_uniforms, u_size),
    VC_MEDIUM_FIELDS(surface_uniforms, med),
};

static void bind_tex(int unit, GLuint tex, GLint loc)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(loc, unit);
}

/* The largest kernel radius: 5% of the scene's bounding diagonal (a beam spread wider than that is
   diffuse light, not a caustic; the cap also bounds the point sprites' fill). */
#define VC_SPLAT_MAX_OF_SCENE 0.05f

int vc_surface_caustics(vc_state *s, const gk_gi_frame *f, int n, gk_err *e)
{
    GLuint prog = gk_program_get(s->ctx.programs, "volcaustics/surface.vert", "volcaustics/surface.frag",
                                 vc_work_begin(s, VC_WORK_SURFACE), e);
    const surface_uniforms *u =
        prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(surface_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->surface.fbo);
    const GLenum b0 = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &b0);
    glViewport(0, 0, s->surface.width, s->surface.height);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(prog);
    bind_tex(3, f->gbuf_depth, u->u_depth);
    bind_tex(4, f->gbuf_normal, u->u_normal);
    glUniform1i(u->u_res, s->cb_res);
    glUniformMatrix4fv(u->u_view_proj, 1, GL_FALSE, f->view_proj.m);
    glUniformMatrix4fv(u->u_inv_view_proj, 1, GL_FALSE, f->inv_view_proj.m);
    glUniform1f(u->u_px_per_rad, 0.5f * f->proj.m[5] * (float)f->height);
    glUniform1f(u->u_h_max, VC_SPLAT_MAX_OF_SCENE * v3_len(v3_sub(s->scene_max, s->scene_min)));
    GLfloat range[2] = {1.0f, 1.0f};
    glGetFloatv(GL_ALIASED_POINT_SIZE_RANGE, range);
    glUniform1f(u->u_max_point, range[1]);
    glUniform2f(u->u_size, (float)f->width, (float)f->height);
    vc_set_medium(&u->med, f->scene);
    glBindVertexArray(s->empty_vao);
    for (int i = 0; i < n; i++) {
        bind_tex(0, s->cb[i].p1, u->u_p1);
        bind_tex(1, s->cb[i].p2, u->u_p2);
        bind_tex(2, s->cb[i].flux, u->u_flux);
        glDrawArrays(GL_POINTS, 0, s->cb_res * s->cb_res);
    }
    vc_work_end(s, VC_WORK_SURFACE);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    return 0;
}
