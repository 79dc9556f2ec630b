/* GI methods inside the frame (DESIGN §5): the renderer lends each method its G-buffer, HDR
 * target, lights and a scene-drawing callback through gk_gi_frame (app/gi/gi.h), creates a
 * method's state on first use, hands it each new scene once, and collects its pass times.
 *
 * Light injection needs a 2D depth map per light (gk_gi_light.shadow_depth_tex): the direct-light
 * shadow maps are cube maps or arrays owned by the shadow method, so the GI layer keeps its own
 * single-face depth maps — perspective along the emitter's axis for local lights (the cone of a
 * spot; 160 degrees for one-sided area emitters and point lights, which covers what a ceiling
 * light sees), orthographic over the scene bounds for directional lights. They are re-rendered
 * only when the scene changes or animates. */
#include "render_gi.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "renderer_internal.h"

#define GI_LIGHT_MAP_SIZE 1024
#define GI_MAX_METHODS 16

struct gk_render_gi {
    void *state[GI_MAX_METHODS];             /* per registered method, created on first use */
    unsigned generation_of[GI_MAX_METHODS];  /* renderer scene generation each state last saw (0 = none) */
    bool changed_unseen[GI_MAX_METHODS];     /* a new scene the shadow masks prepared the method for this
                                                frame, not yet told to its render() (scene_changed) */
    unsigned failed_on[GI_MAX_METHODS];      /* scene generation on which the method failed (0 = none):
                                                skipped until the next scene, never retried per frame */
    GLuint depth_tex[GK_GI_MAX_LIGHTS];
    GLuint fbo;
    gk_gi_light lights[GK_GI_MAX_LIGHTS];
    int n_lights;
    unsigned maps_generation;                /* scene generation the maps were rendered for (static scenes) */
};

gk_render_gi *gk_render_gi_create(void)
{
    return calloc(1, sizeof(gk_render_gi));
}

void gk_render_gi_destroy(gk_render_gi *g)
{
    if (!g)
        return;
    int n;
    const gk_gi_method *const *m = gk_gi_methods(&n);
    for (int i = 0; i < n && i < GI_MAX_METHODS; i++)
        if (g->state[i])
            m[i]->destroy(g->state[i]);
    glDeleteTextures(GK_GI_MAX_LIGHTS, g->depth_tex);
    if (g->fbo)
        glDeleteFramebuffers(1, &g->fbo);
    free(g);
}

void gk_render_gi_declare_knobs(gk_budget *b)
{
    int n;
    const gk_gi_method *const *m = gk_gi_methods(&n);
    for (int i = 0; i < n; i++)
        m[i]->declare_knobs(b);
}

static bool listed(const char *const *names, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], name) == 0)
            return true;
    return false;
}

int gk_render_gi_methods(const gk_scene *s, const char **names, int max)
{
    int n = 0;
    if (n < max)
        names[n++] = "none";
    if (!s)
        return n;
    /* What the scene needs (gk_scene_methods) AND what is implemented and applies. */
    const char *needs[16];
    int n_needs = gk_scene_methods(s, needs, 16);
    int count;
    const gk_gi_method *const *m = gk_gi_methods(&count);
    for (int i = 0; i < n_needs && n < max; i++) {
        if (strcmp(needs[i], "none") == 0)
            continue;
        for (int k = 0; k < count; k++)
            if (strcmp(m[k]->name, needs[i]) == 0 && m[k]->applies(s) && !listed(names, n, needs[i]))
                names[n++] = m[k]->name;
    }
    return n;
}

/* The single-face view of one light for injection (see the header comment). */
static mat4 light_view_proj(const gk_scene *s, const gk_light *l, vec3 pos, vec3 dir, float *znear, float *zfar,
                            bool *perspective)
{
    vec3 c = v3_scale(v3_add(s->bmin, s->bmax), 0.5f);
    float radius = 0.5f * v3_len(v3_sub(s->bmax, s->bmin)) + 1e-3f;
    vec3 up = fabsf(dir.y) < 0.95f ? v3(0, 1, 0) : v3(1, 0, 0);
    if (l->type == GK_LIGHT_DIRECTIONAL) {
        vec3 eye = v3_sub(c, v3_scale(dir, 2.0f * radius));
        *znear = 0.0f;
        *zfar = 4.0f * radius;
        *perspective = false;
        return m4_mul(m4_ortho(-radius, radius, -radius, radius, *znear, *zfar), m4_look_at(eye, c, up));
    }
    float fov = 160.0f * (float)M_PI / 180.0f;
    if (l->type == GK_LIGHT_SPOT && l->shape != GK_SHAPE_RECT)
        fov = fminf(fov, 2.0f * l->outer_cone + 0.1f);
    float far = v3_len(v3_sub(c, pos)) + radius;
    *znear = fmaxf(0.01f, far * 1e-3f);
    *zfar = far;
    *perspective = true;
    return m4_mul(m4_perspective(fov, 1.0f, *znear, *zfar), m4_look_at(pos, v3_add(pos, dir), up));
}

