/* One frame: shadow maps -> G-buffer -> direct light (emission, then one additive full-screen
 * pass per light) -> GI method (adds indirect light; its passes nest under `gi`) ->
 * compose/tonemap into the caller's framebuffer -> overlay (the kiosk's HUD). Every pass is timed
 * by the renderer's one timer through the pass context lent to it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "../core/tonemap.h"
#include "gl/gbuffer_bind.h"
#include "render_env.h"
#include "render_gi.h"
#include "render_glass.h"
#include "renderer_internal.h"

static int ensure_targets(gk_renderer *r, int w, int h, gk_err *e)
{
    if (r->gbuf.fbo && r->gbuf.width == w && r->gbuf.height == h)
        return 0;
    gk_target_destroy(&r->gbuf);
    gk_target_destroy(&r->hdr);
    gk_target_destroy(&r->glass);
    const GLenum gfmt[5] = {GL_RGBA8, GL_RGBA16F, GL_RGBA16F, GL_RGBA8, GL_RGBA16F};
    if (gk_target_create(&r->gbuf, "gbuffer", w, h, gk_render_geom_normal_target(r) ? 5 : 4, gfmt, GL_NEAREST, true,
                         e) != 0)
        return -1;
    const GLenum hfmt[1] = {GL_RGBA16F};
    if (gk_target_create(&r->hdr, "hdr", w, h, 1, hfmt, GL_LINEAR, false, e) != 0)
        return -1;
    r->render_w = w;
    r->render_h = h;
    r->have_frame = false;
    return 0;
}

static int method_index(const gk_shadow_method *m)
{
    for (int i = 0; i < GK_MAX_SHADOW_METHODS && gk_shadow_methods[i]; i++)
        if (gk_shadow_methods[i] == m)
            return i;
    return -1;
}

/* One shadowed light of this frame. */
typedef struct frame_light {
    int node;
    bool shadowed;
    const gk_shadow_method *method; /* the knob's, or CSSM for the environment's lights (render_env.h) */
    int slot;                       /* the light's slot in its method's state */
    gk_shadow_view view;
    unsigned mask;                  /* the GI method's visibility mask in place of the maps (0: none) */
} frame_light;

/* The method's state, created on first use; NULL with e set on failure. */
static void *shadow_state(gk_renderer *r, const gk_shadow_method *m, gk_err *e)
{
    int mi = method_index(m);
    if (mi < 0) {
        gk_fail(e, GK_ERUNTIME, "shadow method %s is not in gk_shadow_methods[]", m->name);
        return NULL;
    }
    if (!r->shadow_state[mi] && !(r->shadow_state[mi] = m->create()))
        gk_fail(e, GK_ERUNTIME, "shadow method %s: out of memory", m->name);
    return r->shadow_state[mi];
}

