/* Photons of the lgv method: emission per light, tracing against the cube-maps with LGV injection
 * and the caustic list (lgv/trace.comp), then the LGV gathering iterations (eq. 6) and the volume
 * textures the lookup filters. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/tonemap.h"
#include "lgv_internal.h"

GLuint lgv_buffer(GLuint old, long bytes, bool zero)
{
    if (old)
        glDeleteBuffers(1, &old);
    GLuint b;
    glGenBuffers(1, &b);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    glBufferData(GL_SHADER_STORAGE_BUFFER, bytes, NULL, GL_DYNAMIC_COPY);
    if (zero) {
        void *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, bytes, GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
        if (p) {
            memset(p, 0, (size_t)bytes);
            glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
        }
    }
    return b;
}

static void zero_buffer(GLuint b, long bytes)
{
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    void *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, bytes, GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
    if (p) {
        memset(p, 0, (size_t)bytes);
        glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    }
}

/* lgv/tracer.glsl (in trace.comp) */
typedef struct tracer_uniforms {
    GLint u_dist, u_nrm, u_alb, u_res, u_levels, u_n_maps, u_n_refractors, u_q, u_loops, u_itp_eps, u_secant_steps,
        u_itp_mode, u_bounds_hit, u_bmin, u_bmax;
} tracer_uniforms;
static const gk_uniform_field tracer_fields[] = {
    GK_UNIFORM(tracer_uniforms, u_dist),      GK_UNIFORM(tracer_uniforms, u_nrm),
    GK_UNIFORM(tracer_uniforms, u_alb),       GK_UNIFORM(tracer_uniforms, u_res),
    GK_UNIFORM(tracer_uniforms, u_levels),    GK_UNIFORM(tracer_uniforms, u_n_maps),
    GK_UNIFORM(tracer_uniforms, u_n_refractors), GK_UNIFORM(tracer_uniforms, u_q),
    GK_UNIFORM(tracer_uniforms, u_loops),     GK_UNIFORM(tracer_uniforms, u_itp_eps),
    GK_UNIFORM(tracer_uniforms, u_secant_steps),
    GK_UNIFORM(tracer_uniforms, u_itp_mode),  GK_UNIFORM(tracer_uniforms, u_bounds_hit),
    GK_UNIFORM(tracer_uniforms, u_bmin),
    GK_UNIFORM(tracer_uniforms, u_bmax),
};

/* lgv/trace.comp's own */
typedef struct trace_uniforms {
    GLint u_photons, u_first, u_frame, u_light_kind, u_light_pos, u_light_dir, u_light_u, u_light_v, u_cone,
        u_power, u_bounces, u_grid_min, u_cell, u_dims, u_inject_scale, u_inject_lobe, u_fixed, u_caustic_cap, u_snap,
        u_plane_hits, u_sphere_normals, u_refractor_surface, u_exit_maps, u_refractor_entry;
} trace_uniforms;
static const gk_uniform_field trace_fields[] = {
    GK_UNIFORM(trace_uniforms, u_photons),
    GK_UNIFORM(trace_uniforms, u_first),       GK_UNIFORM(trace_uniforms, u_frame),
    GK_UNIFORM(trace_uniforms, u_light_kind),  GK_UNIFORM(trace_uniforms, u_light_pos),
    GK_UNIFORM(trace_uniforms, u_light_dir),   GK_UNIFORM(trace_uniforms, u_light_u),
    GK_UNIFORM(trace_uniforms, u_light_v),     GK_UNIFORM(trace_uniforms, u_cone),
    GK_UNIFORM(trace_uniforms, u_power),       GK_UNIFORM(trace_uniforms, u_bounces),
    GK_UNIFORM(trace_uniforms, u_grid_min),    GK_UNIFORM(trace_uniforms, u_cell),
    GK_UNIFORM(trace_uniforms, u_dims),        GK_UNIFORM(trace_uniforms, u_inject_scale),
    GK_UNIFORM(trace_uniforms, u_inject_lobe),
    GK_UNIFORM(trace_uniforms, u_fixed),       GK_UNIFORM(trace_uniforms, u_caustic_cap),
    GK_UNIFORM(trace_uniforms, u_snap),        GK_UNIFORM(trace_uniforms, u_sphere_normals),
    GK_UNIFORM(trace_uniforms, u_plane_hits),
    GK_UNIFORM(trace_uniforms, u_refractor_surface),
    GK_UNIFORM(trace_uniforms, u_exit_maps),   GK_UNIFORM(trace_uniforms, u_refractor_entry),
};

