/* The environment's residual ambient and background (render_env.h). */
#include "render_env.h"

#include <stdlib.h>

#include "renderer_internal.h"

int gk_render_env_lights_drawn(const gk_scene *s, int env_lights)
{
    int n = s->environment.n_env_lights;
    return env_lights < n ? (env_lights < 0 ? 0 : env_lights) : n;
}

bool gk_render_env_light_on(const gk_scene *s, int li, int env_lights)
{
    if (li < 0 || li >= s->n_lights || !s->lights[li].env_part)
        return true;
    return li - s->environment.env_light_first < gk_render_env_lights_drawn(s, env_lights);
}

/* CSSM at 256² as the thesis shadows its environment lights, with the per-layer depth range and the
   final kernel tested against the receiver plane (cssm_plane: shadow_cssm.c says why, with the
   measurement; it replaced cssm_env's 5 cm cap on the slope-scaled shift) */
const gk_shadow_method *gk_render_env_shadow_method(void)
{
    return gk_shadow_method_find("cssm_plane");
}

/* direct/environment.frag */
typedef struct env_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_env_sh, u_env_map, u_env_size;
} env_uniforms;
static const gk_uniform_field env_fields[] = {
    GK_GBUFFER_FIELDS(env_uniforms, gb),
    GK_UNIFORM_AS(env_uniforms, u_env_sh, "u_env_sh[0]"),
    GK_UNIFORM(env_uniforms, u_env_map),
    GK_UNIFORM(env_uniforms, u_env_size),
};

/* Texture unit of the map: after the G-buffer's five. */
#define UNIT_ENV_MAP (UNIT_ALBEDO + GK_GBUFFER_UNITS)

/* The map as RGBA, box-filtered by 2^shift on each side (shift 0: as is). */
static float *map_rgba(const gk_environment *env, int shift, int *w, int *h)
{
    int f = 1 << shift;
    *w = env->width / f, *h = env->height / f;
    float *rgba = calloc((size_t)*w * (size_t)*h * 4, sizeof *rgba);
    if (!rgba)
        return NULL;
    for (int y = 0; y < env->height / f * f; y++)
        for (int x = 0; x < env->width / f * f; x++) {
            float *o = rgba + 4 * ((size_t)(y / f) * (size_t)*w + (size_t)(x / f));
            const float *p = env->rgb + 3 * ((size_t)y * (size_t)env->width + (size_t)x);
            for (int c = 0; c < 3; c++)
                o[c] += p[c] / (float)(f * f);
            o[3] = 1.0f;
        }
    return rgba;
}

static int upload_map(gk_renderer *r, const gk_environment *env, int *w, int *h, gk_err *e)
{
    if (r->env_tex && r->env_tex_generation == r->scene_generation) {
        glBindTexture(GL_TEXTURE_2D, r->env_tex);
        glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, w);
        glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, h);
        return 0;
    }
    /* GLES 3.1 promises 2048 texels a side; a wider map (up to GK_ENV_MAX_WIDTH) is halved until it
       fits: only the background loses detail, the lights and ambient come from the full map */
    GLint max_size = 2048;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    int shift = 0;
    while ((env->width >> shift) > max_size && (env->height >> shift) > 4)
        shift++;
    float *rgba = map_rgba(env, shift, w, h);
    if (!rgba)
        return gk_fail(e, GK_ERUNTIME, "environment: out of memory uploading the map");
    if (r->env_tex)
        glDeleteTextures(1, &r->env_tex);
    /* RGBA32F: sampleable in GLES 3.0 core (read with texelFetch, no filtering needed: the map is
       piecewise constant by definition, environment.h) */
    r->env_tex = gk_texture_2d(GL_RGBA32F, *w, *h, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, r->env_tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, *w, *h, GL_RGBA, GL_FLOAT, rgba);
    free(rgba);
    r->env_tex_generation = r->scene_generation;
    return 0;
}

int gk_render_env_pass(gk_renderer *r, const gk_gbuffer_view *gb, int env_lights, gk_err *e)
{
    const gk_environment *env = &r->scene->environment;
    if (!env->present || !env->rgb || !env->ambient_sh)
        return 0;
    int tw, th;
    if (upload_map(r, env, &tw, &th, e) != 0)
        return -1;
    GLuint prog = gk_program_get(r->progs, "common/fullscreen.vert", "direct/environment.frag", NULL, e);
    const env_uniforms *u = prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(env_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(prog);
    gk_gbuffer_bind(gb, &u->gb, UNIT_ALBEDO, 0);
    glActiveTexture(GL_TEXTURE0 + UNIT_ENV_MAP);
    glBindTexture(GL_TEXTURE_2D, r->env_tex);
    glBindSampler(UNIT_ENV_MAP, 0);
    glUniform1i(u->u_env_map, UNIT_ENV_MAP);
    glUniform2i(u->u_env_size, tw, th);
    int k = gk_render_env_lights_drawn(r->scene, env_lights);
    glUniform3fv(u->u_env_sh, 9, &env->ambient_sh[k][0][0]);
    gk_render_fullscreen(r);
    return 0;
}