/* count_define: the depth draws' counting variant (gk_render_work_shadow_begin), "" without. */
static int pass_shadows(gk_renderer *r, const gk_frame_knobs *fk, const gk_pass_ctx *pctx, frame_light *fl, int n,
                        const char *count_define, gk_err *e)
{
    const gk_shadow_method *m = fk->shadow;
    int map_size = fk->shadow_map;
    if (!m)
        return 0;
    const gk_shadow_method *env_m = gk_render_env_shadow_method();
    gk_shadow_ctx ctx = {.progs = r->progs, .scene = r->scene, .gpu = &r->gpu, .caps = &r->caps,
                         .subdiv = fk->shadow_subdiv, .pass = pctx, .count_define = count_define,
                         .prefilter_work = r->count_work ? &r->prefilter_work : NULL};
    /* Static scene, same lights, same shadow knobs: the maps of the last frame are still right, so
       only the views are rebuilt (they are cheap and the lighting pass binds them). Most kiosk
       scenes are static, and the prefiltered maps (SAT, Fourier bases) cost more than the rest of
       the frame. The bench turns this off to measure a method's per-frame cost. */
    gk_shadow_cache_key key = {.scene_generation = r->scene_generation, .method = m, .map_size = map_size,
                               .subdiv = fk->shadow_subdiv, .env_lights = fk->env_lights};
    bool reuse = !r->opts.rerender_static_shadows && !r->scene->features.has_animation &&
                 memcmp(&key, &r->shadow_cache, sizeof key) == 0;
    int slots[GK_MAX_SHADOW_METHODS] = {0}; /* next free slot of each method's state */
    for (int i = 0; i < n; i++) {
        int size = map_size;
        const gk_light *l = &r->scene->lights[r->scene->nodes[fl[i].node].light];
        const gk_shadow_method *lm = l->env_part && env_m ? env_m : m;
        if (l->env_part)
            size = GK_ENV_SHADOW_MAP;
        if (l->type != GK_LIGHT_DIRECTIONAL && (l->shape == GK_SHAPE_POINT || l->shape == GK_SHAPE_SPHERE) && size > 1024)
            size = 1024; /* six faces: 2048^2 x 6 x 4 B = 96 MB is past a board's budget */
        int mi = method_index(lm);
        if (mi < 0 || slots[mi] >= GK_SHADOW_MAX_LIGHTS)
            continue; /* lights past the method's slots are unshadowed */
        void *st = shadow_state(r, lm, e);
        if (!st)
            return -1;
        if (!gk_shadow_view_for_light(r->scene, fl[i].node, size, &fl[i].view))
            continue;
        if (!reuse && lm->render(st, &ctx, slots[mi], &fl[i].view, e) != 0) {
            memset(&r->shadow_cache, 0, sizeof r->shadow_cache);
            return -1;
        }
        fl[i].shadowed = true;
        fl[i].method = lm;
        fl[i].slot = slots[mi]++;
    }
    r->shadow_cache = key;
    return 0;
}

/* gbuffer/gbuffer.{vert,frag} */
typedef struct gbuffer_uniforms {
    GLint u_viewproj, u_eye;
    gk_draw_uniforms draw;
} gbuffer_uniforms;
static const gk_uniform_field gbuffer_fields[] = {
    GK_UNIFORM(gbuffer_uniforms, u_viewproj),
    GK_UNIFORM(gbuffer_uniforms, u_eye),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_model, "u_model"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_normal_matrix, "u_normal_matrix"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_base_color, "u_base_color"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_metallic_roughness, "u_metallic_roughness"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_emissive, "u_emissive"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_mat_flags, "u_mat_flags"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_base_tex, "u_base_tex"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_mr_tex, "u_mr_tex"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_specular, "u_specular"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_spec_tex, "u_spec_tex"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_spec_color_tex, "u_spec_color_tex"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_emissive_tex, "u_emissive_tex"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_normal_tex, "u_normal_tex"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_normal_scale, "u_normal_scale"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_occlusion_tex, "u_occlusion_tex"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_occlusion_strength, "u_occlusion_strength"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_tex_xf, "u_tex_xf"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_tex_uv1, "u_tex_uv1"),
    GK_UNIFORM_AS(gbuffer_uniforms, draw.u_alpha_cutoff, "u_alpha_cutoff"),
};

/* direct/emission.frag */
typedef struct emission_uniforms {
    gk_gbuffer_uniforms gb;
} emission_uniforms;
static const gk_uniform_field emission_fields[] = {GK_GBUFFER_FIELDS(emission_uniforms, gb)};

/* direct/light.frag, every light kind and shadow variant (the shadow method's own uniforms are
   resolved by its bind) */
typedef struct light_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_gb_geom_normal;
    gk_light_uniforms light;
    GLint u_shadow_mask;
} light_uniforms;
static const gk_uniform_field light_fields[] = {
    GK_GBUFFER_FIELDS(light_uniforms, gb),
    GK_UNIFORM(light_uniforms, u_gb_geom_normal),
    GK_LIGHT_FIELDS(light_uniforms, light),
    GK_UNIFORM(light_uniforms, u_shadow_mask),
};

/* compose/compose.frag */
typedef struct compose_uniforms {
    GLint u_hdr, u_exposure;
} compose_uniforms;
static const gk_uniform_field compose_fields[] = {GK_UNIFORM(compose_uniforms, u_hdr),
                                                  GK_UNIFORM(compose_uniforms, u_exposure)};