void lgv_trace_defines(lgv_state *s, bool probe, char *out, size_t cap)
{
    snprintf(out, cap, "%s#define LGV_GLASS %d\n%s%s", lgv_work_begin(s, LGV_WORK_TRACE),
             s->n_refractors < 2 ? s->n_refractors : 2, s->dbg.seeing_maps ? "#define LGV_SEEING_MAPS 1\n" : "",
             probe ? "#define LGV_PROBE 1\n" : "");
}

int lgv_bind_tracer(lgv_state *s, GLuint prog, gk_err *e)
{
    const tracer_uniforms *u = gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(tracer_fields), sizeof *u, e);
    if (!u)
        return -1;
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, s->dist_tex);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D_ARRAY, s->nrm_tex);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D_ARRAY, s->alb_tex);
    glUniform1i(u->u_dist, 0);
    glUniform1i(u->u_nrm, 1);
    glUniform1i(u->u_alb, 2);
    glUniform1i(u->u_res, s->maps_res);
    glUniform1i(u->u_levels, s->levels);
    glUniform1i(u->u_n_maps, s->n_maps);
    glUniform1i(u->u_n_refractors, s->n_refractors);
    glUniform1i(u->u_q, LGV_Q);
    glUniform1i(u->u_loops, LGV_LOOPS);
    glUniform1f(u->u_itp_eps, LGV_ITP_EPS_REL * s->diag);
    glUniform1i(u->u_secant_steps, LGV_SECANT_STEPS);
    glUniform1i(u->u_itp_mode, s->dbg.itp_mode);
    glUniform1i(u->u_bounds_hit, s->dbg.bounds_hits ? 1 : 0);
    glUniform3f(u->u_bmin, s->bmin.x, s->bmin.y, s->bmin.z);
    glUniform3f(u->u_bmax, s->bmax.x, s->bmax.y, s->bmax.z);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s->centres_ssbo);
    return 0;
}

/* The LGV grid: cubic cells, lgv_size cells along the scene's longest axis (research B.3: the
 * seed's grids have cubic cells, Table 1's axes differ with the scene's extents). */
static int ensure_grid(lgv_state *s, gk_err *e)
{
    vec3 ext = v3_sub(s->bmax, s->bmin);
    float longest = fmaxf(ext.x, fmaxf(ext.y, ext.z));
    float cell = longest / (float)s->lgv_size;
    int d[3];
    for (int a = 0; a < 3; a++) {
        float x = a == 0 ? ext.x : (a == 1 ? ext.y : ext.z);
        d[a] = (int)ceilf(x / cell - 1e-4f);
        d[a] = d[a] < 1 ? 1 : d[a];
    }
    s->cell = cell;
    s->grid_min = s->bmin;
    if (s->lgv_ssbo && !memcmp(d, s->dims, sizeof d))
        return 0;
    memcpy(s->dims, d, sizeof d);
    s->lgv_cells = (long)d[0] * d[1] * d[2];
    long bytes = s->lgv_cells * 12 * 4;
    s->lgv_ssbo = lgv_buffer(s->lgv_ssbo, bytes, true);
    s->src_ssbo = lgv_buffer(s->src_ssbo, bytes, false);
    s->acc_ssbo = lgv_buffer(s->acc_ssbo, bytes, false);
    s->dst_ssbo = lgv_buffer(s->dst_ssbo, bytes, false);
    glDeleteTextures(3, s->vol);
    glGenTextures(3, s->vol);
    for (int i = 0; i < 3; i++) {
        glBindTexture(GL_TEXTURE_3D, s->vol[i]);
        glTexStorage3D(GL_TEXTURE_3D, 1, GL_RGBA16F, d[0], d[1], d[2]);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    }
    if (glGetError() != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "lgv: cannot allocate a %dx%dx%d LGV", d[0], d[1], d[2]);
    return 0;
}

static float light_flux(const gk_light *l, int *kind)
{
    float lum = gk_luminance(l->color[0], l->color[1], l->color[2]) * l->intensity;
    if (l->shape == GK_SHAPE_RECT) {
        *kind = 2;
        return (float)M_PI * lum;     /* a one-sided Lambertian emitter of axial intensity I: pi I */
    }
    if (l->type == GK_LIGHT_SPOT) {
        *kind = 1;
        return 2.0f * (float)M_PI * (1.0f - cosf(l->outer_cone)) * lum;
    }
    *kind = 0;
    return 4.0f * (float)M_PI * lum;
}

