/* Splat ellipses from the photons' neighbours (ispm_radius=footprint; shaders_gles/ispm/
 * footprint.comp): the hit of each photon's neighbouring RSM blocks spans its flux tube on the
 * receiver, and the splat takes that shape, narrow across a caustic line and long along it (and
 * averages its kernel over each splat pixel, ispm_splat.c, so that it may be narrower than one). Runs
 * after the density radius (which the hits without neighbours keep) and before the splats, which
 * read the ellipses as two more instance attributes. */
#include <math.h>

#include "ispm_internal.h"

typedef struct footprint_uniforms {
    GLint u_phase, u_capacity, u_res, u_keyed_by_block, u_cam, u_pixel_angle, u_h_pixels, u_c0, u_h_max, u_normal_cos;
} footprint_uniforms;
static const gk_uniform_field footprint_fields[] = {
    GK_UNIFORM(footprint_uniforms, u_phase),       GK_UNIFORM(footprint_uniforms, u_capacity),
    GK_UNIFORM(footprint_uniforms, u_res),         GK_UNIFORM(footprint_uniforms, u_keyed_by_block),
    GK_UNIFORM(footprint_uniforms, u_cam),         GK_UNIFORM(footprint_uniforms, u_pixel_angle),
    GK_UNIFORM(footprint_uniforms, u_h_pixels),    GK_UNIFORM(footprint_uniforms, u_c0),
    GK_UNIFORM(footprint_uniforms, u_h_max),       GK_UNIFORM(footprint_uniforms, u_normal_cos)};

static void ensure_buffers(ispm_state *s)
{
    if (!s->block_ssbo) {
        glGenBuffers(1, &s->block_ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->block_ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, (long)ISPM_RSM_RES * ISPM_RSM_RES * 4, NULL, GL_DYNAMIC_COPY);
    }
    if (s->foot_buf && s->foot_cap == s->capacity)
        return;
    if (!s->foot_buf)
        glGenBuffers(1, &s->foot_buf);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->foot_buf);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (long)s->capacity * ISPM_FOOT_BYTES, NULL, GL_DYNAMIC_COPY);
    s->foot_cap = s->capacity;
}

int ispm_footprint(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint prog = gk_program_get_compute(s->ctx.programs, "ispm/footprint.comp", NULL, e);
    const footprint_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(footprint_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    ensure_buffers(s);
    const gk_ispm_debug *d = &s->dbg;
    int sw, sh;
    ispm_splat_size(s, f, &sw, &sh);
    glUseProgram(prog);
    glUniform1i(u->u_capacity, s->capacity);
    glUniform1i(u->u_res, ISPM_RSM_RES);
    glUniform1i(u->u_keyed_by_block, !d->rng_by_slot);
    glUniform3f(u->u_cam, f->eye.x, f->eye.y, f->eye.z);
    glUniform1f(u->u_pixel_angle, 2.0f / f->proj.m[5] / (float)sh);
    /* the least semi-axis in kernel samples: the splat averages its kernel over each pixel */
    glUniform1f(u->u_h_pixels, d->h_pixels / (float)(d->pixel_samples > 1 ? d->pixel_samples : 1));
    glUniform1f(u->u_c0, d->c0);
    glUniform1f(u->u_h_max, d->h_max_rel * s->diam);
    glUniform1f(u->u_normal_cos, ISPM_SAME_SURFACE_COS);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s->photon_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s->hit_buf);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s->block_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s->foot_buf);
    for (int phase = 0; phase < 3; phase++) {
        GLuint n = phase == 0 ? (GLuint)(ISPM_RSM_RES * ISPM_RSM_RES) : (GLuint)s->capacity;
        glUniform1i(u->u_phase, phase);
        glDispatchCompute((n + 63) / 64, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    /* the ellipses are read next as instance attributes */
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    return 0;
}