/* shadow/depth.{vert,frag} for the GI light maps */
typedef struct light_map_uniforms {
    GLint u_viewproj;
    gk_draw_uniforms draw;
} light_map_uniforms;
static const gk_uniform_field light_map_fields[] = {GK_UNIFORM(light_map_uniforms, u_viewproj),
                                                    GK_UNIFORM_AS(light_map_uniforms, draw.u_model, "u_model"),
                                                    GK_ALPHA_MASK_FIELDS(light_map_uniforms, draw)};

/* What gk_gi_frame.draw_scene sets in a method's program (gi.h) */
static const gk_uniform_field draw_scene_fields[] = {
    GK_UNIFORM(gk_draw_uniforms, u_model),
    GK_UNIFORM(gk_draw_uniforms, u_base_color),
    GK_UNIFORM(gk_draw_uniforms, u_metallic_roughness),
    GK_UNIFORM(gk_draw_uniforms, u_emissive),
    GK_UNIFORM(gk_draw_uniforms, u_mat_flags),
    GK_UNIFORM(gk_draw_uniforms, u_specular),
};

static int render_light_maps(gk_render_gi *g, gk_renderer *r, gk_err *e)
{
    const gk_scene *s = r->scene;
    bool dynamic = s->features.has_animation;
    if (g->maps_generation == r->scene_generation && !dynamic)
        return 0;
    GLuint prog = gk_program_get(r->progs, "shadow/depth.vert", "shadow/depth.frag", gk_scene_gpu_depth_defines(s), e);
    const light_map_uniforms *u = prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(light_map_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    if (!g->fbo)
        glGenFramebuffers(1, &g->fbo);
    g->n_lights = 0;
    for (int i = 0; i < s->n_nodes && g->n_lights < GK_GI_MAX_LIGHTS; i++) {
        int li = s->nodes[i].light;
        if (li < 0 || li >= s->n_lights)
            continue;
        const gk_light *l = &s->lights[li];
        int k = g->n_lights++;
        gk_gi_light *L = &g->lights[k];
        memset(L, 0, sizeof *L);
        L->scene_light = li;
        L->node = i;
        gk_scene_light_frame(s, i, &L->position, &L->direction, &L->axis_u, &L->axis_v);
        L->radiant = v3(l->color[0] * l->intensity, l->color[1] * l->intensity, l->color[2] * l->intensity);
        L->shadow_view_proj = light_view_proj(s, l, L->position, L->direction, &L->shadow_near, &L->shadow_far,
                                              &L->shadow_is_perspective);
        if (!g->depth_tex[k])
            g->depth_tex[k] = gk_texture_2d(GL_DEPTH_COMPONENT32F, GI_LIGHT_MAP_SIZE, GI_LIGHT_MAP_SIZE, GL_NEAREST);
        L->shadow_depth_tex = g->depth_tex[k];
        glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, g->depth_tex[k], 0);
        GLenum none = GL_NONE;
        glDrawBuffers(1, &none);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return gk_fail(e, GK_ERUNTIME, "GI light map: framebuffer incomplete");
        glViewport(0, 0, GI_LIGHT_MAP_SIZE, GI_LIGHT_MAP_SIZE);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        glClear(GL_DEPTH_BUFFER_BIT);
        glUseProgram(prog);
        glUniformMatrix4fv(u->u_viewproj, 1, GL_FALSE, L->shadow_view_proj.m);
        gk_scene_gpu_draw(&r->gpu, s, &u->draw, gk_scene_gpu_depth_flags(s) | GK_DRAW_SKIP_PROXIES);
    }
    glDisable(GL_DEPTH_TEST);
    g->maps_generation = r->scene_generation;
    return 0;
}

