/* The GL side of each vct pass: program variants, bindings, dispatches and barriers. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vct_internal.h"

static void defines_common(const gk_vct *v, char *out, size_t n)
{
    snprintf(out, n, "#define CONSERVATIVE %d\n#define AVERAGE_CAS %d\n#define EMISSIVE %d\n",
             v->opt.conservative ? 1 : 0, v->opt.average_cas ? 1 : 0, v->emissive ? 1 : 0);
}

static int groups(int n, int g) { return (n + g - 1) / g; }

/* Uniform locations, one struct per shader (all its variants), resolved once per program. */

/* vct/clear.comp */
typedef struct clear_uniforms {
    GLint u_res, u_region_lo, u_region_size, u_channels;
} clear_uniforms;
static const gk_uniform_field clear_fields[] = {
    GK_UNIFORM(clear_uniforms, u_res), GK_UNIFORM(clear_uniforms, u_region_lo),
    GK_UNIFORM(clear_uniforms, u_region_size), GK_UNIFORM(clear_uniforms, u_channels)};

/* vct/voxelize.comp */
typedef struct voxelize_uniforms {
    GLint u_res, u_grid_origin, u_voxel_size, u_region_lo, u_region_hi, u_emission_scale, u_tri_first, u_tri_count,
        u_alpha_tex, u_thick;
} voxelize_uniforms;
static const gk_uniform_field voxelize_fields[] = {
    GK_UNIFORM(voxelize_uniforms, u_res),          GK_UNIFORM(voxelize_uniforms, u_grid_origin),
    GK_UNIFORM(voxelize_uniforms, u_voxel_size),   GK_UNIFORM(voxelize_uniforms, u_region_lo),
    GK_UNIFORM(voxelize_uniforms, u_region_hi),    GK_UNIFORM(voxelize_uniforms, u_emission_scale),
    GK_UNIFORM(voxelize_uniforms, u_tri_first),    GK_UNIFORM(voxelize_uniforms, u_tri_count),
    GK_UNIFORM(voxelize_uniforms, u_alpha_tex),    GK_UNIFORM(voxelize_uniforms, u_thick)};

/* vct/inject.comp (arrays: the location of element 0, set with glUniform*v) */
typedef struct inject_uniforms {
    GLint u_res, u_region_lo, u_region_size, u_grid_origin, u_voxel_size, u_emission_max, u_shadow_ambient,
        u_shadow_bias, u_n_lights;
    GLint u_shadow[VCT_MAX_LIGHTS];
    GLint u_light_type, u_light_pos, u_light_dir, u_light_radiant, u_light_spot, u_light_lambert, u_light_shadow,
        u_shadow_vp, u_shadow_range;
} inject_uniforms;
static const gk_uniform_field inject_fields[] = {
    GK_UNIFORM(inject_uniforms, u_res),
    GK_UNIFORM(inject_uniforms, u_region_lo),
    GK_UNIFORM(inject_uniforms, u_region_size),
    GK_UNIFORM(inject_uniforms, u_grid_origin),
    GK_UNIFORM(inject_uniforms, u_voxel_size),
    GK_UNIFORM(inject_uniforms, u_emission_max),
    GK_UNIFORM(inject_uniforms, u_shadow_ambient),
    GK_UNIFORM(inject_uniforms, u_shadow_bias),
    GK_UNIFORM(inject_uniforms, u_n_lights),
    GK_UNIFORM_AS(inject_uniforms, u_shadow[0], "u_shadow0"),
    GK_UNIFORM_AS(inject_uniforms, u_shadow[1], "u_shadow1"),
    GK_UNIFORM_AS(inject_uniforms, u_shadow[2], "u_shadow2"),
    GK_UNIFORM_AS(inject_uniforms, u_shadow[3], "u_shadow3"),
    GK_UNIFORM(inject_uniforms, u_light_type),
    GK_UNIFORM(inject_uniforms, u_light_pos),
    GK_UNIFORM(inject_uniforms, u_light_dir),
    GK_UNIFORM(inject_uniforms, u_light_radiant),
    GK_UNIFORM(inject_uniforms, u_light_spot),
    GK_UNIFORM(inject_uniforms, u_light_lambert),
    GK_UNIFORM(inject_uniforms, u_light_shadow),
    GK_UNIFORM(inject_uniforms, u_shadow_vp),
    GK_UNIFORM(inject_uniforms, u_shadow_range),
};
_Static_assert(VCT_MAX_LIGHTS == 4, "inject_fields lists u_shadow0..3 (shaders_gles/vct/inject.comp)");

/* vct/axis_dist.comp */
typedef struct axis_dist_uniforms {
    GLint u_res;
} axis_dist_uniforms;
static const gk_uniform_field axis_dist_fields[] = {GK_UNIFORM(axis_dist_uniforms, u_res)};

/* vct/thin_flag.comp */
typedef struct thin_flag_uniforms {
    GLint u_res;
} thin_flag_uniforms;
static const gk_uniform_field thin_flag_fields[] = {GK_UNIFORM(thin_flag_uniforms, u_res)};