int lgv_trace_photons(lgv_state *s, const gk_gi_frame *f, gk_err *e)
{
    if (ensure_grid(s, e) != 0)
        return -1;
    int cap = s->photons;
    if (!s->caustic_ssbo || s->caustic_cap != cap) {
        s->caustic_cap = cap;
        s->caustic_ssbo = lgv_buffer(s->caustic_ssbo, LGV_CAUSTIC_HEADER + (long)cap * LGV_CAUSTIC_BYTES, true);
    }
    if (!s->stats_ssbo)
        s->stats_ssbo = lgv_buffer(0, LGV_ST_N * 4, true);
    zero_buffer(s->lgv_ssbo, s->lgv_cells * 48);
    zero_buffer(s->stats_ssbo, LGV_ST_N * 4);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->caustic_ssbo);
    const GLuint header[4] = {0, 0, 0, 0};
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof header, header);
    /* lights that emit photons: point, spot and rectangle lights (directional lights and suns are
       left to the direct pass: the glass and caustic scenes use lamps) */
    const gk_scene *sc = f->scene;
    float total = 0, flux[64];
    int kind[64], n = f->n_lights < 64 ? f->n_lights : 64;
    for (int i = 0; i < n; i++) {
        const gk_light *l = &sc->lights[f->lights[i].scene_light];
        flux[i] = l->type == GK_LIGHT_DIRECTIONAL ? 0.0f : light_flux(l, &kind[i]);
        total += flux[i];
    }
    if (total <= 0.0f)
        return 0;
    /* fixed point: 2^29 units for the whole scene's flux (a cell can hold several times all of it) */
    s->fixed_scale = 536870912.0f / total;
    char defines[256];
    lgv_trace_defines(s, false, defines, sizeof defines);
    GLuint prog = gk_program_get_compute(s->ctx.programs, "lgv/trace.comp", defines, e);
    const trace_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(trace_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(prog);
    if (lgv_bind_tracer(s, prog, e) != 0)
        return -1;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s->lgv_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s->caustic_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s->stats_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, s->probe_ssbo ? s->probe_ssbo : s->stats_ssbo);
    glUniform1ui(u->u_frame, s->frame_index + s->dbg.seed);
    glUniform1i(u->u_bounces, s->dbg.max_events > 0 ? s->dbg.max_events : LGV_BOUNCES);
    glUniform3f(u->u_grid_min, s->grid_min.x, s->grid_min.y, s->grid_min.z);
    glUniform1f(u->u_cell, s->cell);
    glUniform3i(u->u_dims, s->dims[0], s->dims[1], s->dims[2]);
    glUniform1f(u->u_inject_scale, s->dbg.inject_lobe ? LGV_INJECT_SCALE_LOBE : LGV_INJECT_SCALE);
    glUniform1i(u->u_inject_lobe, s->dbg.inject_lobe ? 1 : 0);
    glUniform1f(u->u_fixed, s->fixed_scale);
    glUniform1i(u->u_caustic_cap, cap);
    glUniform1i(u->u_snap, s->dbg.snap_hits ? 1 : 0);
    glUniform1i(u->u_plane_hits, s->dbg.plane_hits ? 1 : 0);
    glUniform1i(u->u_sphere_normals, s->dbg.sphere_normals ? 1 : 0);
    glUniform1i(u->u_refractor_surface, s->dbg.refractor_surface ? 1 : 0);
    glUniform1i(u->u_exit_maps, s->dbg.exit_maps ? 1 : 0);
    glUniform1i(u->u_refractor_entry, s->dbg.refractor_entry ? 1 : 0);
    unsigned first = 0;
    int left = s->photons;
    for (int i = 0; i < n; i++) {
        if (flux[i] <= 0.0f)
            continue;
        int count = (int)lroundf((float)s->photons * flux[i] / total);
        count = count > left ? left : count;
        if (count <= 0)
            continue;
        left -= count;
        const gk_light *l = &sc->lights[f->lights[i].scene_light];
        const gk_gi_light *gl = &f->lights[i];
        int k;
        float lum_flux = light_flux(l, &k);
        float scale = lum_flux / (gk_luminance(l->color[0], l->color[1], l->color[2]) > 0
                                      ? gk_luminance(l->color[0], l->color[1], l->color[2]) : 1.0f) / (float)count;
        glUniform1i(u->u_photons, count);
        glUniform1ui(u->u_first, first);
        glUniform1i(u->u_light_kind, kind[i]);
        glUniform3f(u->u_light_pos, gl->position.x, gl->position.y, gl->position.z);
        glUniform3f(u->u_light_dir, gl->direction.x, gl->direction.y, gl->direction.z);
        vec3 hu = v3_scale(gl->axis_u, 0.5f * l->size[0]), hv = v3_scale(gl->axis_v, 0.5f * l->size[1]);
        glUniform3f(u->u_light_u, hu.x, hu.y, hu.z);
        glUniform3f(u->u_light_v, hv.x, hv.y, hv.z);
        glUniform2f(u->u_cone, cosf(l->outer_cone), cosf(l->inner_cone));
        /* photon power: colour x (flux per unit colour) / photons */
        glUniform3f(u->u_power, l->color[0] * scale, l->color[1] * scale, l->color[2] * scale);
        glDispatchCompute((GLuint)(count + 63) / 64, 1, 1);
        first += (unsigned)count;
    }
    lgv_work_end(s, LGV_WORK_TRACE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return 0;
}