static int pass_gbuffer(gk_renderer *r, const mat4 *viewproj, vec3 eye, gk_err *e)
{
    char defines[128];
    snprintf(defines, sizeof defines, "%s%s", gk_render_gbuffer_defines(r), gk_render_work_gbuffer_begin(r));
    GLuint prog = gk_program_get(r->progs, "gbuffer/gbuffer.vert", "gbuffer/gbuffer.frag", defines, e);
    const gbuffer_uniforms *u = prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(gbuffer_fields), sizeof *u, e) : NULL;
    if (!u) {
        gk_render_work_gbuffer_end(r);
        return -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, r->gbuf.fbo);
    glViewport(0, 0, r->render_w, r->render_h);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW); /* glTF's front faces */
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    glClearBufferfv(GL_COLOR, 2, zero);
    glClearBufferfv(GL_COLOR, 3, zero);
    if (r->gbuf.n_color > 4)
        glClearBufferfv(GL_COLOR, 4, zero);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glUseProgram(prog);
    glUniformMatrix4fv(u->u_viewproj, 1, GL_FALSE, viewproj->m);
    glUniform3f(u->u_eye, eye.x, eye.y, eye.z);
    gk_scene_gpu_draw(&r->gpu, r->scene, &u->draw, GK_DRAW_MATERIALS | GK_DRAW_SKIP_GLASS | GK_DRAW_SKIP_BLEND | GK_DRAW_CULL_SINGLE_SIDED);
    gk_render_work_gbuffer_end(r);
    return 0;
}

static int pass_direct(gk_renderer *r, const gk_frame_knobs *fk, const frame_light *fl, int n,
                       const gk_gbuffer_view *gbuf, gk_err *e)
{
    glBindFramebuffer(GL_FRAMEBUFFER, r->hdr.fbo);
    glViewport(0, 0, r->render_w, r->render_h);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    GLuint prog = gk_program_get(r->progs, "common/fullscreen.vert", "direct/emission.frag", NULL, e);
    if (!prog)
        return -1;
    const emission_uniforms *eu = gk_program_uniforms(r->progs, prog, GK_FIELDS(emission_fields), sizeof *eu, e);
    if (!eu)
        return -1;
    glUseProgram(prog);
    gk_gbuffer_bind(gbuf, &eu->gb, UNIT_ALBEDO, 0);
    gk_render_fullscreen(r);

    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    const char *count_define = gk_render_work_begin(r);
    for (int i = 0; i < n; i++) {
        const gk_scene *s = r->scene;
        const gk_light *l = &s->lights[s->nodes[fl[i].node].light];
        bool method_shadow = fl[i].shadowed && !fl[i].mask;
        /* a splitting method's light in two draws (SHADOW_SPLIT, shadow.h): the pixels its lookup
           settles early, then the others; each pixel is added once, in the same order of lights */
        int draws = method_shadow && fl[i].method->split && gk_render_split_enabled() ? 2 : 1;
        if (draws == 2 && !gk_render_split_first(r))
            draws = 1;
        for (int k = 0; k < draws; k++) {
            if (k == 1)
                gk_render_split_second();
            char extra[320], defines[384];
            snprintf(extra, sizeof extra, "%s%s%s",
                     fl[i].mask ? "#define SHADOW_MASK 1\n" : fl[i].shadowed ? fl[i].method->glsl_define : "",
                     draws == 1 ? "" : k == 0 ? "#define SHADOW_SPLIT 1\n" : "#define SHADOW_SPLIT 2\n",
                     method_shadow ? count_define : "");
            gk_render_light_defines(l, extra, defines, sizeof defines);
            prog = gk_program_get(r->progs, "common/fullscreen.vert", "direct/light.frag", defines, e);
            const light_uniforms *lu =
                prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(light_fields), sizeof *lu, e) : NULL;
            if (!lu) {
                if (draws == 2)
                    gk_render_split_end(r);
                glDisable(GL_BLEND);
                return -1;
            }
            glUseProgram(prog);
            gk_gbuffer_bind(gbuf, &lu->gb, UNIT_ALBEDO, 0);
            gk_gbuffer_bind_geom_normal(gbuf, lu->u_gb_geom_normal, UNIT_GEOM_NORMAL, 0);
            gk_render_set_light(r, &lu->light, fl[i].node);
            if (fl[i].mask) {
                glActiveTexture(GL_TEXTURE0 + UNIT_SHADOW);
                glBindTexture(GL_TEXTURE_2D, fl[i].mask);
                glBindSampler(UNIT_SHADOW, 0);
                glUniform1i(lu->u_shadow_mask, UNIT_SHADOW);
            } else if (fl[i].shadowed && fl[i].method->bind(r->shadow_state[method_index(fl[i].method)], r->progs,
                                                            fl[i].slot, &fl[i].view, prog, UNIT_SHADOW, e) != 0) {
                if (draws == 2)
                    gk_render_split_end(r);
                glDisable(GL_BLEND);
                return -1;
            }
            gk_render_fullscreen(r);
        }
        if (draws == 2)
            gk_render_split_end(r);
    }
    gk_render_work_end(r);
    int rc = gk_render_env_pass(r, gbuf, fk->env_lights, e);
    glDisable(GL_BLEND);
    return rc;
}

