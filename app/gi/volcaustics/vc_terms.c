/* volcaustics terms (A) and (C) and the composite D = A + B + C (research dong-001.md §6.1, §6.3
 * passes 6-8): (A) by a shadowed ray march at the march resolution (shaders_gles/volcaustics/
 * airlight.frag) into an RGBA16F image, then two full-screen draws over the renderer's HDR image:
 * one multiplies it by the medium's transmittances (C), one adds A (bilinear), B and the surface
 * caustics of (C) (composite.frag). */
#include <math.h>
#include <stdio.h>

#include "medium_uniforms.h"
#include "vc_internal.h"

void vc_set_medium(const vc_medium_uniforms *u, const gk_scene *sc)
{
    const gk_medium *m = &sc->medium;
    glUniform3f(u->u_sigma_s, m->sigma_s[0], m->sigma_s[1], m->sigma_s[2]);
    glUniform3f(u->u_sigma_t, m->sigma_s[0] + m->sigma_a[0], m->sigma_s[1] + m->sigma_a[1], m->sigma_s[2] + m->sigma_a[2]);
    glUniform1f(u->u_hg_g, m->g);
    vec3 lo = m->bounded ? m->box_min : v3(-VC_UNBOUNDED, -VC_UNBOUNDED, -VC_UNBOUNDED);
    vec3 hi = m->bounded ? m->box_max : v3(VC_UNBOUNDED, VC_UNBOUNDED, VC_UNBOUNDED);
    glUniform3f(u->u_box_min, lo.x, lo.y, lo.z);
    glUniform3f(u->u_box_max, hi.x, hi.y, hi.z);
}

static void bind_tex(int unit, GLuint tex, GLint loc)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(loc, unit);
}

/* (A)'s march steps per pixel: fixed; the march resolution (vc_march) is its budget. 48 steps of the
   2-3 m a ray crosses the fog layer of caustic-ring-fog: 5-6 cm, the ring wall's shadow spans
   several steps. */
#define VC_AIR_STEPS 48

typedef struct air_uniforms {
    GLint u_depth, u_shadow[VC_MAX_LIGHTS], u_n_lights, u_light_kind, u_light_pos, u_light_dir, u_light_radiant,
        u_light_cone, u_light_shadow, u_shadow_vp, u_inv_view_proj, u_eye, u_full_size, u_size, u_steps;
    vc_medium_uniforms med;
} air_uniforms;
static const gk_uniform_field air_fields[] = {
    GK_UNIFORM(air_uniforms, u_depth),
    GK_UNIFORM_AS(air_uniforms, u_shadow[0], "u_shadow0"), GK_UNIFORM_AS(air_uniforms, u_shadow[1], "u_shadow1"),
    GK_UNIFORM_AS(air_uniforms, u_shadow[2], "u_shadow2"), GK_UNIFORM_AS(air_uniforms, u_shadow[3], "u_shadow3"),
    GK_UNIFORM(air_uniforms, u_n_lights),
    GK_UNIFORM_AS(air_uniforms, u_light_kind, "u_light_kind[0]"), GK_UNIFORM_AS(air_uniforms, u_light_pos, "u_light_pos[0]"),
    GK_UNIFORM_AS(air_uniforms, u_light_dir, "u_light_dir[0]"),
    GK_UNIFORM_AS(air_uniforms, u_light_radiant, "u_light_radiant[0]"),
    GK_UNIFORM_AS(air_uniforms, u_light_cone, "u_light_cone[0]"),
    GK_UNIFORM_AS(air_uniforms, u_light_shadow, "u_light_shadow[0]"),
    GK_UNIFORM_AS(air_uniforms, u_shadow_vp, "u_shadow_vp[0]"),
    GK_UNIFORM(air_uniforms, u_inv_view_proj), GK_UNIFORM(air_uniforms, u_eye), GK_UNIFORM(air_uniforms, u_full_size),
    GK_UNIFORM(air_uniforms, u_size), GK_UNIFORM(air_uniforms, u_steps),
    VC_MEDIUM_FIELDS(air_uniforms, med),
};

