/* volcaustics passes 1a, 1b and 2 (research dong-001.md §6.3), once per caustic light: the light's
 * view of the scene with and without the specular objects and of the specular objects' back faces,
 * then one light ray per light-view texel, reflected by a mirror or refracted twice through glass
 * where the light meets a specular object (the light's caustic buffer: p1, p2, flux; shaders_gles/
 * volcaustics/raygen.comp). The light view is one perspective frustum fitted to the specular
 * objects' bounds (research §6.8's mitigation for a small object in a wide spot: every
 * caustic-buffer texel can carry a line), so the caustic buffer's resolution is the light view's.
 * The caustic lights are the scene's first vc_lights point and spot lights (in the scene's order)
 * whose view frames the specular objects; the light views are shared, each light keeps its own
 * caustic buffer for the lines pass (vc_lines.c). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "medium_uniforms.h"
#include "vc_internal.h"

/* A mirror or clear glass, as lightview.frag classifies them (app/scene/features.c). */
static bool is_specular(const gk_material *m)
{
    return !m->light_proxy && m->roughness < 0.2f && (m->metallic > 0.5f || m->transmission > 0.5f);
}

void vc_specular_bounds(vc_state *s, const gk_scene *sc)
{
    vec3 lo = v3(INFINITY, INFINITY, INFINITY), hi = v3(-INFINITY, -INFINITY, -INFINITY);
    s->have_specular = false;
    for (int i = 0; i < sc->n_nodes; i++) {
        const gk_node *n = &sc->nodes[i];
        for (int k = n->mesh_first; k < n->mesh_first + n->mesh_count; k++) {
            const gk_mesh *m = &sc->meshes[k];
            if (!is_specular(&sc->materials[m->material]))
                continue;
            for (int c = 0; c < 8; c++) {
                vec3 p = v3(c & 1 ? m->bmax.x : m->bmin.x, c & 2 ? m->bmax.y : m->bmin.y, c & 4 ? m->bmax.z : m->bmin.z);
                vec3 w = m4_point(n->world, p);
                lo = v3_min(lo, w);
                hi = v3_max(hi, w);
            }
            s->have_specular = true;
        }
    }
    s->spec_min = lo, s->spec_max = hi;
    s->scene_min = sc->bmin, s->scene_max = sc->bmax;
}

/* Light i of the frame (a point or spot light), its view framed on the specular bounds; L->ok false
   when it cannot make a volume caustic. */
static void frame_light(vc_state *s, const gk_gi_frame *f, int i, vc_light *L)
{
    memset(L, 0, sizeof *L);
    const gk_light *sl = &f->scene->lights[f->lights[i].scene_light];
    if (!s->have_specular || (sl->type != GK_LIGHT_POINT && sl->type != GK_LIGHT_SPOT))
        return;
    L->pos = f->lights[i].position;
    L->axis = f->lights[i].direction;
    L->radiant = f->lights[i].radiant;
    L->spot = sl->type == GK_LIGHT_SPOT;
    L->cos_outer = cosf(sl->outer_cone);
    L->cos_inner = cosf(sl->inner_cone);
    if (v3_maxc(L->radiant) <= 0.0f)
        return;
    vec3 c = v3_scale(v3_add(s->spec_min, s->spec_max), 0.5f);
    float r = 0.5f * v3_len(v3_sub(s->spec_max, s->spec_min));
    float dist = v3_len(v3_sub(c, L->pos));
    if (dist <= r * 1.01f)
        return; /* the light inside the specular objects' bounds: no one frustum sees them */
    float half = asinf(r / dist) * 1.05f;
    L->fwd = v3_scale(v3_sub(c, L->pos), 1.0f / dist);
    vec3 up = fabsf(L->fwd.y) < 0.95f ? v3(0, 1, 0) : v3(1, 0, 0);
    float scene_r = 0.5f * v3_len(v3_sub(s->scene_max, s->scene_min));
    float znear = fmaxf(0.01f, 0.9f * (dist - r)), zfar = dist + 2.0f * scene_r + r;
    L->vp = m4_mul(m4_perspective(2.0f * half, 1.0f, znear, zfar), m4_look_at(L->pos, c, up));
    L->inv_vp = m4_inverse(L->vp);
    float texel = 2.0f * tanf(half) / (float)s->buffer_res;
    L->texel_omega0 = texel * texel;
    L->spec_extent = 2.0f * r;
    L->ok = true;
}