int gk_render_compose(gk_renderer *r, GLuint fbo, int w, int h, bool linear_out, const char *count_define, gk_err *e)
{
    char defines[96];
    snprintf(defines, sizeof defines, "%s%s", linear_out ? "#define GK_LINEAR_OUT 1\n" : "",
             count_define ? count_define : "");
    GLuint prog = gk_program_get(r->progs, "common/fullscreen.vert", "compose/compose.frag",
                                 defines[0] ? defines : NULL, e);
    const compose_uniforms *u = prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(compose_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->shown ? r->shown : r->hdr.color[0]);
    glUniform1i(u->u_hdr, 0);
    glUniform1f(u->u_exposure, r->exposure);
    gk_render_fullscreen(r);
    return 0;
}

/* Exposure (tonemap.h): key 0.18 over the mean luminance of the first frame of a scene, then
 * fixed, so the display does not pump as lights move. */
static void measure_exposure(gk_renderer *r)
{
    int w = r->render_w, h = r->render_h;
    float *px = malloc(sizeof(float) * 4 * (size_t)w * (size_t)h);
    r->exposure = 1.0f;
    r->exposure_known = true;
    if (!px)
        return;
    glBindFramebuffer(GL_FRAMEBUFFER, r->hdr.fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, px);
    double sum = 0.0;
    for (long i = 0; i < (long)w * h; i++) {
        float y = gk_luminance(px[4 * i], px[4 * i + 1], px[4 * i + 2]);
        if (isfinite(y))
            sum += y;
    }
    free(px);
    double mean = sum / ((double)w * h);
    if (mean > 1e-8)
        r->exposure = (float)(0.18 / mean);
}

bool gk_renderer_gi_failed(const gk_renderer *r, const char *method)
{
    return gk_render_gi_failed(r->gi, r, method);
}

/* Whether this frame has a `gi` pass: a method other than none, or a cross-fade still running. */
static bool gi_runs(const gk_renderer *r, const gk_frame_params *fp)
{
    return (fp && fp->method && strcmp(fp->method, "none") != 0) || gk_gi_blend_active(r);
}

/* Runs the GI method as the `gi` pass, with the cross-fade of render_gi_blend.c around it. A method
   that fails is logged once (render_gi.c then skips it until the next scene) and the frame keeps its
   direct light: a kiosk keeps showing something. */

