/* Seed 000 passes 11–13: the photon trace through the lists, the disk splats at the splat
 * resolution, and the joint bilateral upsampling that adds ρ_d/π · E_caustic to the HDR image
 * (shaders_gles/ispm/trace.comp, splat.*, upsample.frag). */
#include <math.h>
#include <stdio.h>

#include "gl/gbuffer_bind.h"
#include "ispm_internal.h"

typedef struct trace_uniforms {
    GLint u_view, u_proj, u_res, u_near, u_tmax, u_eps_abs, u_eps_slope, u_backface, u_plane, u_hit_px, u_edge_on_cos, u_edge_reach, u_skip_rel, u_bounces,
        u_mirror_shape, u_capacity, u_c0, u_omega_texel, u_cos_min, u_h_min, u_h_max;
} trace_uniforms;
static const gk_uniform_field trace_fields[] = {
    GK_UNIFORM(trace_uniforms, u_view),     GK_UNIFORM(trace_uniforms, u_proj),        GK_UNIFORM(trace_uniforms, u_res),
    GK_UNIFORM(trace_uniforms, u_near),     GK_UNIFORM(trace_uniforms, u_tmax),        GK_UNIFORM(trace_uniforms, u_eps_abs),
    GK_UNIFORM(trace_uniforms, u_eps_slope), GK_UNIFORM(trace_uniforms, u_backface),   GK_UNIFORM(trace_uniforms, u_plane),
    GK_UNIFORM(trace_uniforms, u_hit_px),   GK_UNIFORM(trace_uniforms, u_edge_on_cos), GK_UNIFORM(trace_uniforms, u_edge_reach),
    GK_UNIFORM(trace_uniforms, u_skip_rel),    GK_UNIFORM(trace_uniforms, u_bounces),
    GK_UNIFORM(trace_uniforms, u_mirror_shape), GK_UNIFORM(trace_uniforms, u_capacity),
    GK_UNIFORM(trace_uniforms, u_c0),       GK_UNIFORM(trace_uniforms, u_omega_texel), GK_UNIFORM(trace_uniforms, u_cos_min),
    GK_UNIFORM(trace_uniforms, u_h_min),    GK_UNIFORM(trace_uniforms, u_h_max)};

typedef struct splat_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_viewproj, u_cam, u_pixel_angle, u_h_pixels, u_to_full, u_plane_tol, u_normal_cos, u_kernel_norm, u_delta,
        u_cone, u_footprint, u_samples;
} splat_uniforms;
static const gk_uniform_field splat_fields[] = {
    GK_GBUFFER_FIELDS(splat_uniforms, gb),   GK_UNIFORM(splat_uniforms, u_viewproj),   GK_UNIFORM(splat_uniforms, u_cam),
    GK_UNIFORM(splat_uniforms, u_pixel_angle), GK_UNIFORM(splat_uniforms, u_h_pixels), GK_UNIFORM(splat_uniforms, u_to_full),
    GK_UNIFORM(splat_uniforms, u_plane_tol), GK_UNIFORM(splat_uniforms, u_normal_cos), GK_UNIFORM(splat_uniforms, u_kernel_norm),
    GK_UNIFORM(splat_uniforms, u_delta),     GK_UNIFORM(splat_uniforms, u_cone),     GK_UNIFORM(splat_uniforms, u_footprint),
    GK_UNIFORM(splat_uniforms, u_samples)};

typedef struct up_uniforms { gk_gbuffer_uniforms gb; GLint u_low, u_to_low, u_k; } up_uniforms;
static const gk_uniform_field up_fields[] = {GK_GBUFFER_FIELDS(up_uniforms, gb), GK_UNIFORM(up_uniforms, u_low),
                                             GK_UNIFORM(up_uniforms, u_to_low), GK_UNIFORM(up_uniforms, u_k)};

/* Near plane and tan(fovy/2) of a GL perspective matrix (column-major). */
static float proj_near(mat4 p) { return p.m[14] / (p.m[10] - 1.0f); }
static float proj_tan_half_y(mat4 p) { return 1.0f / p.m[5]; }