/* vct/mip_aniso.comp */
typedef struct mip_uniforms {
    GLint u_half;
    GLint u_res, u_dst_res, u_from_level0, u_dir, u_views_only;
} mip_uniforms;
static const gk_uniform_field mip_fields[] = {GK_UNIFORM(mip_uniforms, u_res), GK_UNIFORM(mip_uniforms, u_dst_res),
                                              GK_UNIFORM(mip_uniforms, u_from_level0), GK_UNIFORM(mip_uniforms, u_dir),
                                              GK_UNIFORM(mip_uniforms, u_half), GK_UNIFORM(mip_uniforms, u_views_only)};

/* vct/trace.comp */
typedef struct trace_uniforms {
    gk_gbuffer_uniforms g;
    GLint u_gb_geom_normal;
    GLint u_vox0, u_voxp[3], u_voxp_l0[3], u_dir_levels;
    GLint u_low_size, u_block, u_res, u_res_f, u_grid_origin, u_grid_size, u_step_mul, u_ao_lambda, u_max_dist,
        u_apex_offset, u_footprint_clamp, u_spec_aperture, u_n_cones, u_cone_dir, u_cone_aperture, u_cone_weight,
        u_skip_top;
} trace_uniforms;
static const gk_uniform_field trace_fields[] = {
    GK_GBUFFER_FIELDS(trace_uniforms, g),
    GK_UNIFORM(trace_uniforms, u_gb_geom_normal),
    VCT_CONE_FIELDS(trace_uniforms),
    GK_UNIFORM(trace_uniforms, u_low_size),
    GK_UNIFORM(trace_uniforms, u_block),
    GK_UNIFORM(trace_uniforms, u_grid_origin),
    GK_UNIFORM(trace_uniforms, u_grid_size),
    GK_UNIFORM(trace_uniforms, u_spec_aperture),
    GK_UNIFORM(trace_uniforms, u_n_cones),
    GK_UNIFORM(trace_uniforms, u_cone_dir),
    GK_UNIFORM(trace_uniforms, u_cone_aperture),
    GK_UNIFORM(trace_uniforms, u_cone_weight),
    GK_UNIFORM(trace_uniforms, u_skip_top),
};

/* vct/bounce.comp */
typedef struct bounce_uniforms {
    GLint u_vox0, u_voxp[3], u_voxp_l0[3], u_dir_levels;
    GLint u_res, u_res_f, u_step_mul, u_ao_lambda, u_max_dist, u_apex_offset, u_footprint_clamp, u_n_cones, u_cone_dir,
        u_cone_aperture, u_cone_weight;
} bounce_uniforms;
static const gk_uniform_field bounce_fields[] = {
    VCT_CONE_FIELDS(bounce_uniforms),
    GK_UNIFORM(bounce_uniforms, u_n_cones),
    GK_UNIFORM(bounce_uniforms, u_cone_dir),
    GK_UNIFORM(bounce_uniforms, u_cone_aperture),
    GK_UNIFORM(bounce_uniforms, u_cone_weight),
};

/* vct/compose.{vert,frag} */
typedef struct compose_uniforms {
    gk_gbuffer_uniforms g;
    GLint u_diffuse_lo, u_spec_lo, u_low_size, u_block, u_voxel_world, u_spec_enabled;
} compose_uniforms;
static const gk_uniform_field compose_fields[] = {
    GK_GBUFFER_FIELDS(compose_uniforms, g),
    GK_UNIFORM(compose_uniforms, u_diffuse_lo),
    GK_UNIFORM(compose_uniforms, u_spec_lo),
    GK_UNIFORM(compose_uniforms, u_low_size),
    GK_UNIFORM(compose_uniforms, u_block),
    GK_UNIFORM(compose_uniforms, u_voxel_world),
    GK_UNIFORM(compose_uniforms, u_spec_enabled),
};

/* The voxelizer's uniforms shared by its two programs (the fragments', vct_thick's solid pass). */
static void voxelize_set_uniforms(const gk_vct *v, const voxelize_uniforms *uv, const int lo[3], const int hi[3])
{
    glUniform1i(uv->u_res, v->res);
    glUniform3f(uv->u_grid_origin, v->origin[0], v->origin[1], v->origin[2]);
    glUniform1f(uv->u_voxel_size, v->voxel);
    glUniform3i(uv->u_region_lo, lo[0], lo[1], lo[2]);
    glUniform3i(uv->u_region_hi, hi[0], hi[1], hi[2]);
    glUniform1f(uv->u_emission_scale, v->tris.max_emission > 0 ? 1.0f / v->tris.max_emission : 0.0f);
    glUniform1f(uv->u_thick, v->cur.thick);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, v->alpha_tex);
    glUniform1i(uv->u_alpha_tex, 0);
}

/* One thread per triangle, at most 65535 groups of 64 per dispatch. */
static void voxelize_dispatch(const gk_vct *v, const voxelize_uniforms *uv)
{
    for (int first = 0; first < v->tris.n; first += 65535 * 64) {
        int count = v->tris.n - first < 65535 * 64 ? v->tris.n - first : 65535 * 64;
        glUniform1i(uv->u_tri_first, first);
        glUniform1i(uv->u_tri_count, count);
        glDispatchCompute((GLuint)groups(count, 64), 1, 1);
    }
}

