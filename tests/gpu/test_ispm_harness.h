/* Shared set-up of the ispm GPU tests (included by tests/gpu/test_ispm_*.c; not a program itself):
 * a scene (built with the shared fixture's builders or loaded from config/scenes), the renderer's
 * own G-buffer shader, and one call that runs the ispm method for a frame and reads back what it
 * added to the HDR image. The camera and the first light come from the scene. */
#ifndef TEST_ISPM_HARNESS_H
#define TEST_ISPM_HARNESS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "gi/ispm/ispm.h"
#include "gl/gl_program.h"
#include "gl/gl_target.h"
#include "render/scene_gpu.h"

typedef struct ispm_h {
    gkt_gl gl;
    gk_program_cache *programs;
    gk_scene *scene;
    gk_scene_gpu gpu;
    bool have_gpu;
    gk_target gbuf, hdr;
    int w, h;
    mat4 view, proj, vp, inv_vp;
    vec3 eye;
    gk_gi_light light;
    gk_budget budget;
    void *self;
    float *img;          /* w*h*4: what the method added to the HDR image this frame */
    float *albedo;       /* w*h*4 G-buffer albedo (rgb) + metallic */
    float *normal;       /* w*h*4 G-buffer normal + roughness */
    bool count_work;     /* frames are the bench's counting frames (gk_gi_frame.count_work) */
} ispm_h;

static inline int ih_draw_scene(void *ctx, unsigned prog, gk_err *e)
{
    ispm_h *h = ctx;
    (void)e;
    gk_draw_uniforms u;
    gk_draw_uniforms_lookup(prog, &u);
    gk_scene_gpu_draw(&h->gpu, h->scene, &u, GK_DRAW_MATERIALS);
    return 0;
}

/* The G-buffer of the scene's camera (again after the scene or the camera moved). */
static inline int ih_gbuffer(ispm_h *h)
{
    gk_err e = {0};
    gk_scene_evaluate(h->scene, 0.0f);
    gk_scene_camera(h->scene, (float)h->w / (float)h->h, &h->view, &h->proj, &h->eye);
    h->vp = m4_mul(h->proj, h->view);
    h->inv_vp = m4_inverse(h->vp);
    for (int i = 0; i < h->scene->n_nodes; i++)
        if (h->scene->nodes[i].light >= 0) {
            const gk_light *L = &h->scene->lights[h->scene->nodes[i].light];
            h->light.scene_light = h->scene->nodes[i].light, h->light.node = i;
            gk_scene_light_frame(h->scene, i, &h->light.position, &h->light.direction, &h->light.axis_u,
                                 &h->light.axis_v);
            h->light.radiant = v3(L->color[0] * L->intensity, L->color[1] * L->intensity, L->color[2] * L->intensity);
            break;
        }
    /* the geometry is uploaded once (tests that change it reopen the harness) */
    if (!h->have_gpu && gk_scene_gpu_upload(&h->gpu, h->scene, &e)) {
        fprintf(stderr, "upload: %s\n", e.msg);
        return -1;
    }
    h->have_gpu = true;
    GLuint gp = gk_program_get(h->programs, "gbuffer/gbuffer.vert", "gbuffer/gbuffer.frag", NULL, &e);
    if (!gp) {
        fprintf(stderr, "gbuffer: %s\n", e.msg);
        return -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, h->gbuf.fbo);
    const GLenum b4[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glDrawBuffers(4, b4);
    glViewport(0, 0, h->w, h->h);
    glClearColor(0, 0, 0, 0);
    glClearDepthf(1);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(gp);
    gk_uniform_mat4(gp, "u_viewproj", h->vp.m);
    gk_uniform_3f(gp, "u_eye", h->eye.x, h->eye.y, h->eye.z);
    gk_draw_uniforms du;
    gk_draw_uniforms_lookup(gp, &du);
    gk_scene_gpu_draw(&h->gpu, h->scene, &du, GK_DRAW_MATERIALS);
    glDisable(GL_DEPTH_TEST);
    unsigned char *a8 = malloc((size_t)h->w * h->h * 4);
    gkt_read_rgba(&h->gbuf, 0, GL_UNSIGNED_BYTE, a8);   /* RGBA8 reads only as bytes */
    for (int i = 0; i < h->w * h->h * 4; i++)
        h->albedo[i] = a8[i] / 255.0f;
    free(a8);
    gkt_read_rgba(&h->gbuf, 1, GL_FLOAT, h->normal);
    return 0;
}

/* scene: evaluated or not; the harness owns it only for h_close's gk_scene_free when owned. */
static inline int ih_open(ispm_h *h, gk_scene *scene, int w, int hh)
{
    memset(h, 0, sizeof *h);
    gk_err e = {0};
    if (gkt_gl_open(&h->gl) != 0)
        return -1;
    h->programs = gk_program_cache_create(NULL, h->gl.egl.gles_version);
    h->scene = scene;
    h->w = w, h->h = hh;
    const GLenum gb[4] = {GL_RGBA8, GL_RGBA16F, GL_RGBA16F, GL_RGBA8}; /* the renderer's layout */
    const GLenum hf[1] = {GL_RGBA32F};
    if (gkt_target(&h->gbuf, "test gbuffer", w, hh, 4, gb, true) || gkt_target(&h->hdr, "test hdr", w, hh, 1, hf, false))
        return -1;
    h->img = malloc((size_t)w * hh * 4 * sizeof(float));
    h->albedo = malloc((size_t)w * hh * 4 * sizeof(float));
    h->normal = malloc((size_t)w * hh * 4 * sizeof(float));
    if (ih_gbuffer(h))
        return -1;
    gk_budget_init(&h->budget);
    gk_gi_ispm.declare_knobs(&h->budget);
    gk_gi_context ctx = {.programs = h->programs, .gles_version = h->gl.egl.gles_version};
    h->self = gk_gi_ispm.create(&ctx, &e);
    if (!h->self || gk_gi_ispm.set_scene(h->self, scene, &e)) {
        fprintf(stderr, "ispm: %s\n", e.msg);
        return -1;
    }
    return 0;
}

/* "ispm_photons=4096,..." pinned on the harness budget (the rest at their defaults). */
static inline int ih_budget(ispm_h *h, const char *list)
{
    gk_err e = {0};
    gk_budget_init(&h->budget);
    gk_gi_ispm.declare_knobs(&h->budget);
    if (list && gk_budget_pin_list(&h->budget, list, &e)) {
        fprintf(stderr, "budget: %s\n", e.msg);
        return -1;
    }
    return 0;
}

/* debug edits on the defaults; caustics_only and measure are always on in the tests unless edit
   turns them off */
static inline void ih_debug(ispm_h *h, void (*edit)(gk_ispm_debug *))
{
    gk_ispm_debug d;
    gk_ispm_default_debug(&d);
    d.caustics_only = true, d.measure = true;
    if (edit)
        edit(&d);
    gk_ispm_set_debug(h->self, &d);
}

/* One frame of a GI method on the harness's scene and G-buffer (the ispm tests: ih_frame): what it
   added lands in h->img. */
static inline int ih_frame_of(ispm_h *h, const gk_gi_method *m, void *self)
{
    gk_gi_frame f = {0};
    f.scene = h->scene, f.width = h->w, f.height = h->h;
    f.view = h->view, f.proj = h->proj, f.view_proj = h->vp, f.inv_view_proj = h->inv_vp, f.eye = h->eye;
    f.gbuf_albedo = h->gbuf.color[0], f.gbuf_normal = h->gbuf.color[1], f.gbuf_emission = h->gbuf.color[2];
    f.gbuf_depth = h->gbuf.depth;
    f.gbuf_specular = h->gbuf.color[3];
    f.hdr_fbo = h->hdr.fbo;
    f.n_lights = 1, f.lights = &h->light, f.budget = &h->budget;
    f.draw_scene = ih_draw_scene, f.draw_ctx = h;
    f.count_work = h->count_work;
    glBindFramebuffer(GL_FRAMEBUFFER, h->hdr.fbo);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, b1);
    glViewport(0, 0, h->w, h->h);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    gk_err e = {0};
    if (m->render(self, &f, &e)) {
        fprintf(stderr, "render: %s\n", e.msg);
        return -1;
    }
    gkt_read_rgba(&h->hdr, 0, GL_FLOAT, h->img);
    return glGetError() == GL_NO_ERROR ? 0 : -1;
}

