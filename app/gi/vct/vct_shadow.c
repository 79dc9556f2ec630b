/* The soft-shadow cone (thesis §3.3, Fig. 17; summary A.2.6) as gk_gi_method.shadow_mask: one
 * cone per G-buffer pixel toward the light through the voxel map, opacity only, visibility 1 - A
 * into an R32F mask the renderer's direct pass multiplies in (shadow/mask.glsl) instead of its
 * shadow maps. The direct pass runs before the GI pass, so the mask first brings the voxel map up to
 * date (vct_update: nothing to do on a static scene after its first frame); the trace pass later
 * in the frame finds it done. Knob vct_shadow: map (off), the thesis's apertures, or the light's. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gl/gl_target.h"

#include "vct_internal.h"

/* vct/shadow_cone.comp */
typedef struct shadow_uniforms {
    gk_gbuffer_uniforms g;
    GLint u_gb_geom_normal;
    GLint u_vox0, u_voxp[3], u_voxp_l0[3], u_dir_levels, u_skip_top;
    GLint u_res, u_res_f, u_grid_origin, u_grid_size, u_step_mul, u_ao_lambda, u_max_dist, u_apex_offset,
        u_footprint_clamp, u_light_directional, u_light_pos, u_light_dir, u_aperture, u_light_diameter;
} shadow_uniforms;
static const gk_uniform_field shadow_fields[] = {
    GK_GBUFFER_FIELDS(shadow_uniforms, g),
    GK_UNIFORM(shadow_uniforms, u_gb_geom_normal),
    VCT_CONE_FIELDS(shadow_uniforms),
    GK_UNIFORM(shadow_uniforms, u_skip_top),
    GK_UNIFORM(shadow_uniforms, u_grid_origin),
    GK_UNIFORM(shadow_uniforms, u_grid_size),
    GK_UNIFORM(shadow_uniforms, u_light_directional),
    GK_UNIFORM(shadow_uniforms, u_light_pos),
    GK_UNIFORM(shadow_uniforms, u_light_dir),
    GK_UNIFORM(shadow_uniforms, u_aperture),
    GK_UNIFORM(shadow_uniforms, u_light_diameter),
};

/* The cone's aperture (diameter at unit distance, summary §0.3: 2 tan(theta / 2)) at a fixed level,
   or -1: the light's own (the shader divides the light's diameter by the receiver's distance). */
static float level_aperture(int level)
{
    static const float degrees[] = {[VCT_SHADOW_CONE9] = 9, [VCT_SHADOW_CONE6] = 6, [VCT_SHADOW_CONE3] = 3,
                                    [VCT_SHADOW_CONE0] = 0};
    if (level < VCT_SHADOW_CONE9 || level > VCT_SHADOW_CONE0)
        return -1.0f;
    return 2.0f * tanf(0.5f * degrees[level] * 3.14159265f / 180.0f);
}

/* The emitter's diameter for the light-sized cone: a sphere's or disc's, a rectangle's equal-area
   disc's; a directional light's 2 tan(angular radius). 0 (a point light): the 0-degree cone. */
static float light_diameter(const gk_light *l)
{
    if (!l)
        return 0.0f;
    if (l->type == GK_LIGHT_DIRECTIONAL)
        return 2.0f * tanf(l->radius);
    if (l->shape == GK_SHAPE_RECT)
        return 2.0f * sqrtf(l->size[0] * l->size[1] / 3.14159265f);
    return 2.0f * l->radius;
}

static int ensure_mask(gk_vct *v, int light, int w, int h, gk_err *e)
{
    if (v->mask_w != w || v->mask_h != h) {
        vct_shadow_free(v);
        v->mask_w = w, v->mask_h = h;
    }
    if (v->shadow_mask[light])
        return 0;
    v->shadow_mask[light] = gk_texture_2d(GL_R32F, w, h, GL_NEAREST);
    if (!v->shadow_mask[light])
        return gk_fail(e, GK_ERUNTIME, "vct: shadow mask %dx%d could not be made", w, h);
    return 0;
}

void vct_shadow_free(gk_vct *v)
{
    glDeleteTextures(VCT_MAX_LIGHTS, v->shadow_mask);
    for (int i = 0; i < VCT_MAX_LIGHTS; i++)
        v->shadow_mask[i] = 0;
}