/* vct_thick (voxelize.comp SOLID_PASS): the voxels behind every fragment marked solid, in a dispatch
   of its own after the fragments' (the mark is a bit of the fixed-point count channel: none with the
   thesis's CAS averages). Its own program, not a call in the fragments' loop: with the marks written
   there, light-leak at vct_res=128 and 3 voxels leaked 0.98% instead of 0.096% (the dark room saw
   the wall's lit column near the side walls), and as much with atomicOr(.., 0u) in place of the
   mark, so the loop's code on llvmpipe, not the marks, lost voxels; apart, the same marks give
   0.065%. The bench's count of the voxelizer's atomics (vct_work.c) leaves this dispatch out. */
static int voxelize_solid_pass(gk_vct *v, const char *defs, const int lo[3], const int hi[3], gk_err *e)
{
    if (!(v->cur.thick > 0.0f) || v->opt.average_cas)
        return 0;
    char solid_defs[320];
    snprintf(solid_defs, sizeof solid_defs, "%s#define SOLID_PASS 1\n", defs);
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/voxelize.comp", solid_defs, e);
    const voxelize_uniforms *uv = p ? gk_program_uniforms(v->ctx.programs, p, GK_FIELDS(voxelize_fields), sizeof *uv, e) : NULL;
    if (!uv)
        return -1;
    glUseProgram(p);
    voxelize_set_uniforms(v, uv, lo, hi);
    voxelize_dispatch(v, uv);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return 0;
}

/* vct/clear.comp over a region of the buffer bound at binding 1: `channels` uints per voxel zeroed. */
static void clear_region(const gk_vct *v, GLuint clear, const clear_uniforms *uc, const int lo[3], const int size[3],
                         int channels)
{
    glUseProgram(clear);
    glUniform1i(uc->u_res, v->res);
    glUniform3i(uc->u_region_lo, lo[0], lo[1], lo[2]);
    glUniform3i(uc->u_region_size, size[0], size[1], size[2]);
    glUniform1i(uc->u_channels, channels);
    glDispatchCompute((GLuint)groups(size[0], 4), (GLuint)groups(size[1], 4), (GLuint)groups(size[2], 4));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* vct_axis_clamp=thin: the flag volume made anew over the whole grid (a dirty region's surfaces may make
   or unmake a thin wall with the static ones beside it): cleared, each fragment's facing ORed in by
   voxelize.comp FACE_PASS (a dispatch of its own, as the solid marks', see below), then
   vct/thin_flag.comp's THIN_BIT per voxel, then THIN_MARK on the voxels up to VCT_THIN_DEPTH behind
   the fragments of flagged voxels (voxelize.comp THIN_MARKS: where the axis clamp stops too; unlike
   vct_thick's marks not opaque, so a thin shell's other face stays visible). The voxel data (scratch,
   radiance) are not touched: a scene without thin walls is traced as without the clamp, and keeps
   no flag volume (it lives during the voxelization alone, 4 bytes per voxel). */
static int thin_flag_pass(gk_vct *v, const char *defs, GLuint clear, const clear_uniforms *uc, gk_err *e)
{
    char face_defs[320], mark_defs[320];
    snprintf(face_defs, sizeof face_defs, "%s#define FACE_PASS 1\n", defs);
    snprintf(mark_defs, sizeof mark_defs, "%s#define SOLID_PASS 1\n#define THIN_MARKS 1\n", defs);
    GLuint face = gk_program_get_compute(v->ctx.programs, "vct/voxelize.comp", face_defs, e);
    GLuint flag = face ? gk_program_get_compute(v->ctx.programs, "vct/thin_flag.comp", defs, e) : 0;
    GLuint mark = flag ? gk_program_get_compute(v->ctx.programs, "vct/voxelize.comp", mark_defs, e) : 0;
    const voxelize_uniforms *uv = mark ? gk_program_uniforms(v->ctx.programs, face, GK_FIELDS(voxelize_fields), sizeof *uv, e) : NULL;
    const thin_flag_uniforms *uf = uv ? gk_program_uniforms(v->ctx.programs, flag, GK_FIELDS(thin_flag_fields), sizeof *uf, e) : NULL;
    const voxelize_uniforms *um = uf ? gk_program_uniforms(v->ctx.programs, mark, GK_FIELDS(voxelize_fields), sizeof *um, e) : NULL;
    if (!um)
        return -1;
    if (!v->thin_ssbo) {   /* allocated once per grid (vct_free_gpu), cleared on the GPU each time */
        glGenBuffers(1, &v->thin_ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->thin_ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)gk_vct_thin_flag_memory(v->res), NULL, GL_DYNAMIC_COPY);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        GLenum err = glGetError();
        if (err != GL_NO_ERROR)
            return gk_fail(e, GK_ERUNTIME, "vct: allocating the %d^3 thin-wall flags failed (GL error 0x%x)", v->res, err);
    }
    int all_lo[3] = {0, 0, 0}, all_hi[3] = {v->res - 1, v->res - 1, v->res - 1};
    int all_size[3] = {v->res, v->res, v->res};
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->thin_ssbo);
    clear_region(v, clear, uc, all_lo, all_size, 1);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, v->thin_ssbo);
    glUseProgram(face);
    voxelize_set_uniforms(v, uv, all_lo, all_hi);
    voxelize_dispatch(v, uv);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    GLuint zero_count = 0;
    if (!v->thin_count_ssbo)
        glGenBuffers(1, &v->thin_count_ssbo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->thin_count_ssbo);
    glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof zero_count, &zero_count, GL_DYNAMIC_READ);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, v->thin_count_ssbo);
    glUseProgram(flag);
    glUniform1i(uf->u_res, v->res);
    glDispatchCompute((GLuint)groups(v->res, 4), (GLuint)groups(v->res, 4), (GLuint)groups(v->res, 4));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    /* a read back once per voxelization (a static scene's: once), so that a scene without thin walls
       traces without the clamp's per-sample work */
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->thin_count_ssbo);
    const GLuint *count = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, sizeof *count, GL_MAP_READ_BIT);
    v->thin_voxels = count ? (long)*count : 1;
    if (count)
        glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    if (v->thin_voxels == 0) {   /* nothing to clamp at: the volume is not kept (made anew each time) */
        glDeleteBuffers(1, &v->thin_ssbo);
        v->thin_ssbo = 0;
        return 0;
    }
    glUseProgram(mark);
    voxelize_set_uniforms(v, um, all_lo, all_hi);
    glUniform1f(um->u_thick, VCT_THIN_DEPTH);
    voxelize_dispatch(v, um);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return 0;
}