/* The light views (shared by the lights) and caustic buffers 0..n-1 at the buffer resolution. */
static int ensure_buffers(vc_state *s, int n, gk_err *e)
{
    int R = s->buffer_res;
    if (s->cb_res != R) {
        vc_free_light_buffers(s);
        const GLenum lv_fmt[2] = {GL_RGBA8, GL_RGBA8};
        if (gk_target_create(&s->lv, "volcaustics light view", R, R, 2, lv_fmt, GL_NEAREST, true, e) ||
            gk_target_create(&s->lv_nospec, "volcaustics light view without specular objects", R, R, 1, lv_fmt,
                             GL_NEAREST, true, e) ||
            gk_target_create(&s->lv_back, "volcaustics light view of the specular back faces", R, R, 1, lv_fmt,
                             GL_NEAREST, true, e))
            return -1;
        s->cb_res = R;
    }
    /* rgba32f images: written by the compute pass (core GLES 3.1), read by texelFetch in lines.vert */
    for (; s->n_cb < n; s->n_cb++) {
        vc_caustic_buffer *cb = &s->cb[s->n_cb];
        cb->p1 = gk_texture_2d(GL_RGBA32F, R, R, GL_NEAREST);
        cb->p2 = gk_texture_2d(GL_RGBA32F, R, R, GL_NEAREST);
        cb->flux = gk_texture_2d(GL_RGBA32F, R, R, GL_NEAREST);
    }
    return 0;
}

void vc_free_light_buffers(vc_state *s)
{
    gk_target_destroy(&s->lv);
    gk_target_destroy(&s->lv_nospec);
    gk_target_destroy(&s->lv_back);
    for (int i = 0; i < s->n_cb; i++) {
        GLuint t[3] = {s->cb[i].p1, s->cb[i].p2, s->cb[i].flux};
        glDeleteTextures(3, t);
    }
    memset(s->cb, 0, sizeof s->cb);
    s->n_cb = 0;
    s->cb_res = 0;
}

typedef struct lightview_uniforms {
    GLint u_light_vp, u_light_pos;
} lightview_uniforms;
static const gk_uniform_field lightview_fields[] = {GK_UNIFORM(lightview_uniforms, u_light_vp),
                                                   GK_UNIFORM(lightview_uniforms, u_light_pos)};

