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

int vct_pass_voxelize(gk_vct *v, const int lo[3], const int hi[3], gk_err *e)
{
    char defs[256];
    defines_common(v, defs, sizeof defs);
    GLuint clear = gk_program_get_compute(v->ctx.programs, "vct/clear.comp", defs, e);
    GLuint vox = clear ? gk_program_get_compute(v->ctx.programs, "vct/voxelize.comp", defs, e) : 0;
    if (!vox)
        return -1;
    int size[3] = {hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1};
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, v->tri_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);

    glUseProgram(clear);
    glUniform1i(glGetUniformLocation(clear, "u_res"), v->res);
    glUniform3i(glGetUniformLocation(clear, "u_region_lo"), lo[0], lo[1], lo[2]);
    glUniform3i(glGetUniformLocation(clear, "u_region_size"), size[0], size[1], size[2]);
    glUniform1i(glGetUniformLocation(clear, "u_channels"), gk_vct_channels(v->emissive));
    glDispatchCompute((GLuint)groups(size[0], 4), (GLuint)groups(size[1], 4), (GLuint)groups(size[2], 4));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    glUseProgram(vox);
    glUniform1i(glGetUniformLocation(vox, "u_res"), v->res);
    glUniform3f(glGetUniformLocation(vox, "u_grid_origin"), v->origin[0], v->origin[1], v->origin[2]);
    glUniform1f(glGetUniformLocation(vox, "u_voxel_size"), v->voxel);
    glUniform3i(glGetUniformLocation(vox, "u_region_lo"), lo[0], lo[1], lo[2]);
    glUniform3i(glGetUniformLocation(vox, "u_region_hi"), hi[0], hi[1], hi[2]);
    glUniform1f(glGetUniformLocation(vox, "u_emission_scale"),
                v->tris.max_emission > 0 ? 1.0f / v->tris.max_emission : 0.0f);
    /* at most 65535 groups of 64 per dispatch */
    for (int first = 0; first < v->tris.n; first += 65535 * 64) {
        int count = v->tris.n - first < 65535 * 64 ? v->tris.n - first : 65535 * 64;
        glUniform1i(glGetUniformLocation(vox, "u_tri_first"), first);
        glUniform1i(glGetUniformLocation(vox, "u_tri_count"), count);
        glDispatchCompute((GLuint)groups(count, 64), 1, 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    v->stats.voxelize_runs++;
    v->stats.last_voxelized_region = (long)size[0] * size[1] * size[2];
    return 0;
}

static void uniform_at(GLuint p, const char *name, int i, char *buf, size_t n)
{
    snprintf(buf, n, "%s[%d]", name, i);
    (void)p;
}

int vct_pass_inject(gk_vct *v, const gk_gi_frame *f, gk_err *e)
{
    char defs[256];
    defines_common(v, defs, sizeof defs);
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/inject.comp", defs, e);
    if (!p)
        return -1;
    glUseProgram(p);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);
    glBindImageTexture(0, v->vox0, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glUniform1i(glGetUniformLocation(p, "u_res"), v->res);
    glUniform3i(glGetUniformLocation(p, "u_region_lo"), 0, 0, 0);
    glUniform3i(glGetUniformLocation(p, "u_region_size"), v->res, v->res, v->res);
    glUniform3f(glGetUniformLocation(p, "u_grid_origin"), v->origin[0], v->origin[1], v->origin[2]);
    glUniform1f(glGetUniformLocation(p, "u_voxel_size"), v->voxel);
    glUniform1f(glGetUniformLocation(p, "u_emission_max"), v->tris.max_emission);
    glUniform1f(glGetUniformLocation(p, "u_shadow_ambient"), v->opt.shadow_ambient);
    glUniform1f(glGetUniformLocation(p, "u_shadow_bias"), 0.0015f);
    int n = f->n_lights < VCT_MAX_LIGHTS ? f->n_lights : VCT_MAX_LIGHTS;
    glUniform1i(glGetUniformLocation(p, "u_n_lights"), n);
    char nm[64];
    for (int i = 0; i < VCT_MAX_LIGHTS; i++) {
        snprintf(nm, sizeof nm, "u_shadow%d", i);
        glUniform1i(glGetUniformLocation(p, nm), 8 + i);
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
        uniform_at(p, "u_light_type", i, nm, sizeof nm);
        glUniform1i(glGetUniformLocation(p, nm), type);
        uniform_at(p, "u_light_pos", i, nm, sizeof nm);
        glUniform3f(glGetUniformLocation(p, nm), L->position.x, L->position.y, L->position.z);
        uniform_at(p, "u_light_dir", i, nm, sizeof nm);
        glUniform3f(glGetUniformLocation(p, nm), L->direction.x, L->direction.y, L->direction.z);
        uniform_at(p, "u_light_radiant", i, nm, sizeof nm);
        glUniform3f(glGetUniformLocation(p, nm), L->radiant.x, L->radiant.y, L->radiant.z);
        uniform_at(p, "u_light_spot", i, nm, sizeof nm);
        glUniform2f(glGetUniformLocation(p, nm), scale, -co * scale);
        uniform_at(p, "u_light_lambert", i, nm, sizeof nm);
        glUniform1i(glGetUniformLocation(p, nm), lambert);
        uniform_at(p, "u_light_shadow", i, nm, sizeof nm);
        glUniform1i(glGetUniformLocation(p, nm), L->shadow_depth_tex != 0);
        uniform_at(p, "u_shadow_vp", i, nm, sizeof nm);
        glUniformMatrix4fv(glGetUniformLocation(p, nm), 1, GL_FALSE, L->shadow_view_proj.m);
    }
    glDispatchCompute((GLuint)groups(v->res, 4), (GLuint)groups(v->res, 4), (GLuint)groups(v->res, 4));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    for (int i = 0; i < VCT_MAX_LIGHTS; i++) {
        glActiveTexture(GL_TEXTURE8 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindSampler(8 + (GLuint)i, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    v->stats.inject_runs++;
    return 0;
}

int vct_pass_mips(gk_vct *v, gk_err *e)
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
    snprintf(defs + used, sizeof defs - used, "#define DIRECTIONAL_INJECTION %d\n", v->opt.directional_injection ? 1 : 0);
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/mip_aniso.comp", defs, e);
    if (!p)
        return -1;
    glUseProgram(p);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, v->scratch_ssbo);
    glUniform1i(glGetUniformLocation(p, "u_res"), v->res);
    for (int l = 1; l < v->levels; l++) {
        int dst_res = v->res >> l;
        glUniform1i(glGetUniformLocation(p, "u_dst_res"), dst_res);
        glUniform1i(glGetUniformLocation(p, "u_from_level0"), l == 1);
        for (int d = 0; d < 6; d++) {
            if (l == 1)
                glBindImageTexture(0, v->vox0, 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
            else
                glBindImageTexture(0, v->voxd[d], l - 2, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
            glBindImageTexture(1, v->voxd[d], l - 1, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glUniform1i(glGetUniformLocation(p, "u_dir"), d);
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

static void bind_tex(GLuint prog, const char *name, int unit, GLenum target, GLuint tex, GLuint sampler)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(target, tex);
    glBindSampler((GLuint)unit, sampler);
    glUniform1i(glGetUniformLocation(prog, name), unit);
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
    char defs[256];
    snprintf(defs, sizeof defs,
             "#define ISO_MIPS %d\n#define AXIS_WEIGHT_SQ %d\n#define OPACITY_CORRECTION %d\n#define SPECULAR %d\n"
             "#define CLIP_CONES %d\n",
             v->cur.aniso ? 0 : 1, v->opt.axis_weight_sq ? 1 : 0, v->opt.opacity_correction ? 1 : 0,
             v->specular ? 1 : 0, v->opt.clip_cones ? 1 : 0);
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/trace.comp", defs, e);
    if (!p)
        return -1;
    glUseProgram(p);
    bind_tex(p, "u_vox0", 0, GL_TEXTURE_3D, v->vox0, 0);
    if (v->cur.aniso)
        for (int d = 0; d < 6; d++) {
            char nm[24];
            snprintf(nm, sizeof nm, "u_voxd%d", d);
            bind_tex(p, nm, 1 + d, GL_TEXTURE_3D, v->voxd[d], 0);
        }
    bind_tex(p, "u_gbuf_depth", 7, GL_TEXTURE_2D, f->gbuf_depth, v->nearest_sampler);
    bind_tex(p, "u_gbuf_normal", 8, GL_TEXTURE_2D, f->gbuf_normal, v->nearest_sampler);
    bind_tex(p, "u_gbuf_albedo", 11, GL_TEXTURE_2D, f->gbuf_albedo, v->nearest_sampler);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_inv_view_proj"), 1, GL_FALSE, f->inv_view_proj.m);
    glUniform3f(glGetUniformLocation(p, "u_eye"), f->eye.x, f->eye.y, f->eye.z);
    glUniform2i(glGetUniformLocation(p, "u_full_size"), f->width, f->height);
    glUniform2i(glGetUniformLocation(p, "u_low_size"), v->trace_w, v->trace_h);
    int block = (int)lroundf(1.0f / b->trace_scale);
    glUniform1i(glGetUniformLocation(p, "u_block"), block < 1 ? 1 : block);
    glUniform1i(glGetUniformLocation(p, "u_res"), v->res);
    glUniform1f(glGetUniformLocation(p, "u_res_f"), (float)v->res);
    glUniform3f(glGetUniformLocation(p, "u_grid_origin"), v->origin[0], v->origin[1], v->origin[2]);
    glUniform1f(glGetUniformLocation(p, "u_grid_size"), v->size);
    glUniform1f(glGetUniformLocation(p, "u_step_mul"), b->step);
    glUniform1f(glGetUniformLocation(p, "u_ao_lambda"), v->opt.ao_lambda);
    glUniform1f(glGetUniformLocation(p, "u_max_dist"), v->opt.max_dist);
    glUniform1f(glGetUniformLocation(p, "u_apex_offset"), v->opt.apex_offset);
    glUniform1f(glGetUniformLocation(p, "u_footprint_clamp"), v->opt.footprint_clamp);
    glUniform1f(glGetUniformLocation(p, "u_spec_aperture"), v->opt.spec_aperture);
    float dir[VCT_MAX_CONES][3], ap[VCT_MAX_CONES], w[VCT_MAX_CONES];
    int n = vct_cone_set(b->cones, v->opt.faithful_weights, dir, ap, w);
    glUniform1i(glGetUniformLocation(p, "u_n_cones"), n);
    glUniform3fv(glGetUniformLocation(p, "u_cone_dir"), n, &dir[0][0]);
    glUniform1fv(glGetUniformLocation(p, "u_cone_aperture"), n, ap);
    glUniform1fv(glGetUniformLocation(p, "u_cone_weight"), n, w);
    static const GLuint zero = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->counter_ssbo);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, v->counter_ssbo);
    glBindImageTexture(0, v->trace_diffuse, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(1, v->trace_spec, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute((GLuint)groups(v->trace_w, 8), (GLuint)groups(v->trace_h, 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    unbind_units(12);
    v->stats.trace_runs++;
    return 0;
}

int vct_pass_compose(gk_vct *v, const gk_gi_frame *f, gk_err *e)
{
    GLuint p = gk_program_get(v->ctx.programs, "vct/compose.vert", "vct/compose.frag",
                              v->opt.faithful_weights ? "#define FAITHFUL_COMPOSE 1\n" : "#define FAITHFUL_COMPOSE 0\n", e);
    if (!p)
        return -1;
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
    bind_tex(p, "u_diffuse_lo", 0, GL_TEXTURE_2D, v->trace_diffuse, v->nearest_sampler);
    bind_tex(p, "u_spec_lo", 1, GL_TEXTURE_2D, v->trace_spec, v->nearest_sampler);
    bind_tex(p, "u_gbuf_depth", 2, GL_TEXTURE_2D, f->gbuf_depth, v->nearest_sampler);
    bind_tex(p, "u_gbuf_normal", 3, GL_TEXTURE_2D, f->gbuf_normal, v->nearest_sampler);
    bind_tex(p, "u_gbuf_albedo", 5, GL_TEXTURE_2D, f->gbuf_albedo, v->nearest_sampler);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_inv_view_proj"), 1, GL_FALSE, f->inv_view_proj.m);
    glUniform2i(glGetUniformLocation(p, "u_full_size"), f->width, f->height);
    glUniform2i(glGetUniformLocation(p, "u_low_size"), v->trace_w, v->trace_h);
    int block = (int)lroundf(1.0f / v->cur.trace_scale);
    glUniform1i(glGetUniformLocation(p, "u_block"), block < 1 ? 1 : block);
    glUniform1f(glGetUniformLocation(p, "u_voxel_world"), v->voxel);
    glUniform1f(glGetUniformLocation(p, "u_spec_enabled"), v->specular ? 1.0f : 0.0f);
    glBindVertexArray(v->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    unbind_units(7);
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