int vct_pass_voxelize(gk_vct *v, const int lo[3], const int hi[3], gk_err *e)
{
    char defs[256], vox_defs[320];
    defines_common(v, defs, sizeof defs);
    snprintf(vox_defs, sizeof vox_defs, "%s%s", defs, vct_work_voxelize_begin(v));
    GLuint clear = gk_program_get_compute(v->ctx.programs, "vct/clear.comp", defs, e);
    GLuint vox = clear ? gk_program_get_compute(v->ctx.programs, "vct/voxelize.comp", vox_defs, e) : 0;
    const clear_uniforms *uc = vox ? gk_program_uniforms(v->ctx.programs, clear, GK_FIELDS(clear_fields), sizeof *uc, e) : NULL;
    const voxelize_uniforms *uv = uc ? gk_program_uniforms(v->ctx.programs, vox, GK_FIELDS(voxelize_fields), sizeof *uv, e) : NULL;
    if (!uv)
        return -1;
    int size[3] = {hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1};
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, v->tri_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);

    clear_region(v, clear, uc, lo, size, gk_vct_channels(v->emissive));

    glUseProgram(vox);
    voxelize_set_uniforms(v, uv, lo, hi);
    voxelize_dispatch(v, uv);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    vct_work_voxelize_end(v);
    if (v->cur.axis_clamp == VCT_AXIS_THIN && thin_flag_pass(v, defs, clear, uc, e) != 0)
        return -1;
    if (voxelize_solid_pass(v, defs, lo, hi, e) != 0)
        return -1;
    v->voxelize_ran = true;
    v->stats.voxelize_runs++;
    v->stats.last_voxelized_region = (long)size[0] * size[1] * size[2];
    return 0;
}

int vct_axis_clamp_in_use(const gk_vct *v, int level)
{
    if (level == VCT_AXIS_THIN)
        return v->thin_voxels > 0 ? 1 : 0;
    return level;
}

int vct_pass_axis_dist(gk_vct *v, int nth, gk_err *e)
{
    char defs[256];
    defines_common(v, defs, sizeof defs);
    size_t used = strlen(defs);
    bool thin = nth == VCT_AXIS_THIN;   /* first, counting only thin walls' voxels */
    snprintf(defs + used, sizeof defs - used, "#define NTH %d\n#define THIN_ONLY %d\n", thin ? 1 : nth, thin ? 1 : 0);
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/axis_dist.comp", defs, e);
    const axis_dist_uniforms *u = p ? gk_program_uniforms(v->ctx.programs, p, GK_FIELDS(axis_dist_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    if (!v->axis_ssbo) {
        glGenBuffers(1, &v->axis_ssbo);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->axis_ssbo);
        glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)gk_vct_axis_clamp_memory(v->res), NULL, GL_DYNAMIC_COPY);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        GLenum err = glGetError();
        if (err != GL_NO_ERROR)
            return gk_fail(e, GK_ERUNTIME, "vct: allocating the axis clamp's %d^3 distances failed (GL error 0x%x)",
                           v->res, err);
    }
    glUseProgram(p);
    glUniform1i(u->u_res, v->res);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, v->axis_ssbo);
    if (thin)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, v->thin_ssbo);
    glDispatchCompute((GLuint)groups(v->res, 8), (GLuint)groups(v->res, 8), 3);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    v->axis_valid = true;
    v->axis_nth = nth;
    return 0;
}