int vc_airlight(vc_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint prog = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "volcaustics/airlight.frag",
                                 vc_work_begin(s, VC_WORK_AIRLIGHT), e);
    const air_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(air_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->air.fbo);
    const GLenum b0 = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &b0);
    glViewport(0, 0, s->air.width, s->air.height);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(prog);
    bind_tex(0, f->gbuf_depth, u->u_depth);
    int kind[VC_MAX_LIGHTS] = {0}, shadow[VC_MAX_LIGHTS] = {0}, n = 0;
    float pos[VC_MAX_LIGHTS][3], dir[VC_MAX_LIGHTS][3], rad[VC_MAX_LIGHTS][3], cone[VC_MAX_LIGHTS][2], vp[VC_MAX_LIGHTS][16];
    for (int i = 0; i < f->n_lights && n < VC_MAX_LIGHTS; i++) {
        const gk_gi_light *L = &f->lights[i];
        const gk_light *sl = &f->scene->lights[L->scene_light];
        kind[n] = sl->type == GK_LIGHT_DIRECTIONAL ? 2 : sl->type == GK_LIGHT_SPOT ? 1 : 0;
        pos[n][0] = L->position.x, pos[n][1] = L->position.y, pos[n][2] = L->position.z;
        dir[n][0] = L->direction.x, dir[n][1] = L->direction.y, dir[n][2] = L->direction.z;
        rad[n][0] = L->radiant.x, rad[n][1] = L->radiant.y, rad[n][2] = L->radiant.z;
        cone[n][0] = cosf(sl->outer_cone), cone[n][1] = cosf(sl->inner_cone);
        shadow[n] = L->shadow_depth_tex != 0;
        for (int k = 0; k < 16; k++)
            vp[n][k] = L->shadow_view_proj.m[k];
        bind_tex(1 + n, L->shadow_depth_tex, u->u_shadow[n]);
        n++;
    }
    for (int i = n; i < VC_MAX_LIGHTS; i++)
        bind_tex(1 + i, 0, u->u_shadow[i]);
    glUniform1i(u->u_n_lights, n);
    if (n > 0) {
        glUniform1iv(u->u_light_kind, n, kind);
        glUniform3fv(u->u_light_pos, n, &pos[0][0]);
        glUniform3fv(u->u_light_dir, n, &dir[0][0]);
        glUniform3fv(u->u_light_radiant, n, &rad[0][0]);
        glUniform2fv(u->u_light_cone, n, &cone[0][0]);
        glUniform1iv(u->u_light_shadow, n, shadow);
        glUniformMatrix4fv(u->u_shadow_vp, n, GL_FALSE, &vp[0][0]);
    }
    glUniformMatrix4fv(u->u_inv_view_proj, 1, GL_FALSE, f->inv_view_proj.m);
    glUniform3f(u->u_eye, f->eye.x, f->eye.y, f->eye.z);
    glUniform2f(u->u_full_size, (float)f->width, (float)f->height);
    glUniform2f(u->u_size, (float)s->air.width, (float)s->air.height);
    glUniform1i(u->u_steps, VC_AIR_STEPS);
    vc_set_medium(&u->med, f->scene);
    glBindVertexArray(s->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    vc_work_end(s, VC_WORK_AIRLIGHT);
    glBindVertexArray(0);
    return 0;
}

typedef struct comp_uniforms {
    GLint u_depth, u_airlight, u_caustics, u_inv_view_proj, u_eye, u_light_pos, u_has_light, u_terms, u_surface,
        u_albedo, u_has_surface;
    vc_medium_uniforms med;
} comp_uniforms;
static const gk_uniform_field comp_fields[] = {
    GK_UNIFORM(comp_uniforms, u_depth), GK_UNIFORM(comp_uniforms, u_airlight), GK_UNIFORM(comp_uniforms, u_caustics),
    GK_UNIFORM(comp_uniforms, u_inv_view_proj), GK_UNIFORM(comp_uniforms, u_eye),
    GK_UNIFORM(comp_uniforms, u_light_pos), GK_UNIFORM(comp_uniforms, u_has_light), GK_UNIFORM(comp_uniforms, u_terms),
    GK_UNIFORM(comp_uniforms, u_surface), GK_UNIFORM(comp_uniforms, u_albedo), GK_UNIFORM(comp_uniforms, u_has_surface),
    VC_MEDIUM_FIELDS(comp_uniforms, med),
};

/* The first local light (C's light-side attenuation). */
static bool first_local_light(const gk_gi_frame *f, vec3 *pos)
{
    for (int i = 0; i < f->n_lights; i++)
        if (f->scene->lights[f->lights[i].scene_light].type != GK_LIGHT_DIRECTIONAL) {
            *pos = f->lights[i].position;
            return true;
        }
    return false;
}

static int composite_draw(vc_state *s, const gk_gi_frame *f, const char *defines, bool have_lines, bool have_surface,
                          gk_err *e)
{
    GLuint prog = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "volcaustics/composite.frag", defines, e);
    const comp_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(comp_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(prog);
    bind_tex(0, f->gbuf_depth, u->u_depth);
    bind_tex(1, s->air.color[0], u->u_airlight);
    bind_tex(2, s->caustic.color[0], u->u_caustics);
    bind_tex(3, have_surface ? s->surface.color[0] : 0, u->u_surface);
    bind_tex(4, f->gbuf_albedo, u->u_albedo);
    glUniform1i(u->u_has_surface, have_surface ? 1 : 0);
    glUniformMatrix4fv(u->u_inv_view_proj, 1, GL_FALSE, f->inv_view_proj.m);
    glUniform3f(u->u_eye, f->eye.x, f->eye.y, f->eye.z);
    vec3 lp = v3(0, 0, 0);
    bool has = first_local_light(f, &lp);
    glUniform3f(u->u_light_pos, lp.x, lp.y, lp.z);
    glUniform1i(u->u_has_light, has ? 1 : 0);
    glUniform1i(u->u_terms, (int)(have_lines ? s->terms : s->terms & ~(unsigned)GK_VC_TERM_VCAUSTICS));
    vc_set_medium(&u->med, f->scene);
    glBindVertexArray(s->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    return 0;
}

int vc_composite(vc_state *s, const gk_gi_frame *f, bool have_lines, bool have_surface, gk_err *e)
{
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr_fbo);
    const GLenum b0 = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &b0);
    glViewport(0, 0, f->width, f->height);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ZERO, GL_SRC_COLOR);   /* C = HDR x T(v, p) T(s, p) */
    const char *count = vc_work_begin(s, VC_WORK_COMPOSITE); /* one count over both draws */
    char defines[96];
    snprintf(defines, sizeof defines, "#define VC_ATTENUATE 1\n%s", count);
    int rc = composite_draw(s, f, defines, have_lines, have_surface, e);
    if (rc == 0) {
        glBlendFunc(GL_ONE, GL_ONE);          /* + A + B */
        snprintf(defines, sizeof defines, "#define VC_ADD 1\n%s", count);
        rc = composite_draw(s, f, defines, have_lines, have_surface, e);
    }
    vc_work_end(s, VC_WORK_COMPOSITE);
    glDisable(GL_BLEND);
    return rc;
}
