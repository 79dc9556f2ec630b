/* Renderer lifetime, scene upload and the GI method list. The passes are in render_frame.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "ltc_table.h"
#include "render_gi.h"
#include "renderer_internal.h"

/* The LTC tables as one RGBA32F texture (rows 0..N-1: Minv, N..2N-1: A, B), read with texelFetch
 * and filtered in the shader (RGBA32F is not filterable in GLES 3.1 core; fp16 cannot hold Minv at
 * the smallest roughness). */
static GLuint create_ltc_texture(void)
{
    static float texels[GK_LTC_N * 2 * GK_LTC_N * 4];
    memcpy(texels, gk_ltc_minv, sizeof gk_ltc_minv);
    float *amp = texels + GK_LTC_N * GK_LTC_N * 4;
    for (int i = 0; i < GK_LTC_N * GK_LTC_N; i++) {
        amp[4 * i] = gk_ltc_amp[2 * i];
        amp[4 * i + 1] = gk_ltc_amp[2 * i + 1];
        amp[4 * i + 2] = amp[4 * i + 3] = 0.0f;
    }
    GLuint tex = gk_texture_2d(GL_RGBA32F, GK_LTC_N, 2 * GK_LTC_N, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, GK_LTC_N, 2 * GK_LTC_N, GL_RGBA, GL_FLOAT, texels);
    glBindTexture(GL_TEXTURE_2D, 0);
    return tex;
}

gk_renderer *gk_renderer_create(const gk_render_opts *opts, gk_err *e)
{
    if (!opts || opts->width <= 0 || opts->height <= 0) {
        gk_fail(e, GK_EINPUT, "renderer: bad output size %dx%d", opts ? opts->width : 0, opts ? opts->height : 0);
        return NULL;
    }
    gk_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        gk_fail(e, GK_ERUNTIME, "renderer: out of memory");
        return NULL;
    }
    r->opts = *opts;
    if (opts->shader_dir) {
        r->shader_dir = strdup(opts->shader_dir);
        r->opts.shader_dir = r->shader_dir;
    }
    gk_gl_caps_query(&r->caps, opts->gles_version);
    if (!r->caps.color_buffer_half) {
        gk_fail(e, GK_ERUNTIME,
                "renderer: RGBA16F is not colour-renderable (needs GLES 3.2, EXT_color_buffer_half_float or "
                "EXT_color_buffer_float)");
        free(r->shader_dir);
        free(r);
        return NULL;
    }
    r->progs = gk_program_cache_create(r->shader_dir, r->caps.gles >= 32 ? 32 : 31);
    r->timer = gk_timer_create(opts->gpu_timer_queries && r->caps.timer_query);
    r->gi = gk_render_gi_create();
    gk_render_knobs_init(&r->knobs);
    glGenVertexArrays(1, &r->empty_vao);
    r->ltc_tex = create_ltc_texture();
    if (!r->progs || !r->timer || !r->gi) {
        gk_renderer_destroy(r);
        gk_fail(e, GK_ERUNTIME, "renderer: out of memory");
        return NULL;
    }
    /* Compile the always-used programs now, so a broken shader fails at start, not mid-show. */
    static const char *const vf[][2] = {
        {"gbuffer/gbuffer.vert", "gbuffer/gbuffer.frag"},
        {"common/fullscreen.vert", "direct/emission.frag"},
        {"common/fullscreen.vert", "compose/compose.frag"},
        {"shadow/depth.vert", "shadow/depth.frag"},
    };
    if (!gk_render_geom_normal_target(r))
        gk_log("renderer: %d draw buffers, the G-buffer needs 5 for the geometric normal: normal-mapped "
                    "surfaces offset shadows and start vct's cones along the mapped normal",
                    r->caps.max_draw_buffers);
    for (size_t i = 0; i < sizeof vf / sizeof vf[0]; i++)
        if (!gk_program_get(r->progs, vf[i][0], vf[i][1], i == 0 ? gk_render_gbuffer_defines(r) : NULL, e)) {
            gk_renderer_destroy(r);
            return NULL;
        }
    return r;
}