static int draw_scene_cb(void *ctx, unsigned program, gk_err *e)
{
    gk_renderer *r = ctx;
    const gk_draw_uniforms *u = gk_program_uniforms(r->progs, program, GK_FIELDS(draw_scene_fields), sizeof *u, e);
    if (!u)
        return -1;
    /* u_glass (vec2 ior, transmission) is optional (gi.h): looked up here, once per draw_scene call
       (a method calls it once per map face when its scene changes, not per pixel or per mesh). */
    gk_draw_uniforms du = *u;
    du.u_glass = glGetUniformLocation(program, "u_glass");
    /* ... and so are what common/alpha_mask.glsl reads (vpl's RSMs, lgv's cube maps cut the holes) */
    du.u_base_tex = glGetUniformLocation(program, "u_base_tex");
    du.u_alpha_cutoff = glGetUniformLocation(program, "u_alpha_cutoff");
    du.u_tex_xf = glGetUniformLocation(program, "u_tex_xf");
    du.u_tex_uv1 = glGetUniformLocation(program, "u_tex_uv1");
    /* ... and which draw it is (lgv's cube maps tell the glass instances apart) */
    du.u_node_mesh = glGetUniformLocation(program, "u_node_mesh");
    gk_scene_gpu_draw(&r->gpu, r->scene, &du, GK_DRAW_MATERIALS | GK_DRAW_SKIP_PROXIES);
    return 0;
}

static int method_index(const char *method)
{
    int count;
    const gk_gi_method *const *m = gk_gi_methods(&count);
    for (int i = 0; method && i < count && i < GI_MAX_METHODS; i++)
        if (strcmp(m[i]->name, method) == 0)
            return i;
    return -1;
}

bool gk_render_gi_failed(const gk_render_gi *g, const gk_renderer *r, const char *method)
{
    int k = method_index(method);
    return k >= 0 && g->failed_on[k] == r->scene_generation;
}

/* Creates the method's state on first use and hands it each new scene once. */
static int prepare(gk_render_gi *g, gk_renderer *r, const gk_gi_method *m, int k, bool *changed, gk_err *e)
{
    if (!g->state[k]) {
        gk_gi_context ctx = {.programs = r->progs, .gles_version = r->caps.gles, .cpu_workers = r->opts.cpu_workers};
        if (!(g->state[k] = m->create(&ctx, e)))
            return -1;
    }
    *changed = g->generation_of[k] != r->scene_generation;
    if (*changed) {
        if (m->set_scene(g->state[k], r->scene, e) != 0)
            return -1;
        g->generation_of[k] = r->scene_generation;
    }
    return 0;
}

/* The frame a method is lent (gi.h), after prepare() and render_light_maps(). */
static void fill_frame(gk_render_gi *g, gk_renderer *r, const gk_pass_ctx *ctx, bool changed, gk_gi_frame *out)
{
    const gk_gbuffer_view *gb = ctx->gbuffer;
    gk_gi_frame f;
    memset(&f, 0, sizeof f);
    f.pass = ctx;
    f.scene = r->scene;
    f.time_s = r->time_s; /* gi.h: the time the scene was evaluated at (lightmap's IIM blend reads it) */
    f.scene_changed = changed || r->scene->features.has_animation;
    f.width = gb->width;
    f.height = gb->height;
    f.view = gb->view;
    f.proj = gb->proj;
    f.view_proj = gb->view_proj;
    f.inv_view_proj = gb->inv_view_proj;
    f.eye = gb->eye;
    f.gbuf_albedo = gb->albedo;
    f.gbuf_normal = gb->normal;
    f.gbuf_emission = gb->emission;
    f.gbuf_depth = gb->depth;
    f.gbuf_specular = gb->specular;
    f.gbuf_geom_normal = gb->geom_normal;
    f.direct_tex = 0; /* the method adds into the same HDR target: reading it would be a feedback loop */
    f.hdr_fbo = r->hdr.fbo;
    f.n_lights = g->n_lights;
    f.lights = g->lights;
    f.budget = ctx->budget;
    f.draw_scene = draw_scene_cb;
    f.draw_ctx = r;
    f.count_work = r->count_work; /* a bench counting frame (pass_work.h) */
    *out = f;
}