int ispm_trace(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint prog = gk_program_get_compute(s->ctx.programs, "ispm/trace.comp", NULL, e);
    const trace_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(trace_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    const gk_ispm_debug *d = &s->dbg;
    glUseProgram(prog);
    glUniformMatrix4fv(u->u_view, 1, GL_FALSE, f->view.m);
    glUniformMatrix4fv(u->u_proj, 1, GL_FALSE, f->proj.m);
    glUniform2i(u->u_res, s->trace_res, s->trace_res);
    glUniform1f(u->u_near, proj_near(f->proj));
    glUniform1f(u->u_tmax, s->diam);
    glUniform1f(u->u_eps_abs, d->eps_abs_rel * s->diam);
    glUniform1f(u->u_eps_slope, d->eps_slope);
    glUniform1i(u->u_backface, !d->no_backface_rule);
    glUniform1i(u->u_plane, !d->faithful_hit);
    glUniform1f(u->u_hit_px, d->hit_px);
    glUniform1f(u->u_edge_on_cos, d->edge_on_cos);
    glUniform1f(u->u_edge_reach, d->edge_reach);
    /* the empty-space skip's margin with the plane test: the depth slope of a surface seen at
       edge_on_cos over the test's reach, in pixels of the larger angular size */
    float px_angle = 2.0f * fmaxf(proj_tan_half_y(f->proj), 1.0f / f->proj.m[0]) / (float)s->trace_res;
    float slope = sqrtf(1.0f - d->edge_on_cos * d->edge_on_cos) / fmaxf(d->edge_on_cos, 1e-3f);
    glUniform1f(u->u_skip_rel, slope * px_angle * (d->hit_px + 0.5f) * 1.4143f);
    glUniform1i(u->u_bounces, s->bounces);
    glUniform1i(u->u_mirror_shape, !d->flat_mirror_normal);
    glUniform1i(u->u_capacity, s->capacity);
    glUniform1f(u->u_c0, d->c0);
    glUniform1f(u->u_omega_texel, s->light.omega_texel);
    glUniform1f(u->u_cos_min, d->cos_min);
    glUniform1f(u->u_h_min, d->h_min_rel * s->diam);
    glUniform1f(u->u_h_max, d->h_max_rel * s->diam);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s->nodes_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s->pixels_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s->photon_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s->hit_buf);
    glDispatchCompute((GLuint)(s->capacity + 63) / 64, 1, 1);
    /* the hits are read next as instance attributes */
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    return 0;
}

void ispm_splat_size(const ispm_state *s, const gk_gi_frame *f, int *w, int *h)
{
    *w = (int)lroundf((float)f->width * s->splat_scale), *h = (int)lroundf((float)f->height * s->splat_scale);
    *w = *w < 1 ? 1 : *w, *h = *h < 1 ? 1 : *h;
}

static int ensure_splat_target(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    int w, h;
    ispm_splat_size(s, f, &w, &h);
    if (s->splat_fbo && w == s->splat_w && h == s->splat_h)
        return 0;
    if (s->splat_fbo) {
        glDeleteFramebuffers(1, &s->splat_fbo);
        glDeleteTextures(1, &s->splat_tex);
    }
    /* additive blending of irradiance (research A.5): RGBA32F with EXT_float_blend, else RGBA16F
       (colour-renderable with EXT_color_buffer_half_float, checked at create, or 3.2 core) */
    glGenTextures(1, &s->splat_tex);
    glBindTexture(GL_TEXTURE_2D, s->splat_tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, s->splat_fmt, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glGenFramebuffers(1, &s->splat_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->splat_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s->splat_tex, 0);
    GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "ispm: splat target %dx%d %s incomplete (0x%04x)", w, h,
                       s->splat_fmt == GL_RGBA32F ? "RGBA32F" : "RGBA16F", st);
    s->splat_w = w, s->splat_h = h;
    s->st.splat_w = w, s->st.splat_h = h;
    return 0;
}

/* ∫κ dA over the disk of radius 1 (research Appendix E): cone π/3, Gaussian 2πδ(1 − e^{−1/(2δ)}). */
static float kernel_mass(const gk_ispm_debug *d)
{
    const float pi = 3.14159265f;
    return d->cone_kernel ? pi / 3.0f : 2.0f * pi * d->delta * (1.0f - expf(-1.0f / (2.0f * d->delta)));
}