static void pass_gi(gk_renderer *r, const gk_frame_params *fp, const gk_frame_knobs *fk, const gk_pass_ctx *ctx)
{
    const char *method = fp ? fp->method : NULL;
    bool run_method = method && strcmp(method, "none") != 0;
    if (!gi_runs(r, fp))
        return;
    gk_err gi_err = {0};
    gk_pass_begin(ctx, "gi");
    int rc = gk_gi_blend_before_method(r, ctx, fk->gi_blend, &gi_err);
    if (rc != 0)
        gk_log("renderer: GI cross-fade failed, showing the new GI at once: %s", gi_err.msg);
    if (run_method && gk_render_gi_run(r->gi, r, method, ctx, &gi_err) != 0)
        gk_log("renderer: GI method %s failed on scene %s, showing it without GI: %s", method,
               r->scene->name[0] ? r->scene->name : "?", gi_err.msg);
    else if (run_method && rc == 0 && gk_gi_occlusion_apply(r, ctx, &gi_err) != 0)
        gk_log("renderer: the occlusion texture on GI failed, showing GI without it: %s", gi_err.msg);
    if (rc == 0 && gk_gi_blend_after_method(r, ctx, &gi_err) != 0)
        gk_log("renderer: GI cross-fade failed, showing the new GI at once: %s", gi_err.msg);
    gk_pass_end(ctx);
}

/* The GI method's shadow masks for the frame's lights (render_gi.h), inside the direct pass whose
   cost they are (the method's passes nest under `direct`). A method that fails is logged once, as in
   pass_gi, and the lights keep their shadow maps. */
static void gi_shadow_masks(gk_renderer *r, const gk_frame_params *fp, const gk_pass_ctx *ctx, frame_light *fl, int n)
{
    int nodes[64];
    unsigned masks[64];
    for (int i = 0; i < n; i++)
        nodes[i] = fl[i].node;
    gk_err err = {0};
    if (gk_render_gi_shadow_masks(r->gi, r, fp ? fp->method : NULL, ctx, nodes, n, masks, &err) != 0)
        gk_log("renderer: GI method %s failed on scene %s, showing it without GI: %s", fp->method,
               r->scene->name[0] ? r->scene->name : "?", err.msg);
    for (int i = 0; i < n; i++)
        fl[i].mask = masks[i];
}

/* True when fp->stop asks to abandon the frame before pass `next`; *last is the pass that ran last
   and becomes `next` when the frame goes on. */
static bool stop_before(const gk_frame_params *fp, const char *next, const char **last)
{
    if (fp && fp->stop && fp->stop(fp->stop_user, next, *last))
        return true;
    *last = next;
    return false;
}

