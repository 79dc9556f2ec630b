/* volcaustics passes 3-5 (research dong-001.md §6.3): every caustic-buffer texel's light ray as one
 * GL_LINES segment built in the vertex shader from gl_VertexID (no geometry shader), each fragment
 * adding the single scattering where the view ray crosses the line, into the (B) image (RGBA32F or
 * RGBA16F, additive blending; every caustic light's lines into the same image), culled behind the scene's surfaces (shaders_gles/volcaustics/lines.*). */
#include <math.h>

#include "medium_uniforms.h"
#include "vc_internal.h"

/* The seed's Gaussian filter [Jensen01] (lines.frag) over [-1, 1] (r_f = 1), by the midpoint rule
   with 4096 steps (smooth integrand: exact to 1e-7): 1.3024 (alpha 0.918, beta 1.953). */
double vc_filter_integral_unit(void)
{
    const double alpha = 0.918, beta = 1.953;
    const int n = 4096;
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        double x = -1.0 + (i + 0.5) * 2.0 / n;
        sum += alpha * (1.0 - (1.0 - exp(-beta * x * x / 2.0)) / (1.0 - exp(-beta))) * 2.0 / n;
    }
    return sum;
}

typedef struct lines_uniforms {
    GLint u_p1, u_p2, u_flux, u_res, u_view_proj, u_depth, u_inv_view_proj, u_eye, u_fwd, u_size, u_pix_area, u_dx,
        u_rf, u_filter_norm;
    vc_medium_uniforms med;
} lines_uniforms;
static const gk_uniform_field lines_fields[] = {
    GK_UNIFORM(lines_uniforms, u_p1), GK_UNIFORM(lines_uniforms, u_p2), GK_UNIFORM(lines_uniforms, u_flux),
    GK_UNIFORM(lines_uniforms, u_res), GK_UNIFORM(lines_uniforms, u_view_proj), GK_UNIFORM(lines_uniforms, u_depth),
    GK_UNIFORM(lines_uniforms, u_inv_view_proj), GK_UNIFORM(lines_uniforms, u_eye), GK_UNIFORM(lines_uniforms, u_fwd),
    GK_UNIFORM(lines_uniforms, u_size), GK_UNIFORM(lines_uniforms, u_pix_area), GK_UNIFORM(lines_uniforms, u_dx),
    GK_UNIFORM(lines_uniforms, u_rf), GK_UNIFORM(lines_uniforms, u_filter_norm),
    VC_MEDIUM_FIELDS(lines_uniforms, med),
};

static void bind_tex(int unit, GLuint tex, GLint loc)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(loc, unit);
}

int vc_lines(vc_state *s, const gk_gi_frame *f, int n, gk_err *e)
{
    GLuint prog = gk_program_get(s->ctx.programs, "volcaustics/lines.vert", "volcaustics/lines.frag",
                                 vc_work_begin(s, VC_WORK_LINES), e);
    const lines_uniforms *u =
        prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(lines_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->caustic.fbo);
    const GLenum b0 = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &b0);
    glViewport(0, 0, s->caustic.width, s->caustic.height);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(prog);
    bind_tex(3, f->gbuf_depth, u->u_depth);
    glUniform1i(u->u_res, s->cb_res);
    glUniformMatrix4fv(u->u_view_proj, 1, GL_FALSE, f->view_proj.m);
    glUniformMatrix4fv(u->u_inv_view_proj, 1, GL_FALSE, f->inv_view_proj.m);
    glUniform3f(u->u_eye, f->eye.x, f->eye.y, f->eye.z);
    /* the optical axis: the view matrix's -Z row (world) */
    vec3 fwd = v3_norm(v3(-f->view.m[2], -f->view.m[6], -f->view.m[10]));
    glUniform3f(u->u_fwd, fwd.x, fwd.y, fwd.z);
    glUniform2f(u->u_size, (float)f->width, (float)f->height);
    /* a pixel on the image plane at distance 1: (2 tan_x / W)(2 tan_y / H), proj[0][0] = 1/tan_x */
    float pix_area = 4.0f / (f->proj.m[0] * f->proj.m[5] * (float)f->width * (float)f->height);
    glUniform1f(u->u_pix_area, pix_area);
    glUniform1f(u->u_dx, s->dx);
    glUniform1f(u->u_rf, s->rf);
    glUniform1f(u->u_filter_norm, (float)(1.0 / (vc_filter_integral_unit() * s->rf)));
    vc_set_medium(&u->med, f->scene);
    glBindVertexArray(s->empty_vao);
    for (int i = 0; i < n; i++) {   /* the lights' lines add into one image */
        bind_tex(0, s->cb[i].p1, u->u_p1);
        bind_tex(1, s->cb[i].p2, u->u_p2);
        bind_tex(2, s->cb[i].flux, u->u_flux);
        glDrawArrays(GL_LINES, 0, 2 * s->cb_res * s->cb_res);
    }
    vc_work_end(s, VC_WORK_LINES);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    return 0;
}