/* One frame of the method: what it added lands in h->img. */
static inline int ih_frame(ispm_h *h) { return ih_frame_of(h, &gk_gi_ispm, h->self); }

static inline double ih_lum(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

/* Where the ray of pixel (x, y) (its centre) meets the plane y = y0; false when it does not. */
static inline bool ih_on_plane_y(const ispm_h *h, int x, int y, float y0, vec3 *out)
{
    float nx = ((float)x + 0.5f) / (float)h->w * 2 - 1, ny = ((float)y + 0.5f) / (float)h->h * 2 - 1;
    vec4 a = m4_vec4(h->inv_vp, (vec4){nx, ny, -1, 1}), b = m4_vec4(h->inv_vp, (vec4){nx, ny, 1, 1});
    vec3 pa = v3(a.x / a.w, a.y / a.w, a.z / a.w), pb = v3(b.x / b.w, b.y / b.w, b.z / b.w);
    if (fabsf(pb.y - pa.y) < 1e-9f)
        return false;
    float t = (y0 - pa.y) / (pb.y - pa.y);
    if (t <= 0.0f)
        return false;
    *out = v3_lerp(pa, pb, t);
    return true;
}

/* The G-buffer sees an upward-facing non-metal surface at pixel i (a floor, not a mirror rim). */
static inline bool ih_floor_pixel(const ispm_h *h, int i)
{
    return h->normal[i * 4 + 1] > 0.99f && h->albedo[i * 4 + 3] < 0.5f && h->albedo[i * 4] > 0.0f;
}

static inline void ih_close(ispm_h *h)
{
    if (h->self)
        gk_gi_ispm.destroy(h->self);
    gk_target_destroy(&h->gbuf);
    gk_target_destroy(&h->hdr);
    if (h->have_gpu)
        gk_scene_gpu_free(&h->gpu);
    gk_program_cache_destroy(h->programs);
    free(h->img);
    free(h->albedo);
    free(h->normal);
    gkt_gl_close(&h->gl);
}

/* A test group's fixture on a scene built in memory (tests/common/gl_fixture.h): the harness opened
   on it with the tests' debug settings; closed, and the scene freed. */
static inline int ih_open_built(ispm_h *h, gkt_scene *t, int w, int hh)
{
    if (ih_open(h, &t->s, w, hh))
        return -1;
    ih_debug(h, NULL);
    return 0;
}

static inline void ih_close_built(ispm_h *h, gkt_scene *t)
{
    ih_close(h);
    gkt_scene_free(t);
}

#endif