int ispm_splat(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    if (ensure_splat_target(s, f, e))
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->splat_fbo);
    const GLenum b0 = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &b0);
    glViewport(0, 0, s->splat_w, s->splat_h);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    if (!s->light.ok)
        return 0;
    const gk_ispm_debug *d = &s->dbg;
    bool feet = s->radius == ISPM_RADIUS_FOOTPRINT;
    int samples = feet && d->pixel_samples > 1 ? d->pixel_samples : 1;
    /* one kernel sample a pixel: splat.frag's variant without the loop (the same values) */
    const char *count = ispm_work_splat_begin(s);
    char defines[96];
    snprintf(defines, sizeof defines, "%s%s", samples == 1 ? "#define SPLAT_ONE_SAMPLE 1\n" : "", count ? count : "");
    GLuint prog = gk_program_get(s->ctx.programs, "ispm/splat.vert", "ispm/splat.frag", defines, e);
    const splat_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(splat_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(prog);
    gk_gbuffer_view gv = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gv, &u->gb, 0, 0);
    glUniformMatrix4fv(u->u_viewproj, 1, GL_FALSE, f->view_proj.m);
    glUniform3f(u->u_cam, f->eye.x, f->eye.y, f->eye.z);
    glUniform1f(u->u_pixel_angle, 2.0f * proj_tan_half_y(f->proj) / (float)s->splat_h);
    glUniform1f(u->u_h_pixels, d->h_pixels);
    glUniform1f(u->u_to_full, (float)f->width / (float)s->splat_w);
    /* "Same surface" (research A.1.12): within half a radius of the disk's plane, normals within 37°. */
    glUniform1f(u->u_plane_tol, 0.5f);
    glUniform1f(u->u_normal_cos, ISPM_SAME_SURFACE_COS);
    glUniform1f(u->u_kernel_norm, d->faithful_kernel ? 1.0f / 3.14159265f : 1.0f / kernel_mass(d));
    glUniform1f(u->u_delta, d->delta);
    glUniform1i(u->u_cone, d->cone_kernel);
    glUniform1i(u->u_footprint, feet);
    glUniform1i(u->u_samples, samples);
    if (!s->splat_vao)
        glGenVertexArrays(1, &s->splat_vao);
    glBindVertexArray(s->splat_vao);
    glBindBuffer(GL_ARRAY_BUFFER, s->hit_buf);
    for (GLuint a = 0; a < 3; a++) {
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(a, 4, GL_FLOAT, GL_FALSE, ISPM_HIT_BYTES, (const void *)(uintptr_t)(a * 16));
        glVertexAttribDivisor(a, 1);
    }
    /* ispm_radius=footprint: the ellipse's two (axis, semi-axis) from ispm_footprint.c */
    if (feet) {
        glBindBuffer(GL_ARRAY_BUFFER, s->foot_buf);
        for (GLuint a = 3; a < 5; a++) {
            glEnableVertexAttribArray(a);
            glVertexAttribPointer(a, 4, GL_FLOAT, GL_FALSE, ISPM_FOOT_BYTES, (const void *)(uintptr_t)((a - 3) * 16));
            glVertexAttribDivisor(a, 1);
        }
    } else {
        glDisableVertexAttribArray(3);
        glDisableVertexAttribArray(4);
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, s->capacity);
    ispm_work_splat_end(s);
    glDisable(GL_BLEND);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return 0;
}

int ispm_upsample(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint prog = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "ispm/upsample.frag",
                                 ispm_work_upsample_begin(s), e);
    const up_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(up_fields), sizeof *u, e) : NULL;
    if (!u) {
        ispm_work_upsample_end(s);
        return -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr_fbo);
    glViewport(0, 0, f->width, f->height);
    glUseProgram(prog);
    gk_gbuffer_view gv = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gv, &u->gb, 0, 0);
    /* the splats on the first unit after the G-buffer's (GK_GBUFFER_UNITS: it grew a specular target) */
    glActiveTexture(GL_TEXTURE0 + GK_GBUFFER_UNITS);
    glBindTexture(GL_TEXTURE_2D, s->splat_tex);
    glUniform1i(u->u_low, GK_GBUFFER_UNITS);
    glUniform1f(u->u_to_low, (float)s->splat_w / (float)f->width);
    glUniform1f(u->u_k, s->dbg.upsample_k);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    if (!s->empty_vao)
        glGenVertexArrays(1, &s->empty_vao);
    glBindVertexArray(s->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    ispm_work_upsample_end(s);
    return 0;
}