/* The method's index (-1: none, unknown, or failed on this scene), its state made and handed the
   scene, the GI light maps rendered; -1 in *k with e filled when that fails (the method is then
   skipped on this scene). */
static int ready(gk_render_gi *g, gk_renderer *r, const char *method, int *k, bool *changed, gk_err *e)
{
    *k = -1;
    if (!method || strcmp(method, "none") == 0)
        return 0;
    int i = method_index(method);
    if (i < 0 || g->failed_on[i] == r->scene_generation)
        return 0; /* unknown, or broken on this scene: direct light only (the kiosk keeps showing something) */
    int count;
    const gk_gi_method *m = gk_gi_methods(&count)[i];
    if (prepare(g, r, m, i, changed, e) != 0 || render_light_maps(g, r, e) != 0) {
        g->failed_on[i] = r->scene_generation;
        return -1;
    }
    *k = i;
    return 0;
}

int gk_render_gi_shadow_masks(gk_render_gi *g, gk_renderer *r, const char *method, const gk_pass_ctx *ctx,
                              const int *nodes, int n, unsigned *masks, gk_err *e)
{
    for (int i = 0; i < n; i++)
        masks[i] = 0;
    int k = method ? method_index(method) : -1, count;
    const gk_gi_method *const *methods = gk_gi_methods(&count);
    /* only a method whose budget asks for masks is made ready here, before the direct pass: the
       others' set-up and light maps stay in the gi pass they are timed in */
    if (k < 0 || !methods[k]->shadow_mask || !methods[k]->wants_shadow_mask ||
        !methods[k]->wants_shadow_mask(ctx->budget))
        return 0;
    bool changed = false;
    if (ready(g, r, method, &k, &changed, e) != 0)
        return -1;
    if (k < 0)
        return 0;
    g->changed_unseen[k] = changed; /* the method's render() this frame is told the scene changed */
    gk_gi_frame f;
    fill_frame(g, r, ctx, changed, &f);
    for (int li = 0; li < g->n_lights; li++) {
        int at = -1; /* the frame light on the GI light's node */
        for (int i = 0; i < n && at < 0; i++)
            if (nodes[i] == g->lights[li].node)
                at = i;
        if (at < 0)
            continue;
        if (methods[k]->shadow_mask(g->state[k], &f, li, &masks[at], e) != 0) {
            g->failed_on[k] = r->scene_generation;
            for (int i = 0; i < n; i++)
                masks[i] = 0;
            return -1;
        }
    }
    return 0;
}

int gk_render_gi_run(gk_render_gi *g, gk_renderer *r, const char *method, const gk_pass_ctx *ctx, gk_err *e)
{
    int k, count;
    bool changed = false;
    if (ready(g, r, method, &k, &changed, e) != 0)
        return -1;
    if (k < 0)
        return 0;
    changed = changed || g->changed_unseen[k];
    g->changed_unseen[k] = false;
    const gk_gi_method *m = gk_gi_methods(&count)[k];
    gk_gi_frame f;
    fill_frame(g, r, ctx, changed, &f);
    if (r->opts.rebuild_gi && m->invalidate)
        m->invalidate(g->state[k]);
    int rc = m->render(g->state[k], &f, e);
    if (rc != 0)
        g->failed_on[k] = r->scene_generation;
    glBindFramebuffer(GL_FRAMEBUFFER, r->hdr.fbo);
    glViewport(0, 0, r->render_w, r->render_h);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    return rc;
}

long gk_render_gi_memory(const gk_render_gi *g, const char *method)
{
    int count;
    const gk_gi_method *const *m = gk_gi_methods(&count);
    for (int i = 0; i < count && i < GI_MAX_METHODS; i++)
        if (g->state[i] && strcmp(m[i]->name, method) == 0 && m[i]->memory_bytes)
            return m[i]->memory_bytes(g->state[i]);
    return 0;
}

int gk_render_gi_pass_work(const gk_render_gi *g, const char *method, gk_pass_work *out, int max)
{
    int count;
    const gk_gi_method *const *m = gk_gi_methods(&count);
    for (int i = 0; i < count && i < GI_MAX_METHODS; i++)
        if (g->state[i] && strcmp(m[i]->name, method) == 0 && m[i]->pass_work)
            return m[i]->pass_work(g->state[i], out, max);
    return 0;
}
