/* glTF alphaMode BLEND (the `blend` pass, after gi and glass): the blended surfaces are left out of
 * the G-buffer, so direct light and GI shade what lies behind them, and are drawn here over the lit
 * HDR image, forward-shaded (blend/forward.frag): one mesh at a time, farthest first (by the
 * distance from the eye to its bounds' centre), each with one draw for its emission and the
 * environment's SH ambient that keeps 1 - alpha of what lies behind, then one additive draw per
 * light of the frame. The opaque G-buffer's depth tests them; they write no depth.
 *
 * What it lacks against the tracer's stochastic transparency: no shadows on the blended surface
 * (its lights are unshadowed), no shadow of partial strength behind it (the shadow maps hold it as
 * an opaque caster, the tracer lets 1 - alpha of the light through), no GI on it or through it
 * (the GI methods see the G-buffer only), and the order is per mesh, not per triangle: a mesh that
 * overlaps itself or another blended mesh is blended in draw order there. */
#include <stdio.h>
#include <stdlib.h>

#include "render_env.h"
#include "renderer_internal.h"

/* blend/forward.frag over gbuffer/gbuffer.vert */
typedef struct forward_uniforms {
    GLint u_viewproj, u_eye, u_env_sh;
    gk_draw_uniforms draw;
    gk_light_uniforms light;
} forward_uniforms;
#define FORWARD_DRAW_FIELDS                                                                                            \
    GK_UNIFORM(forward_uniforms, u_viewproj), GK_UNIFORM(forward_uniforms, u_eye),                                    \
        GK_UNIFORM_AS(forward_uniforms, draw.u_model, "u_model"),                                                      \
        GK_UNIFORM_AS(forward_uniforms, draw.u_normal_matrix, "u_normal_matrix"),                                      \
        GK_UNIFORM_AS(forward_uniforms, draw.u_base_color, "u_base_color"),                                            \
        GK_UNIFORM_AS(forward_uniforms, draw.u_metallic_roughness, "u_metallic_roughness"),                            \
        GK_UNIFORM_AS(forward_uniforms, draw.u_emissive, "u_emissive"),                                                \
        GK_UNIFORM_AS(forward_uniforms, draw.u_mat_flags, "u_mat_flags"),                                              \
        GK_UNIFORM_AS(forward_uniforms, draw.u_base_tex, "u_base_tex"),                                                \
        GK_UNIFORM_AS(forward_uniforms, draw.u_mr_tex, "u_mr_tex"),                                                    \
        GK_UNIFORM_AS(forward_uniforms, draw.u_specular, "u_specular"),                                                \
        GK_UNIFORM_AS(forward_uniforms, draw.u_spec_tex, "u_spec_tex"),                                                \
        GK_UNIFORM_AS(forward_uniforms, draw.u_spec_color_tex, "u_spec_color_tex"),                                    \
        GK_UNIFORM_AS(forward_uniforms, draw.u_emissive_tex, "u_emissive_tex"),                                        \
        GK_UNIFORM_AS(forward_uniforms, draw.u_normal_tex, "u_normal_tex"),                                            \
        GK_UNIFORM_AS(forward_uniforms, draw.u_normal_scale, "u_normal_scale"),                                        \
        GK_UNIFORM_AS(forward_uniforms, draw.u_occlusion_tex, "u_occlusion_tex"),                                      \
        GK_UNIFORM_AS(forward_uniforms, draw.u_occlusion_strength, "u_occlusion_strength"),                            \
        GK_UNIFORM_AS(forward_uniforms, draw.u_tex_xf, "u_tex_xf"),                                                    \
        GK_UNIFORM_AS(forward_uniforms, draw.u_tex_uv1, "u_tex_uv1")
static const gk_uniform_field ambient_fields[] = {FORWARD_DRAW_FIELDS, GK_UNIFORM(forward_uniforms, u_env_sh)};
static const gk_uniform_field light_fields[] = {FORWARD_DRAW_FIELDS, GK_LIGHT_FIELDS(forward_uniforms, light)};

/* One blended mesh of a node, and its distance from the eye. */
typedef struct blend_draw {
    int node, mesh;
    float dist;
} blend_draw;

static int farthest_first(const void *a, const void *b)
{
    float da = ((const blend_draw *)a)->dist, db = ((const blend_draw *)b)->dist;
    return (da < db) - (da > db);
}

static bool is_blended(const gk_scene *s, int k)
{
    int m = s->meshes[k].material;
    return m >= 0 && m < s->n_materials && s->materials[m].alpha_blend;
}

bool gk_render_blend_needed(const gk_renderer *r)
{
    for (int i = 0; r->scene && i < r->scene->n_materials; i++)
        if (r->scene->materials[i].alpha_blend)
            return true;
    return false;
}

