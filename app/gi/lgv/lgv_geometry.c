/* The geometry volume of eq. (6)'s fuzzy occlusion G (lgv/lgv_geometry.comp, lgv_geometry_max.comp):
 * built from the lattice maps' texels as surfels whenever the maps or the LGV's grid change (a static
 * scene builds it once), on the LGV's cell corners, 3 fixed-point opacities per corner. */
#include <string.h>

#include "lgv_internal.h"

typedef struct geometry_uniforms {
    GLint u_map, u_grid_min, u_cell, u_gdims, u_fixed;
} geometry_uniforms;
static const gk_uniform_field geometry_fields[] = {
    GK_UNIFORM(geometry_uniforms, u_map),   GK_UNIFORM(geometry_uniforms, u_grid_min),
    GK_UNIFORM(geometry_uniforms, u_cell),  GK_UNIFORM(geometry_uniforms, u_gdims),
    GK_UNIFORM(geometry_uniforms, u_fixed),
};
typedef struct merge_uniforms {
    GLint u_values;
} merge_uniforms;
static const gk_uniform_field merge_fields[] = {GK_UNIFORM(merge_uniforms, u_values)};

int lgv_build_geometry(lgv_state *s, gk_err *e)
{
    int gd[3] = {s->dims[0] + 1, s->dims[1] + 1, s->dims[2] + 1};
    if (s->geo_ssbo && s->geo_cell == s->cell && !memcmp(gd, s->geo_dims, sizeof gd) && s->geo_maps_stamp == s->maps_stamp)
        return 0;
    gk_program_cache *pc = s->ctx.programs;
    const char *count = lgv_work_begin(s, LGV_WORK_GEOMETRY);
    GLuint prog = gk_program_get_compute(pc, "lgv/lgv_geometry.comp", count[0] ? count : NULL, e);
    const geometry_uniforms *u = prog ? gk_program_uniforms(pc, prog, GK_FIELDS(geometry_fields), sizeof *u, e) : NULL;
    GLuint merge = u ? gk_program_get_compute(pc, "lgv/lgv_geometry_max.comp", NULL, e) : 0;
    const merge_uniforms *mu = merge ? gk_program_uniforms(pc, merge, GK_FIELDS(merge_fields), sizeof *mu, e) : NULL;
    if (!mu) {
        lgv_work_end(s, LGV_WORK_GEOMETRY);
        return -1;
    }
    long values = 3L * gd[0] * gd[1] * gd[2];
    s->geo_ssbo = lgv_buffer(s->geo_ssbo, values * 4, true);
    GLuint tmp = lgv_buffer(0, values * 4, true);
    for (int m = 0; m < s->n_maps; m++) { /* lattice maps only: a refractor map sees its glass from inside */
        glUseProgram(prog);
        if (lgv_bind_tracer(s, prog, e) != 0) {
            glDeleteBuffers(1, &tmp);
            lgv_work_end(s, LGV_WORK_GEOMETRY);
            return -1;
        }
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, tmp);
        glUniform1i(u->u_map, m);
        glUniform3f(u->u_grid_min, s->grid_min.x, s->grid_min.y, s->grid_min.z);
        glUniform1f(u->u_cell, s->cell);
        glUniform3i(u->u_gdims, gd[0], gd[1], gd[2]);
        glUniform1f(u->u_fixed, LGV_GEO_FIXED);
        glDispatchCompute((GLuint)(s->maps_res + 7) / 8, (GLuint)(s->maps_res + 7) / 8, 6);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUseProgram(merge);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, tmp);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s->geo_ssbo);
        glUniform1i(mu->u_values, (GLint)values);
        glDispatchCompute((GLuint)(values + 63) / 64, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glDeleteBuffers(1, &tmp);
    lgv_work_end(s, LGV_WORK_GEOMETRY);
    memcpy(s->geo_dims, gd, sizeof gd);
    s->geo_cell = s->cell;
    s->geo_maps_stamp = s->maps_stamp;
    return 0;
}