void gk_renderer_destroy(gk_renderer *r)
{
    if (!r)
        return;
    if (r->have_gpu)
        gk_scene_gpu_free(&r->gpu);
    gk_target_destroy(&r->gbuf);
    gk_target_destroy(&r->hdr);
    gk_target_destroy(&r->glass);
    gk_render_split_destroy(r);
    gk_gi_blend_destroy(r);
    gk_render_work_destroy(r);
    for (int i = 0; i < GK_MAX_SHADOW_METHODS && gk_shadow_methods[i]; i++)
        if (r->shadow_state[i])
            gk_shadow_methods[i]->destroy(r->shadow_state[i]);
    if (r->gi)
        gk_render_gi_destroy(r->gi);
    if (r->empty_vao)
        glDeleteVertexArrays(1, &r->empty_vao);
    if (r->ltc_tex)
        glDeleteTextures(1, &r->ltc_tex);
    if (r->blend_fbo)
        glDeleteFramebuffers(1, &r->blend_fbo);
    if (r->env_tex)
        glDeleteTextures(1, &r->env_tex);
    gk_timer_destroy(r->timer);
    gk_program_cache_destroy(r->progs);
    free(r->shader_dir);
    free(r);
}

void gk_renderer_set_rerender_static_shadows(gk_renderer *r, bool on) { r->opts.rerender_static_shadows = on; }
void gk_renderer_set_rebuild_gi(gk_renderer *r, bool on) { r->opts.rebuild_gi = on; }

int gk_renderer_set_scene(gk_renderer *r, gk_scene *s, gk_err *e)
{
    if (r->have_gpu)
        gk_scene_gpu_free(&r->gpu);
    r->have_gpu = false;
    r->scene = NULL;
    /* A new scene may live at the address of the old one: caches key on the generation. */
    r->scene_generation++;
    memset(&r->shadow_cache, 0, sizeof r->shadow_cache);
    r->have_frame = false;
    r->exposure_known = false;
    gk_gi_blend_reset(r);
    if (!s)
        return 0;
    if (gk_scene_gpu_upload(&r->gpu, s, e) != 0)
        return -1;
    r->have_gpu = true;
    r->scene = s;
    if (s->has_exposure) { /* the scene's own exposure (EV) wins over the measured key */
        r->exposure = exp2f(s->exposure_ev);
        r->exposure_known = true;
    }
    return 0;
}

int gk_renderer_methods(const gk_renderer *r, const char **names, int max)
{
    if (r->scene)
        return gk_render_gi_methods(r->scene, names, max);
    int n = 0;
    if (n < max)
        names[n++] = "none";
    return n;
}

int gk_render_light_kind(const gk_light *l)
{
    if (l->type == GK_LIGHT_DIRECTIONAL)
        return 2;
    switch (l->shape) {
    case GK_SHAPE_SPHERE: return 3;
    case GK_SHAPE_DISC: return 4;
    case GK_SHAPE_RECT: return 5;
    default: return l->type == GK_LIGHT_SPOT ? 1 : 0;
    }
}

void gk_render_light_defines(const gk_light *l, const char *extra, char *out, size_t size)
{
    snprintf(out, size, "#define GK_LIGHT_KIND %d\n%s%s", gk_render_light_kind(l),
             l->type == GK_LIGHT_SPOT ? "#define GK_LIGHT_SPOT 1\n" : "", extra ? extra : "");
}

void gk_render_set_light(gk_renderer *r, const gk_light_uniforms *u, int node)
{
    const gk_light *l = &r->scene->lights[r->scene->nodes[node].light];
    vec3 pos, dir, lu, lv;
    gk_scene_light_frame(r->scene, node, &pos, &dir, &lu, &lv);
    glUniform3f(u->u_light_pos, pos.x, pos.y, pos.z);
    glUniform3f(u->u_light_dir, dir.x, dir.y, dir.z);
    glUniform3f(u->u_light_u, lu.x, lu.y, lu.z);
    glUniform3f(u->u_light_v, lv.x, lv.y, lv.z);
    glUniform3f(u->u_light_color, l->color[0] * l->intensity, l->color[1] * l->intensity, l->color[2] * l->intensity);
    glUniform1f(u->u_light_range, l->range);
    glUniform2f(u->u_light_cone, cosf(l->outer_cone), cosf(l->inner_cone));
    glUniform1f(u->u_light_radius, l->radius);
    glUniform2f(u->u_light_size, l->size[0], l->size[1]);
    glActiveTexture(GL_TEXTURE0 + UNIT_LTC);
    glBindTexture(GL_TEXTURE_2D, r->ltc_tex);
    glBindSampler(UNIT_LTC, 0);
    glUniform1i(u->u_ltc, UNIT_LTC);
}

void gk_render_fullscreen(gk_renderer *r)
{
    glBindVertexArray(r->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

float gk_renderer_exposure(const gk_renderer *r) { return r->exposure; }

const gk_budget *gk_renderer_budget_ran(const gk_renderer *r)
{
    return r->have_ran ? &r->ran : NULL;
}

void gk_renderer_cut(gk_renderer *r)
{
    gk_gi_blend_reset(r);
}