static int pass_shadow(gk_vct *v, const gk_gi_frame *f, const vct_budget *b, int light, gk_err *e)
{
    char defs[320];
    vct_map_defines(v, defs, sizeof defs);
    size_t used = strlen(defs);
    snprintf(defs + used, sizeof defs - used,
             "#define AXIS_WEIGHT_SQ %d\n#define OPACITY_CORRECTION %d\n#define CLIP_CONES %d\n#define EMPTY_SKIP %d\n",
             v->opt.axis_weight_sq ? 1 : 0, v->opt.opacity_correction ? 1 : 0, v->opt.clip_cones ? 1 : 0,
             b->skip ? 1 : 0);
    GLuint p = gk_program_get_compute(v->ctx.programs, "vct/shadow_cone.comp", defs, e);
    const shadow_uniforms *u = p ? gk_program_uniforms(v->ctx.programs, p, GK_FIELDS(shadow_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    const gk_gi_light *L = &f->lights[light];
    const gk_light *sl = (f->scene && L->scene_light >= 0 && L->scene_light < f->scene->n_lights)
                             ? &f->scene->lights[L->scene_light] : NULL;
    glUseProgram(p);
    vct_bind_map(v, u->u_vox0, u->u_voxp, u->u_voxp_l0, u->u_dir_levels);
    glUniform1i(u->u_skip_top, vct_skip_top(v));
    gk_gbuffer_view gb = gk_gi_gbuffer(f);
    gk_gbuffer_bind(&gb, &u->g, 7, v->nearest_sampler);
    gk_gbuffer_bind_geom_normal(&gb, u->u_gb_geom_normal, 7 + GK_GBUFFER_UNITS, v->nearest_sampler);
    glUniform1i(u->u_res, v->res);
    glUniform1f(u->u_res_f, (float)v->res);
    glUniform3f(u->u_grid_origin, v->origin[0], v->origin[1], v->origin[2]);
    glUniform1f(u->u_grid_size, v->size);
    glUniform1f(u->u_step_mul, 1.0f); /* thesis code's shadow step: max(diameter, 1 voxel) */
    glUniform1f(u->u_ao_lambda, v->opt.ao_lambda);
    glUniform1f(u->u_max_dist, v->opt.max_dist);
    glUniform1f(u->u_apex_offset, v->opt.apex_offset);
    glUniform1f(u->u_footprint_clamp, v->opt.footprint_clamp);
    glUniform1i(u->u_light_directional, sl && sl->type == GK_LIGHT_DIRECTIONAL);
    glUniform3f(u->u_light_pos, L->position.x, L->position.y, L->position.z);
    glUniform3f(u->u_light_dir, L->direction.x, L->direction.y, L->direction.z);
    glUniform1f(u->u_aperture, level_aperture(b->shadow));
    glUniform1f(u->u_light_diameter, light_diameter(sl));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, v->counter_ssbo);
    glBindImageTexture(0, v->shadow_mask[light], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute((GLuint)((f->width + 7) / 8), (GLuint)((f->height + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    for (int unit = 0; unit < 7 + GK_GBUFFER_UNITS + 1; unit++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindTexture(GL_TEXTURE_3D, 0);
        glBindSampler((GLuint)unit, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    v->stats.shadow_runs++;
    return 0;
}

int vct_shadow_mask(void *self, const gk_gi_frame *f, int light, unsigned *tex, gk_err *e)
{
    gk_vct *v = self;
    *tex = 0;
    vct_budget b;
    vct_read_budget(v, f->budget, &b);
    if (b.shadow == VCT_SHADOW_MAP || light < 0 || light >= f->n_lights || light >= VCT_MAX_LIGHTS)
        return 0; /* lights past the ones vct injects keep their shadow maps */
    if (vct_update(v, f, &b, e) != 0 || ensure_mask(v, light, f->width, f->height, e) != 0)
        return -1;
    if (light == 0) { /* the frame's first mask: its samples are counted from zero */
        static const GLuint zero = 0;
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->counter_ssbo);
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 3 * sizeof zero, sizeof zero, &zero); /* shadow_steps */
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    }
    gk_pass_begin(f->pass, "vct_shadow_cone");
    int rc = pass_shadow(v, f, &b, light, e);
    gk_pass_end(f->pass);
    if (rc != 0)
        return -1;
    *tex = v->shadow_mask[light];
    return 0;
}
