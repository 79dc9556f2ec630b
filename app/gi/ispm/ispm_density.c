/* The splat radius from the local photon density (ispm_radius=density; shaders_gles/ispm/
 * density.comp): the hits counted in a screen grid, then each disk sized to hold k photons. Runs
 * between the trace and the splats; the seed's radius (ispm_radius=seed) skips it. */
#include <math.h>

#include "ispm_internal.h"

typedef struct density_uniforms {
    GLint u_phase, u_capacity, u_grid, u_cell, u_viewproj, u_cam, u_pixel_angle, u_k, u_h_min, u_h_max;
} density_uniforms;
static const gk_uniform_field density_fields[] = {
    GK_UNIFORM(density_uniforms, u_phase),    GK_UNIFORM(density_uniforms, u_capacity),
    GK_UNIFORM(density_uniforms, u_grid),     GK_UNIFORM(density_uniforms, u_cell),
    GK_UNIFORM(density_uniforms, u_viewproj), GK_UNIFORM(density_uniforms, u_cam),
    GK_UNIFORM(density_uniforms, u_pixel_angle), GK_UNIFORM(density_uniforms, u_k),
    GK_UNIFORM(density_uniforms, u_h_min),    GK_UNIFORM(density_uniforms, u_h_max)};

int ispm_density_radius(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint prog = gk_program_get_compute(s->ctx.programs, "ispm/density.comp", NULL, e);
    const density_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(density_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    const gk_ispm_debug *d = &s->dbg;
    int gw = (int)ceilf((float)f->width / d->density_cell), gh = (int)ceilf((float)f->height / d->density_cell);
    long cells = (long)gw * gh;
    if (!s->grid_ssbo || cells > s->grid_cap) {
        if (!s->grid_ssbo)
            glGenBuffers(1, &s->grid_ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->grid_ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, cells * 4, NULL, GL_DYNAMIC_COPY);
        s->grid_cap = cells;
    }
    glUseProgram(prog);
    glUniform1i(u->u_capacity, s->capacity);
    glUniform2i(u->u_grid, gw, gh);
    glUniform1f(u->u_cell, d->density_cell);
    glUniformMatrix4fv(u->u_viewproj, 1, GL_FALSE, f->view_proj.m);
    glUniform3f(u->u_cam, f->eye.x, f->eye.y, f->eye.z);
    glUniform1f(u->u_pixel_angle, 2.0f / f->proj.m[5] / (float)f->height);
    glUniform1f(u->u_k, d->density_k);
    glUniform1f(u->u_h_min, d->h_min_rel * s->diam);
    glUniform1f(u->u_h_max, d->h_max_rel * s->diam);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s->hit_buf);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, s->grid_ssbo);
    for (int phase = 0; phase < 3; phase++) {
        GLuint n = phase == 0 ? (GLuint)cells : (GLuint)s->capacity;
        glUniform1i(u->u_phase, phase);
        glDispatchCompute((n + 63) / 64, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    /* the hits are read next as instance attributes */
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    return 0;
}