int gk_renderer_draw(gk_renderer *r, const gk_frame_params *fp, unsigned target_fbo, gk_frame_report *report,
                     gk_err *e)
{
    if (report)
        memset(report, 0, sizeof *report);
    if (!r->scene)
        return gk_fail(e, GK_ERUNTIME, "renderer: draw without a scene");
    const gk_budget *b = fp ? fp->budget : NULL;
    gk_frame_knobs fk;
    gk_render_knobs_read(&r->knobs, b, &fk);
    int w = (int)lroundf((float)r->opts.width * fk.render_scale), h = (int)lroundf((float)r->opts.height * fk.render_scale);
    if (w < 1) w = 1;
    if (h < 1) h = 1;
    /* before the targets may be resized: the last frame's GI is still there to hold (timed: the
       frame's clock starts first) */
    gk_timer_frame_begin(r->timer);
    gk_gi_blend_begin_frame(r, fp ? fp->method : NULL, b, fk.gi_blend);
    if (ensure_targets(r, w, h, e) != 0) {
        gk_frame_report dropped;
        gk_timer_frame_end(r->timer, &dropped); /* closes the hold's passes, if any */
        return -1;
    }
    r->shown = r->hdr.color[0];

    gk_scene *s = r->scene;
    r->time_s = fp ? fp->time_s : 0.0;
    gk_scene_evaluate(s, (float)r->time_s);
    gk_gbuffer_view gb = {
        .albedo = r->gbuf.color[0], .normal = r->gbuf.color[1], .emission = r->gbuf.color[2],
        .depth = r->gbuf.depth, .specular = r->gbuf.color[3], .width = r->render_w, .height = r->render_h,
        .geom_normal = r->gbuf.n_color > 4 ? r->gbuf.color[4] : 0,
    };
    gk_scene_camera(s, (float)r->opts.width / (float)r->opts.height, &gb.view, &gb.proj, &gb.eye);
    gb.view_proj = m4_mul(gb.proj, gb.view);
    gb.inv_view_proj = m4_inverse(gb.view_proj);
    r->have_ran = b != NULL;
    if (b)
        r->ran = *b;
    gk_pass_ctx ctx = {
        .timer = r->timer, .programs = r->progs, .caps = &r->caps, .budget = b, .ran = b ? &r->ran : NULL,
        .scene = s, .gbuffer = &gb,
    };

    frame_light fl[64];
    int n = 0;
    for (int i = 0; i < s->n_nodes && n < 64; i++)
        if (s->nodes[i].light >= 0 && s->nodes[i].light < s->n_lights &&
            gk_render_env_light_on(s, s->nodes[i].light, fk.env_lights))
            fl[n++] = (frame_light){.node = i};

    while (glGetError() != GL_NO_ERROR) {
    }
    /* Each top-level pass asks fp->stop first (stop_before): a stop request abandons the frame
       there. In CPU timing mode every pass ends on a fence, so the pass in flight is all the work
       a stop waits for; with GPU timing the queued GL work of that pass still drains on exit. */
    const char *last = NULL;
    bool abandoned = stop_before(fp, "shadow", &last);
    int rc = 0;
    if (!abandoned) {
        gk_pass_begin(&ctx, "shadow");
        rc = pass_shadows(r, &fk, &ctx, fl, n, gk_render_work_shadow_begin(r), e);
        gk_render_work_shadow_end(r);
        gk_pass_end(&ctx);
    }
    if (rc == 0 && !abandoned && !(abandoned = stop_before(fp, "gbuffer", &last))) {
        gk_pass_begin(&ctx, "gbuffer");
        rc = pass_gbuffer(r, &gb.view_proj, gb.eye, e);
        gk_pass_end(&ctx);
    }
    if (rc == 0 && !abandoned && !(abandoned = stop_before(fp, "direct", &last))) {
        gk_pass_begin(&ctx, "direct");
        gi_shadow_masks(r, fp, &ctx, fl, n);
        rc = pass_direct(r, &fk, fl, n, &gb, e);
        gk_pass_end(&ctx);
    }
    if (rc == 0 && !abandoned && gi_runs(r, fp) && !(abandoned = stop_before(fp, "gi", &last)))
        pass_gi(r, fp, &fk, &ctx);
    if (rc == 0 && !abandoned && gk_render_glass_needed(r) && !(abandoned = stop_before(fp, "glass", &last))) {
        gk_pass_begin(&ctx, "glass");
        rc = gk_render_glass(r, &gb, e);
        gk_pass_end(&ctx);
    }
    if (rc == 0 && !abandoned && gk_render_blend_needed(r) && !(abandoned = stop_before(fp, "blend", &last))) {
        gk_pass_begin(&ctx, "blend");
        rc = gk_render_blend(r, &gb, fk.env_lights, gk_render_work_blend_begin(r), e);
        gk_render_work_blend_end(r);
        gk_pass_end(&ctx);
    }
    if (rc == 0 && !abandoned && !(abandoned = stop_before(fp, "compose", &last))) {
        if (!r->exposure_known)
            measure_exposure(r); /* once per scene, outside every pass: a one-off read-back */
        gk_pass_begin(&ctx, "compose");
        rc = gk_render_compose(r, target_fbo, r->opts.width, r->opts.height, false, gk_render_work_compose_begin(r), e);
        gk_render_work_compose_end(r);
        gk_pass_end(&ctx);
    }
    if (rc == 0 && !abandoned && fp && fp->overlay && !(abandoned = stop_before(fp, "hud", &last))) {
        gk_pass_begin(&ctx, "hud");
        fp->overlay(fp->overlay_user, &ctx, target_fbo);
        gk_pass_end(&ctx);
    }
    gk_frame_report t;
    gk_timer_frame_end(r->timer, &t);
    if (report)
        *report = t;
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
    if (rc != 0)
        return -1;
    if (abandoned) {
        r->have_frame = false; /* the targets hold part of a frame: nothing to capture */
        return GK_FRAME_ABANDONED;
    }
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "renderer: GL error %s during the frame", gk_gl_error_name(err));
    r->have_frame = true;
    return 0;
}