/* One light view; back = true keeps the farthest surface (the depth test reversed, cleared to 0). */
static int light_view(vc_state *s, const gk_gi_frame *f, const vc_light *L, gk_target *t, const char *defines,
                      bool back, gk_err *e)
{
    GLuint prog = gk_program_get(s->ctx.programs, "volcaustics/lightview.vert", "volcaustics/lightview.frag",
                                 defines, e);
    const lightview_uniforms *u =
        prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(lightview_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(t->n_color, bufs);
    glViewport(0, 0, t->width, t->height);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(back ? GL_GREATER : GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glClearColor(0, 0, 0, 0);
    glClearDepthf(back ? 0.0f : 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(prog);
    glUniformMatrix4fv(u->u_light_vp, 1, GL_FALSE, L->vp.m);
    glUniform3f(u->u_light_pos, L->pos.x, L->pos.y, L->pos.z);
    int rc = f->draw_scene(f->draw_ctx, prog, e);
    glDepthFunc(GL_LESS);
    glClearDepthf(1.0f);
    glDisable(GL_DEPTH_TEST);
    return rc;
}

typedef struct raygen_uniforms {
    GLint u_depth_all, u_depth_nospec, u_nrm, u_f0, u_res, u_light_vp, u_light_inv_vp, u_light_pos, u_light_fwd,
        u_light_axis, u_radiant, u_cone, u_spot, u_texel_omega0, u_scene_min, u_scene_max, u_steps, u_depth_back,
        u_nrm_back, u_glass_steps, u_spec_extent;
    vc_medium_uniforms med;
} raygen_uniforms;
static const gk_uniform_field raygen_fields[] = {
    GK_UNIFORM(raygen_uniforms, u_depth_all), GK_UNIFORM(raygen_uniforms, u_depth_nospec),
    GK_UNIFORM(raygen_uniforms, u_nrm), GK_UNIFORM(raygen_uniforms, u_f0), GK_UNIFORM(raygen_uniforms, u_res),
    GK_UNIFORM(raygen_uniforms, u_light_vp), GK_UNIFORM(raygen_uniforms, u_light_inv_vp),
    GK_UNIFORM(raygen_uniforms, u_light_pos), GK_UNIFORM(raygen_uniforms, u_light_fwd),
    GK_UNIFORM(raygen_uniforms, u_light_axis), GK_UNIFORM(raygen_uniforms, u_radiant),
    GK_UNIFORM(raygen_uniforms, u_cone), GK_UNIFORM(raygen_uniforms, u_spot),
    GK_UNIFORM(raygen_uniforms, u_texel_omega0), GK_UNIFORM(raygen_uniforms, u_scene_min),
    GK_UNIFORM(raygen_uniforms, u_scene_max), GK_UNIFORM(raygen_uniforms, u_steps),
    GK_UNIFORM(raygen_uniforms, u_depth_back), GK_UNIFORM(raygen_uniforms, u_nrm_back),
    GK_UNIFORM(raygen_uniforms, u_glass_steps), GK_UNIFORM(raygen_uniforms, u_spec_extent),
    VC_MEDIUM_FIELDS(raygen_uniforms, med),
};

static void bind_tex(int unit, GLuint tex, GLint loc)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(loc, unit);
}

static int generate_rays(vc_state *s, const gk_gi_frame *f, const vc_light *L, const vc_caustic_buffer *cb,
                         const char *defines, gk_err *e)
{
    GLuint prog = gk_program_get_compute(s->ctx.programs, "volcaustics/raygen.comp", defines, e);
    const raygen_uniforms *u =
        prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(raygen_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(prog);
    bind_tex(0, s->lv.depth, u->u_depth_all);
    bind_tex(1, s->lv_nospec.depth, u->u_depth_nospec);
    bind_tex(2, s->lv.color[0], u->u_nrm);
    bind_tex(3, s->lv.color[1], u->u_f0);
    bind_tex(4, s->lv_back.depth, u->u_depth_back);
    bind_tex(5, s->lv_back.color[0], u->u_nrm_back);
    glBindImageTexture(0, cb->p1, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, cb->p2, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(2, cb->flux, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUniform1i(u->u_res, s->buffer_res);
    glUniformMatrix4fv(u->u_light_vp, 1, GL_FALSE, L->vp.m);
    glUniformMatrix4fv(u->u_light_inv_vp, 1, GL_FALSE, L->inv_vp.m);
    glUniform3f(u->u_light_pos, L->pos.x, L->pos.y, L->pos.z);
    glUniform3f(u->u_light_fwd, L->fwd.x, L->fwd.y, L->fwd.z);
    glUniform3f(u->u_light_axis, L->axis.x, L->axis.y, L->axis.z);
    glUniform3f(u->u_radiant, L->radiant.x, L->radiant.y, L->radiant.z);
    glUniform2f(u->u_cone, L->cos_outer, L->cos_inner);
    glUniform1i(u->u_spot, L->spot ? 1 : 0);
    glUniform1f(u->u_texel_omega0, L->texel_omega0);
    glUniform3f(u->u_scene_min, s->scene_min.x, s->scene_min.y, s->scene_min.z);
    glUniform3f(u->u_scene_max, s->scene_max.x, s->scene_max.y, s->scene_max.z);
    glUniform1i(u->u_steps, VC_P2_STEPS);
    glUniform1i(u->u_glass_steps, VC_GLASS_STEPS);
    glUniform1f(u->u_spec_extent, L->spec_extent);
    vc_set_medium(&u->med, f->scene);
    GLuint groups = (GLuint)(s->buffer_res + 7) / 8;
    glDispatchCompute(groups, groups, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    for (int i = 0; i < 3; i++)
        glBindImageTexture((GLuint)i, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    return 0;
}

int vc_light_rays(vc_state *s, const gk_gi_frame *f, int *n_lines, gk_err *e)
{
    *n_lines = 0;
    if (f->scene_changed)
        vc_specular_bounds(s, f->scene);
    s->st.caustic_lights = 0;
    /* one count over every light's rays, one over every light's views */
    const char *raygen_defines = vc_work_begin(s, VC_WORK_RAYGEN), *view_count = vc_work_begin(s, VC_WORK_LIGHTVIEW);
    char front[96], nospec[96], back[96];
    snprintf(front, sizeof front, "#define VC_WITH_SPECULAR 1\n%s", view_count);
    snprintf(nospec, sizeof nospec, "#define VC_NO_SPECULAR 1\n%s", view_count);
    snprintf(back, sizeof back, "#define VC_BACK_FACES 1\n%s", view_count);
    int rc = 0;
    for (int i = 0; i < f->n_lights && *n_lines < s->max_lights && *n_lines < VC_MAX_LIGHTS; i++) {
        vc_light *L = &s->light[*n_lines];
        frame_light(s, f, i, L);
        if (!L->ok)
            continue;
        if (ensure_buffers(s, *n_lines + 1, e) || light_view(s, f, L, &s->lv, front, false, e) ||
            light_view(s, f, L, &s->lv_nospec, nospec, false, e) || light_view(s, f, L, &s->lv_back, back, true, e) ||
            generate_rays(s, f, L, &s->cb[*n_lines], raygen_defines, e)) {
            rc = -1;
            break;
        }
        ++*n_lines;
    }
    vc_work_end(s, VC_WORK_RAYGEN);
    vc_work_end(s, VC_WORK_LIGHTVIEW);
    if (rc)
        return -1;
    s->st.caustic_lights = *n_lines;
    s->st.light_ok = *n_lines > 0;
    return 0;
}