int vct_pass_inject(gk_vct *v, const gk_gi_frame *f, gk_err *e)
{
    char defs[320];
    defines_common(v, defs, sizeof defs);
    size_t len = strlen(defs);
    snprintf(defs + len, sizeof defs - len, "%s", vct_work_inject_begin(v, f->count_work));
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/inject.comp", defs, e);
    const inject_uniforms *u = p ? gk_program_uniforms(v->ctx.programs, p, GK_FIELDS(inject_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(p);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);
    glBindImageTexture(0, v->vox0, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glUniform1i(u->u_res, v->res);
    glUniform3i(u->u_region_lo, 0, 0, 0);
    glUniform3i(u->u_region_size, v->res, v->res, v->res);
    glUniform3f(u->u_grid_origin, v->origin[0], v->origin[1], v->origin[2]);
    glUniform1f(u->u_voxel_size, v->voxel);
    glUniform1f(u->u_emission_max, v->tris.max_emission);
    glUniform1f(u->u_shadow_ambient, v->opt.shadow_ambient);
    /* The shadow test compares distances along the map's axis (inject.comp), so the bias is in world
       units: a quarter voxel, on top of the lookup's one voxel along the normal. It was 0.0015 of
       window depth, which in a perspective map with its near plane at 1 cm is 0.6 m of depth 2 m from
       the light (window depth changes by near / z^2 a metre at depth z): light-leak's dark floor
       behind the wall was injected lit. */
    glUniform1f(u->u_shadow_bias, 0.25f * v->voxel);
    int n = f->n_lights < VCT_MAX_LIGHTS ? f->n_lights : VCT_MAX_LIGHTS;
    glUniform1i(u->u_n_lights, n);
    GLint type_of[VCT_MAX_LIGHTS], lambert_of[VCT_MAX_LIGHTS], shadow_of[VCT_MAX_LIGHTS];
    float pos[VCT_MAX_LIGHTS][3], dir[VCT_MAX_LIGHTS][3], radiant[VCT_MAX_LIGHTS][3], spot[VCT_MAX_LIGHTS][2];
    float vp[VCT_MAX_LIGHTS][16], range[VCT_MAX_LIGHTS][3];
    for (int i = 0; i < VCT_MAX_LIGHTS; i++) {
        glUniform1i(u->u_shadow[i], 8 + i);
        glActiveTexture(GL_TEXTURE8 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, i < n ? f->lights[i].shadow_depth_tex : 0);
        glBindSampler(8 + (GLuint)i, v->nearest_sampler);
        if (i >= n)
            continue;
        const gk_gi_light *L = &f->lights[i];
        const gk_light *sl = (f->scene && L->scene_light >= 0 && L->scene_light < f->scene->n_lights)
                                 ? &f->scene->lights[L->scene_light] : NULL;
        int type = sl ? (sl->type == GK_LIGHT_DIRECTIONAL ? 2 : sl->type == GK_LIGHT_SPOT ? 1 : 0) : 0;
        float ci = sl ? cosf(sl->inner_cone) : 1.0f, co = sl ? cosf(sl->outer_cone) : 0.0f;
        float scale = 1.0f / fmaxf(0.001f, ci - co);
        int lambert = sl && (sl->shape == GK_SHAPE_RECT || sl->shape == GK_SHAPE_DISC) && type != 2;
        type_of[i] = type;
        memcpy(pos[i], (float[3]){L->position.x, L->position.y, L->position.z}, sizeof pos[i]);
        memcpy(dir[i], (float[3]){L->direction.x, L->direction.y, L->direction.z}, sizeof dir[i]);
        memcpy(radiant[i], (float[3]){L->radiant.x, L->radiant.y, L->radiant.z}, sizeof radiant[i]);
        spot[i][0] = scale, spot[i][1] = -co * scale;
        lambert_of[i] = lambert;
        shadow_of[i] = L->shadow_depth_tex != 0;
        memcpy(vp[i], L->shadow_view_proj.m, sizeof vp[i]);
        memcpy(range[i], (float[3]){L->shadow_near, L->shadow_far, L->shadow_is_perspective ? 1.0f : 0.0f},
               sizeof range[i]);
    }
    if (n > 0) {
        glUniform1iv(u->u_light_type, n, type_of);
        glUniform3fv(u->u_light_pos, n, &pos[0][0]);
        glUniform3fv(u->u_light_dir, n, &dir[0][0]);
        glUniform3fv(u->u_light_radiant, n, &radiant[0][0]);
        glUniform2fv(u->u_light_spot, n, &spot[0][0]);
        glUniform1iv(u->u_light_lambert, n, lambert_of);
        glUniform1iv(u->u_light_shadow, n, shadow_of);
        glUniformMatrix4fv(u->u_shadow_vp, n, GL_FALSE, &vp[0][0]);
        glUniform3fv(u->u_shadow_range, n, &range[0][0]);
    }
    glDispatchCompute((GLuint)groups(v->res, 4), (GLuint)groups(v->res, 4), (GLuint)groups(v->res, 4));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    vct_work_inject_end(v);
    for (int i = 0; i < VCT_MAX_LIGHTS; i++) {
        glActiveTexture(GL_TEXTURE8 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindSampler(8 + (GLuint)i, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    v->stats.inject_runs++;
    return 0;
}

int vct_pass_mips(gk_vct *v, bool directional, gk_err *e)
{
    if (!v->cur.aniso) {
        glBindTexture(GL_TEXTURE_3D, v->vox0);
        glGenerateMipmap(GL_TEXTURE_3D);
        glBindTexture(GL_TEXTURE_3D, 0);
        v->stats.mip_runs++;
        return 0;
    }
    char defs[256];
    defines_common(v, defs, sizeof defs);
    size_t used = strlen(defs);
    snprintf(defs + used, sizeof defs - used, "#define DIRECTIONAL_INJECTION %d\n#define PROJECTED_COVERAGE %d\n",
             directional ? 1 : 0, v->opt.projected_coverage ? 1 : 0);
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/mip_aniso.comp", defs, e);
    const mip_uniforms *u = p ? gk_program_uniforms(v->ctx.programs, p, GK_FIELDS(mip_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(p);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);
    glUniform1i(u->u_res, v->res);
    /* map level l is level l - first of the chains: from level 1 on (thesis §4), or with
       vct_level0=aniso from level 0, whose views are the isotropic injection seen from each side */
    int first = v->cur.aniso_level0 ? 0 : 1;
    for (int l = first; l < v->levels; l++) {
        int dst_res = v->res >> l;
        /* with vct_thick, level 1 is made from the injection also under vct_level0=aniso (what its
           views hold, each voxel as fetch() shows it), so that the solid voxels stay out of it
           (mip_aniso.comp fetch) */
        bool from_level0 = l == first || (l == 1 && v->cur.thick > 0.0f);
        glUniform1i(u->u_dst_res, dst_res);
        glUniform1i(u->u_from_level0, from_level0);
        glUniform1i(u->u_views_only, l == 0);
        for (int d = 0; d < 6; d++) {
            /* view d in axis texture d / 2, in the lower (even d) or upper half of each level's depth */
            GLuint packed = v->voxp[d / 2];
            if (from_level0)
                glBindImageTexture(0, v->vox0, 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
            else
                glBindImageTexture(0, packed, l - first - 1, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
            glBindImageTexture(1, packed, l - first, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glUniform1i(u->u_half, d % 2);
            glUniform1i(u->u_dir, d);
            glDispatchCompute((GLuint)groups(dst_res, 4), (GLuint)groups(dst_res, 4), (GLuint)groups(dst_res, 4));
        }
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    v->stats.mip_runs++;
    return 0;
}

int vct_cone_set(int n, bool faithful, float dir[][3], float aperture[], float weight[])
{
    int k = 0;
    if (n == 6) {
        /* thesis code's table (tangent space, normal = +y): centre aperture 1.0, five side cones at
           polar 52.62 deg, aperture 1.098184 */
        static const float side[5][3] = {{-0.794654f, 0.607062f, 0.0f}, {0.642889f, 0.607062f, 0.467086f},
                                         {0.642889f, 0.607062f, -0.467086f}, {-0.245562f, 0.607062f, 0.755761f},
                                         {-0.245562f, 0.607062f, -0.755761f}};
        dir[k][0] = 0, dir[k][1] = 1, dir[k][2] = 0, aperture[k++] = 1.0f;
        for (int i = 0; i < 5; i++) {
            memcpy(dir[k], side[i], sizeof side[i]);
            aperture[k++] = 1.098184f;
        }
    } else {
        /* 4: centre + 3 side cones at polar 55 deg; 9: centre + 8 side cones at polar 55 deg. Not in
           the thesis ("5-12 cones suffice"): apertures chosen so the cones roughly tile the hemisphere. */
        int sides = n == 4 ? 3 : 8;
        float polar = 55.0f * 3.14159265f / 180.0f;
        dir[k][0] = 0, dir[k][1] = 1, dir[k][2] = 0, aperture[k++] = n == 4 ? 1.2f : 1.0f;
        for (int i = 0; i < sides; i++) {
            float az = 2.0f * 3.14159265f * (float)i / (float)sides;
            dir[k][0] = sinf(polar) * cosf(az);
            dir[k][1] = cosf(polar);
            dir[k][2] = sinf(polar) * sinf(az);
            aperture[k++] = n == 4 ? 1.6f : 0.9f;
        }
    }
    float sum = 0;
    for (int i = 0; i < k; i++) {
        if (faithful) {
            weight[i] = dir[i][1]; /* thesis code: 1 for the centre, 0.607 = cos(polar) for the sides */
        } else {
            float half = atanf(0.5f * aperture[i]);
            weight[i] = dir[i][1] * 3.14159265f * sinf(half) * sinf(half); /* W_k = cos(theta) pi sin^2(alpha) */
        }
        sum += weight[i];
    }
    if (!faithful)
        for (int i = 0; i < k; i++)
            weight[i] /= sum; /* w_k = W_k / sum W: the cones' share of the cosine lobe, sums to 1 */
    return k;
}

static void bind_tex(GLint loc, int unit, GLenum target, GLuint tex, GLuint sampler)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(target, tex);
    glBindSampler((GLuint)unit, sampler);
    glUniform1i(loc, unit);
}

void vct_bind_map(const gk_vct *v, GLint vox0, const GLint voxp[3], const GLint voxp_l0[3], GLint dir_levels)
{
    bind_tex(vox0, 0, GL_TEXTURE_3D, v->vox0, 0);
    if (v->cur.aniso)
        for (int a = 0; a < 3; a++) {
            bind_tex(voxp[a], 1 + a, GL_TEXTURE_3D, v->voxp[a], 0);
            bind_tex(voxp_l0[a], 4 + a, GL_TEXTURE_3D, v->voxp[a], v->level0_sampler);
        }
    glUniform1f(dir_levels, (float)(v->levels - (v->cur.aniso_level0 ? 0 : 1)));
}

void vct_map_defines(const gk_vct *v, char *out, size_t n)
{
    snprintf(out, n, "#define ISO_MIPS %d\n#define ANISO_LEVEL0 %d\n", v->cur.aniso ? 0 : 1,
             v->cur.aniso && v->cur.aniso_level0 ? 1 : 0);
}

int vct_skip_top(const gk_vct *v)
{
    int depth = 0;
    while ((1 << (depth + 1)) <= v->res)
        depth++;
    int top = depth - 3;
    return top < 0 ? 0 : top > v->levels - 1 ? v->levels - 1 : top;
}

/* The G-buffer on units first.. first + 3 (gk_gbuffer_bind). */
static void bind_gbuffer(const gk_gbuffer_uniforms *u, const gk_gi_frame *f, int first, GLuint sampler)
{
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gb, u, first, sampler);
}

static void unbind_units(int n)
{
    for (int u = 0; u < n; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindTexture(GL_TEXTURE_3D, 0);
        glBindSampler((GLuint)u, 0);
    }
    glActiveTexture(GL_TEXTURE0);
}

int vct_pass_trace(gk_vct *v, const gk_gi_frame *f, const vct_budget *b, gk_err *e)
{
    char defs[320];
    vct_map_defines(v, defs, sizeof defs);
    size_t used = strlen(defs);
    snprintf(defs + used, sizeof defs - used,
             "#define AXIS_WEIGHT_SQ %d\n#define OPACITY_CORRECTION %d\n#define SPECULAR %d\n"
             "#define CLIP_CONES %d\n#define EMPTY_SKIP %d\n#define AXIS_CLAMP %d\n",
             v->opt.axis_weight_sq ? 1 : 0, v->opt.opacity_correction ? 1 : 0,
             v->specular ? 1 : 0, v->opt.clip_cones ? 1 : 0, b->skip && v->specular ? 1 : 0,
             vct_axis_clamp_in_use(v, b->axis_clamp));
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/trace.comp", defs, e);
    const trace_uniforms *u = p ? gk_program_uniforms(v->ctx.programs, p, GK_FIELDS(trace_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(p);
    vct_bind_map(v, u->u_vox0, u->u_voxp, u->u_voxp_l0, u->u_dir_levels);
    glUniform1i(u->u_skip_top, vct_skip_top(v));
    bind_gbuffer(&u->g, f, 7, v->nearest_sampler);
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind_geom_normal(&gb, u->u_gb_geom_normal, 7 + GK_GBUFFER_UNITS, v->nearest_sampler);
    glUniform2i(u->u_low_size, v->trace_w, v->trace_h);
    int block = (int)lroundf(1.0f / b->trace_scale);
    glUniform1i(u->u_block, block < 1 ? 1 : block);
    glUniform1i(u->u_res, v->res);
    glUniform1f(u->u_res_f, (float)v->res);
    glUniform3f(u->u_grid_origin, v->origin[0], v->origin[1], v->origin[2]);
    glUniform1f(u->u_grid_size, v->size);
    glUniform1f(u->u_step_mul, b->step);
    glUniform1f(u->u_ao_lambda, v->opt.ao_lambda);
    glUniform1f(u->u_max_dist, v->opt.max_dist);
    glUniform1f(u->u_apex_offset, v->opt.apex_offset);
    glUniform1f(u->u_footprint_clamp, v->opt.footprint_clamp);
    glUniform1f(u->u_spec_aperture, v->opt.spec_aperture);
    float dir[VCT_MAX_CONES][3], ap[VCT_MAX_CONES], w[VCT_MAX_CONES];
    int n = vct_cone_set(b->cones, v->opt.faithful_weights, dir, ap, w);
    glUniform1i(u->u_n_cones, n);
    glUniform3fv(u->u_cone_dir, n, &dir[0][0]);
    glUniform1fv(u->u_cone_aperture, n, ap);
    glUniform1fv(u->u_cone_weight, n, w);
    static const GLuint zero[3] = {0, 0, 0}; /* the trace's work counters (vct/trace.comp Counters) */
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->counter_ssbo);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, v->counter_ssbo);
    if (vct_axis_clamp_in_use(v, b->axis_clamp))
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, v->axis_ssbo);
    glBindImageTexture(0, v->trace_diffuse, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(1, v->trace_spec, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute((GLuint)groups(v->trace_w, 8), (GLuint)groups(v->trace_h, 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    unbind_units(7 + GK_GBUFFER_UNITS + 1);
    v->stats.trace_runs++;
    return 0;
}

/* The bounce gather's step multiplier: the thesis code's 0.5 (its text's 1 is the per-pixel default),
   whatever vct_step is, since the pass runs only when the injection does. Measured on cornell vs the
   full reference at 160x120, vct_bounces=2: 0.122 with the budget's step 1, 0.113 with 0.5. */
#define VCT_BOUNCE_STEP 0.5f

int vct_pass_bounce(gk_vct *v, const vct_budget *b, gk_err *e)
{
    char defs[448];
    defines_common(v, defs, sizeof defs);
    size_t used = strlen(defs);
    vct_map_defines(v, defs + used, sizeof defs - used);
    used = strlen(defs);
    snprintf(defs + used, sizeof defs - used,
             "#define AXIS_WEIGHT_SQ %d\n#define OPACITY_CORRECTION %d\n#define CLIP_CONES %d\n%s",
             v->opt.axis_weight_sq ? 1 : 0, v->opt.opacity_correction ? 1 : 0, v->opt.clip_cones ? 1 : 0,
             vct_work_bounce_begin(v));
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/bounce.comp", defs, e);
    const bounce_uniforms *u = p ? gk_program_uniforms(v->ctx.programs, p, GK_FIELDS(bounce_fields), sizeof *u, e) : NULL;
    if (!u || vct_ensure_bounce_target(v, e) != 0) {
        vct_work_bounce_end(v);
        return -1;
    }
    glUseProgram(p);
    vct_bind_map(v, u->u_vox0, u->u_voxp, u->u_voxp_l0, u->u_dir_levels);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);
    glBindImageTexture(0, v->vox_bounce, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glUniform1i(u->u_res, v->res);
    glUniform1f(u->u_res_f, (float)v->res);
    glUniform1f(u->u_step_mul, VCT_BOUNCE_STEP);
    glUniform1f(u->u_ao_lambda, v->opt.ao_lambda);
    glUniform1f(u->u_max_dist, v->opt.max_dist);
    glUniform1f(u->u_apex_offset, v->opt.apex_offset);
    glUniform1f(u->u_footprint_clamp, v->opt.footprint_clamp);
    float dir[VCT_MAX_CONES][3], ap[VCT_MAX_CONES], w[VCT_MAX_CONES];
    int n = vct_cone_set(b->cones, v->opt.faithful_weights, dir, ap, w);
    glUniform1i(u->u_n_cones, n);
    glUniform3fv(u->u_cone_dir, n, &dir[0][0]);
    glUniform1fv(u->u_cone_aperture, n, ap);
    glUniform1fv(u->u_cone_weight, n, w);
    glDispatchCompute((GLuint)groups(v->res, 4), (GLuint)groups(v->res, 4), (GLuint)groups(v->res, 4));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    vct_work_bounce_end(v);
    unbind_units(7);
    GLuint t = v->vox0;   /* the bounced level 0 becomes the map; the old one is next time's target */
    v->vox0 = v->vox_bounce;
    v->vox_bounce = t;
    v->stats.bounce_runs++;
    return 0;
}

int vct_pass_compose(gk_vct *v, const gk_gi_frame *f, gk_err *e)
{
    char defs[160];
    snprintf(defs, sizeof defs, "%s%s", v->opt.faithful_weights ? "#define FAITHFUL_COMPOSE 1\n" : "#define FAITHFUL_COMPOSE 0\n",
             vct_work_compose_begin(v, f->count_work));
    GLuint p = gk_program_get(v->ctx.programs, "vct/compose.vert", "vct/compose.frag", defs, e);
    const compose_uniforms *u = p ? gk_program_uniforms(v->ctx.programs, p, GK_FIELDS(compose_fields), sizeof *u, e) : NULL;
    if (!u) {
        vct_work_compose_end(v);
        return -1;
    }
    /* save the state this pass changes */
    GLint fbo = 0, vp[4], prog = 0, vao = 0, src_rgb, dst_rgb, src_a, dst_a;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
    glGetIntegerv(GL_BLEND_SRC_RGB, &src_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &src_a);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &dst_a);
    GLboolean blend = glIsEnabled(GL_BLEND), depth = glIsEnabled(GL_DEPTH_TEST), cull = glIsEnabled(GL_CULL_FACE);
    GLboolean dmask;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &dmask);

    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f->hdr_fbo);
    glViewport(0, 0, f->width, f->height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    /* hdr' = rgb + hdr * a (see compose.frag); alpha channel of the HDR image left as it was */
    glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
    glUseProgram(p);
    bind_tex(u->u_diffuse_lo, 0, GL_TEXTURE_2D, v->trace_diffuse, v->nearest_sampler);
    bind_tex(u->u_spec_lo, 1, GL_TEXTURE_2D, v->trace_spec, v->nearest_sampler);
    bind_gbuffer(&u->g, f, 2, v->nearest_sampler);
    glUniform2i(u->u_low_size, v->trace_w, v->trace_h);
    int block = (int)lroundf(1.0f / v->cur.trace_scale);
    glUniform1i(u->u_block, block < 1 ? 1 : block);
    glUniform1f(u->u_voxel_world, v->voxel);
    glUniform1f(u->u_spec_enabled, v->specular ? 1.0f : 0.0f);
    glBindVertexArray(v->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    vct_work_compose_end(v);

    unbind_units(2 + GK_GBUFFER_UNITS);
    glBindVertexArray((GLuint)vao);
    glUseProgram((GLuint)prog);
    glBlendFuncSeparate((GLenum)src_rgb, (GLenum)dst_rgb, (GLenum)src_a, (GLenum)dst_a);
    if (!blend)
        glDisable(GL_BLEND);
    if (depth)
        glEnable(GL_DEPTH_TEST);
    if (cull)
        glEnable(GL_CULL_FACE);
    glDepthMask(dmask);
    glViewport(vp[0], vp[1], vp[2], vp[3]);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)fbo);
    return 0;
}