/* lgv/lgv_resolve.comp, lgv_gather.comp, lgv_volume.comp */
typedef struct resolve_uniforms {
    GLint u_values, u_fixed;
} resolve_uniforms;
static const gk_uniform_field resolve_fields[] = {GK_UNIFORM(resolve_uniforms, u_values),
                                                  GK_UNIFORM(resolve_uniforms, u_fixed)};
typedef struct dims_uniforms {
    GLint u_dims;
} dims_uniforms;
static const gk_uniform_field dims_fields[] = {GK_UNIFORM(dims_uniforms, u_dims)};
typedef struct gather_uniforms {
    GLint u_dims, u_occlusion, u_geo_fixed;
} gather_uniforms;
static const gk_uniform_field gather_fields[] = {GK_UNIFORM(gather_uniforms, u_dims),
                                                 GK_UNIFORM(gather_uniforms, u_occlusion),
                                                 GK_UNIFORM(gather_uniforms, u_geo_fixed)};

int lgv_gather(lgv_state *s, const gk_gi_frame *f, gk_err *e)
{
    (void)f;
    gk_program_cache *pc = s->ctx.programs;
    GLuint res = gk_program_get_compute(pc, "lgv/lgv_resolve.comp", NULL, e);
    const resolve_uniforms *ru = res ? gk_program_uniforms(pc, res, GK_FIELDS(resolve_fields), sizeof *ru, e) : NULL;
    GLuint gat = ru ? gk_program_get_compute(pc, "lgv/lgv_gather.comp", NULL, e) : 0;
    const gather_uniforms *gu = gat ? gk_program_uniforms(pc, gat, GK_FIELDS(gather_fields), sizeof *gu, e) : NULL;
    GLuint vol = gu ? gk_program_get_compute(pc, "lgv/lgv_volume.comp", NULL, e) : 0;
    const dims_uniforms *vu = vol ? gk_program_uniforms(pc, vol, GK_FIELDS(dims_fields), sizeof *vu, e) : NULL;
    if (!vu)
        return -1;
    bool occlusion = s->iters > 0 && s->dbg.occlusion;
    if (occlusion && lgv_build_geometry(s, e) != 0)
        return -1;
    int values = (int)(s->lgv_cells * 12);
    glUseProgram(res);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s->lgv_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, s->src_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, s->acc_ssbo);
    glUniform1i(ru->u_values, values);
    glUniform1f(ru->u_fixed, s->fixed_scale);
    glDispatchCompute((GLuint)(values + 63) / 64, 1, 1);
    glUseProgram(gat);
    glUniform3i(gu->u_dims, s->dims[0], s->dims[1], s->dims[2]);
    glUniform1i(gu->u_occlusion, occlusion ? 1 : 0);
    glUniform1f(gu->u_geo_fixed, LGV_GEO_FIXED);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, occlusion ? s->geo_ssbo : s->src_ssbo);
    GLuint a = s->src_ssbo, b = s->dst_ssbo;
    for (int it = 0; it < s->iters; it++) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, a);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, b);
        glDispatchCompute((GLuint)(s->lgv_cells + 63) / 64, 1, 1);
        GLuint t = a;
        a = b, b = t;
    }
    /* the volume: the sum of the iterations (LPV practice, the default), or the last one alone */
    s->out_ssbo = s->dbg.gather_replace ? a : s->acc_ssbo;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(vol);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, s->out_ssbo);
    glUniform3i(vu->u_dims, s->dims[0], s->dims[1], s->dims[2]);
    for (int i = 0; i < 3; i++)
        glBindImageTexture((GLuint)i, s->vol[i], 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute((GLuint)(s->dims[0] + 3) / 4, (GLuint)(s->dims[1] + 3) / 4, (GLuint)(s->dims[2] + 3) / 4);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    return 0;
}
