#include "gbuffer_bind.h"

void gk_gbuffer_bind(const gk_gbuffer_view *g, const gk_gbuffer_uniforms *u, int first_unit, GLuint sampler)
{
    const GLuint tex[GK_GBUFFER_UNITS] = {g->albedo, g->normal, g->emission, g->depth, g->specular};
    const GLint loc[GK_GBUFFER_UNITS] = {u->u_gb_albedo, u->u_gb_normal, u->u_gb_emission, u->u_gb_depth,
                                         u->u_gb_specular};
    for (int i = 0; i < GK_GBUFFER_UNITS; i++) {
        GLint unit = first_unit + i;
        glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
        glBindTexture(GL_TEXTURE_2D, tex[i]);
        glBindSampler((GLuint)unit, sampler);
        glUniform1i(loc[i], unit);
    }
    glUniformMatrix4fv(u->u_inv_viewproj, 1, GL_FALSE, g->inv_view_proj.m);
    glUniform3f(u->u_eye, g->eye.x, g->eye.y, g->eye.z);
    glUniform2f(u->u_viewport, (float)g->width, (float)g->height);
}

void gk_gbuffer_bind_geom_normal(const gk_gbuffer_view *g, GLint location, int unit, GLuint sampler)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, g->geom_normal ? g->geom_normal : g->normal);
    glBindSampler((GLuint)unit, sampler);
    glUniform1i(location, unit);
}