/* The frame's blended meshes, farthest first; *n of them (NULL with *n 0 when there are none). */
static blend_draw *sorted_draws(const gk_scene *s, vec3 eye, int *n)
{
    *n = 0;
    blend_draw *d = malloc(sizeof *d * (size_t)(s->n_meshes + 1));
    if (!d)
        return NULL;
    for (int i = 0; i < s->n_nodes; i++) {
        const gk_node *node = &s->nodes[i];
        for (int k = node->mesh_first; k >= 0 && k < node->mesh_first + node->mesh_count && k < s->n_meshes; k++) {
            if (!is_blended(s, k) || *n >= s->n_meshes)
                continue;
            const gk_mesh *m = &s->meshes[k];
            vec3 c = m4_point(node->world, v3_scale(v3_add(m->bmin, m->bmax), 0.5f));
            d[(*n)++] = (blend_draw){.node = i, .mesh = k, .dist = v3_len(v3_sub(c, eye))};
        }
    }
    qsort(d, (size_t)*n, sizeof *d, farthest_first);
    return d;
}

static const forward_uniforms *use_program(gk_renderer *r, const char *defines, bool ambient, const gk_gbuffer_view *gb,
                                           gk_err *e)
{
    GLuint prog = gk_program_get(r->progs, "gbuffer/gbuffer.vert", "blend/forward.frag", defines, e);
    const forward_uniforms *u =
        !prog ? NULL
        : ambient ? gk_program_uniforms(r->progs, prog, GK_FIELDS(ambient_fields), sizeof *u, e)
                  : gk_program_uniforms(r->progs, prog, GK_FIELDS(light_fields), sizeof *u, e);
    if (!u)
        return NULL;
    glUseProgram(prog);
    glUniformMatrix4fv(u->u_viewproj, 1, GL_FALSE, gb->view_proj.m);
    glUniform3f(u->u_eye, gb->eye.x, gb->eye.y, gb->eye.z);
    return u;
}

/* The HDR image the frame shows (the cross-fade's output while one runs) with the G-buffer's depth. */
static int bind_target(gk_renderer *r, const gk_gbuffer_view *gb, gk_err *e)
{
    if (!r->blend_fbo)
        glGenFramebuffers(1, &r->blend_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->blend_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->shown, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, gb->depth, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "renderer: the blend pass's framebuffer (HDR + G-buffer depth) is incomplete");
    glViewport(0, 0, gb->width, gb->height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    return 0;
}

int gk_render_blend(gk_renderer *r, const gk_gbuffer_view *gb, int env_lights, const char *count_define, gk_err *e)
{
    const gk_scene *s = r->scene;
    int n;
    blend_draw *draws = sorted_draws(s, gb->eye, &n);
    if (!draws)
        return gk_fail(e, GK_ERUNTIME, "renderer: out of memory sorting the blended surfaces");
    int rc = n > 0 ? bind_target(r, gb, e) : 0;
    const gk_environment *env = &s->environment;
    int drawn_env = gk_render_env_lights_drawn(s, env_lights);
    const int flags = GK_DRAW_MATERIALS | GK_DRAW_CULL_SINGLE_SIDED;
    for (int i = 0; rc == 0 && i < n; i++) {
        char ambient[160];
        snprintf(ambient, sizeof ambient, "#define GK_FORWARD_AMBIENT 1\n%s", count_define);
        const forward_uniforms *u = use_program(r, ambient, true, gb, e);
        if (!u) {
            rc = -1;
            break;
        }
        static const float no_sh[9][3];
        glUniform3fv(u->u_env_sh, 9, env->present && env->ambient_sh ? &env->ambient_sh[drawn_env][0][0] : &no_sh[0][0]);
        glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        gk_scene_gpu_draw_mesh(&r->gpu, s, &u->draw, flags, draws[i].node, draws[i].mesh);
        glBlendFunc(GL_ONE, GL_ONE);
        for (int ln = 0; rc == 0 && ln < s->n_nodes; ln++) {
            int li = s->nodes[ln].light;
            if (li < 0 || li >= s->n_lights || !gk_render_env_light_on(s, li, env_lights))
                continue;
            char defines[256];
            gk_render_light_defines(&s->lights[li], count_define, defines, sizeof defines);
            if (!(u = use_program(r, defines, false, gb, e))) {
                rc = -1;
                break;
            }
            gk_render_set_light(r, &u->light, ln);
            gk_scene_gpu_draw_mesh(&r->gpu, s, &u->draw, flags, draws[i].node, draws[i].mesh);
        }
    }
    free(draws);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glActiveTexture(GL_TEXTURE0);
    return rc;
}
