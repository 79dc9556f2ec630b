/* Shared set-up of the vpl GPU tests (included by tests/gpu/test_vpl_*.c; not a program itself):
 * on the shared fixture (tests/common/gl_fixture.h: context, targets, scene builders) the T5 "Cornell corner" scene of dong-001.md §9.2 built in memory
 * (unit box, one-sided walls ρ = 0.75 grey, red left, green right, two cuboids, a 30° spot aimed at
 * the corner (0,0,0) from (0.5, 0.95, 0.9)), the renderer's own G-buffer shader and scene upload,
 * and one call that runs the vpl method for a frame and reads back the indirect radiance it adds. */
#ifndef TEST_VPL_HARNESS_H
#define TEST_VPL_HARNESS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "gi/vpl/vpl.h"
#include "gl/gl_program.h"
#include "gl/gl_target.h"
#include "render/scene_gpu.h"

typedef struct vpl_h {
    gkt_gl gl;
    gk_program_cache *programs;
    gkt_scene box;       /* the built-in Cornell corner (shared scene builders) */
    gk_scene scene;      /* box.s, or the external scene */
    gk_scene_gpu gpu;
    gk_target gbuf, hdr;
    int w, h;
    mat4 view, proj, vp, inv_vp;
    vec3 eye;
    gk_gi_light gl_light;
    gk_budget budget;
    const gk_gi_method *m;
    void *self;
    float *img;          /* w*h*4 indirect radiance of the last frame */
    gk_frame_report times; /* the method's pass timings of the last frame */
    bool count_work;     /* frames are the bench's counting frames (gk_gi_frame.count_work) */
} vpl_h;

static inline int h_draw_scene(void *ctx, unsigned prog, gk_err *e)
{
    vpl_h *h = ctx;
    (void)e;
    gk_draw_uniforms u;
    gk_draw_uniforms_lookup(prog, &u);
    gk_scene_gpu_draw(&h->gpu, &h->scene, &u, GK_DRAW_MATERIALS);
    return 0;
}

/* Points the spot at target (world) and refreshes the frame's light. */
static inline void h_aim(vpl_h *h, vec3 target)
{
    h->gl_light.position = v3(0.5f, 0.95f, 0.9f);
    h->gl_light.direction = v3_norm(v3_sub(target, h->gl_light.position));
    h->gl_light.axis_u = v3(1, 0, 0);
    h->gl_light.axis_v = v3(0, 1, 0);
}

static inline int h_init_with(vpl_h *h, bool with_boxes, int w, int hh, gk_scene *external);

/* with_boxes: the two cuboids of T5; w×h: render size. Returns 0 or prints why not. */
static inline int h_init(vpl_h *h, bool with_boxes, int w, int hh)
{
    return h_init_with(h, with_boxes, w, hh, NULL);
}

/* external: a loaded scene (camera and first light from it) instead of the built-in box. */
static inline int h_init_with(vpl_h *h, bool with_boxes, int w, int hh, gk_scene *external)
{
    memset(h, 0, sizeof *h);
    gk_err e = {0};
    if (gkt_gl_open(&h->gl) != 0)
        return -1;
    h->programs = gk_program_cache_create(NULL, h->gl.egl.gles_version);
    gkt_scene *b = &h->box;
    gkt_scene_init(b, "vpl-cornell-corner");
    /* Lambertian, as the Cornell box (the tests' analytic one-bounce answers use rho / pi) */
    int grey = gkt_material_lambert(b, v3(0.75f, 0.75f, 0.75f)), red = gkt_material_lambert(b, v3(0.75f, 0.1f, 0.1f)),
        green = gkt_material_lambert(b, v3(0.1f, 0.75f, 0.1f));
    /* one-sided walls facing into the unit box */
    gkt_quad(b, v3(0, 0, 0), v3(1, 0, 0), v3(1, 0, 1), v3(0, 0, 1), v3(0, 1, 0), grey);   /* floor */
    gkt_quad(b, v3(0, 1, 0), v3(1, 1, 0), v3(1, 1, 1), v3(0, 1, 1), v3(0, -1, 0), grey);  /* ceiling */
    gkt_quad(b, v3(0, 0, 0), v3(1, 0, 0), v3(1, 1, 0), v3(0, 1, 0), v3(0, 0, 1), grey);   /* back */
    gkt_quad(b, v3(0, 0, 0), v3(0, 1, 0), v3(0, 1, 1), v3(0, 0, 1), v3(1, 0, 0), red);    /* left */
    gkt_quad(b, v3(1, 0, 0), v3(1, 1, 0), v3(1, 1, 1), v3(1, 0, 1), v3(-1, 0, 0), green); /* right */
    if (with_boxes) {
        gkw_geom g = {0};
        gkb_box(&g, v3(0.3f, 0, 0.35f), v3(0.6f, 0.6f, 0.65f), false);
        gkt_object(b, &g, grey);
        gkb_box(&g, v3(0.6f, 0, 0.45f), v3(0.9f, 0.3f, 0.75f), false);
        gkt_object(b, &g, grey);
    }
    b->s.bmin = v3(0, 0, 0), b->s.bmax = v3(1, 1, 1);
    /* the spot: a light of the scene without a node (h_aim places it) */
    gk_light *L0 = &b->lights[b->s.n_lights++];
    L0->type = GK_LIGHT_SPOT, L0->shape = GK_SHAPE_POINT;
    L0->color[0] = L0->color[1] = L0->color[2] = 1;
    L0->intensity = 2.0f;
    L0->inner_cone = 25.0f * 3.14159265f / 180.0f, L0->outer_cone = 30.0f * 3.14159265f / 180.0f;
    gk_scene *s = &h->scene;
    *s = external ? *external : b->s;
    if (gk_scene_gpu_upload(&h->gpu, s, &e)) {
        fprintf(stderr, "upload: %s\n", e.msg);
        return -1;
    }
    h->w = w, h->h = hh;
    const GLenum gb[4] = {GL_RGBA8, GL_RGBA16F, GL_RGBA16F, GL_RGBA8}; /* the renderer's layout */
    const GLenum hf[1] = {GL_RGBA32F};
    if (gkt_target(&h->gbuf, "test gbuffer", w, hh, 4, gb, true) || gkt_target(&h->hdr, "test hdr", w, hh, 1, hf, false))
        return -1;
    h->eye = v3(0.5f, 0.5f, 0.98f);
    h->view = m4_look_at(h->eye, v3(0.5f, 0.5f, 0.0f), v3(0, 1, 0));
    h->proj = m4_perspective(70.0f * 3.14159265f / 180.0f, (float)w / (float)hh, 0.01f, 5.0f);
    if (external)
        gk_scene_camera(s, (float)w / (float)hh, &h->view, &h->proj, &h->eye);
    h->vp = m4_mul(h->proj, h->view);
    h->inv_vp = m4_inverse(h->vp);
    h->gl_light.scene_light = 0, h->gl_light.node = -1;
    h->gl_light.radiant = v3(L0->intensity, L0->intensity, L0->intensity);
    h_aim(h, v3(0, 0, 0));
    if (external) {
        for (int i = 0; i < s->n_nodes; i++)
            if (s->nodes[i].light >= 0) {
                const gk_light *L = &s->lights[s->nodes[i].light];
                h->gl_light.scene_light = s->nodes[i].light, h->gl_light.node = i;
                gk_scene_light_frame(s, i, &h->gl_light.position, &h->gl_light.direction, &h->gl_light.axis_u,
                                     &h->gl_light.axis_v);
                h->gl_light.radiant = v3(L->color[0] * L->intensity, L->color[1] * L->intensity,
                                         L->color[2] * L->intensity);
                break;
            }
    }
    h->img = malloc((size_t)w * hh * 4 * sizeof(float));
    gk_budget_init(&h->budget);
    h->m = &gk_gi_vpl;
    h->m->declare_knobs(&h->budget);
    gk_gi_context ctx = {.programs = h->programs, .gles_version = h->gl.egl.gles_version};
    h->self = h->m->create(&ctx, &e);
    if (!h->self || h->m->set_scene(h->self, s, &e)) {
        fprintf(stderr, "vpl: %s\n", e.msg);
        return -1;
    }
    /* G-buffer once: the camera and geometry are static in every test. */
    GLuint gp = gk_program_get(h->programs, "gbuffer/gbuffer.vert", "gbuffer/gbuffer.frag", NULL, &e);
    if (!gp) {
        fprintf(stderr, "gbuffer: %s\n", e.msg);
        return -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, h->gbuf.fbo);
    const GLenum b4[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glDrawBuffers(4, b4);
    glViewport(0, 0, w, hh);
    glClearColor(0, 0, 0, 0);
    glClearDepthf(1);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(gp);
    gk_uniform_mat4(gp, "u_viewproj", h->vp.m);
    gk_uniform_3f(gp, "u_eye", h->eye.x, h->eye.y, h->eye.z);
    gk_draw_uniforms du;
    gk_draw_uniforms_lookup(gp, &du);
    gk_scene_gpu_draw(&h->gpu, s, &du, GK_DRAW_MATERIALS);
    glDisable(GL_DEPTH_TEST);
    return 0;
}

/* "vpl_n=256,vpl_m=8,..." pinned on the harness budget. */
static inline int h_budget(vpl_h *h, const char *list)
{
    gk_err e = {0};
    gk_budget_init(&h->budget);
    h->m->declare_knobs(&h->budget);
    if (gk_budget_pin_list(&h->budget, list, &e)) {
        fprintf(stderr, "budget: %s\n", e.msg);
        return -1;
    }
    return 0;
}

/* One frame of the method; the indirect radiance it added lands in h->img. */
static inline int h_frame(vpl_h *h, double t)
{
    gk_gi_frame f = {0};
    f.scene = &h->scene, f.time_s = t, f.width = h->w, f.height = h->h;
    f.view = h->view, f.proj = h->proj, f.view_proj = h->vp, f.inv_view_proj = h->inv_vp, f.eye = h->eye;
    f.gbuf_albedo = h->gbuf.color[0], f.gbuf_normal = h->gbuf.color[1], f.gbuf_depth = h->gbuf.depth;
    f.gbuf_specular = h->gbuf.color[3];
    f.hdr_fbo = h->hdr.fbo;
    f.n_lights = 1, f.lights = &h->gl_light, f.budget = &h->budget;
    f.draw_scene = h_draw_scene, f.draw_ctx = h;
    f.count_work = h->count_work;
    glBindFramebuffer(GL_FRAMEBUFFER, h->hdr.fbo);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, b1);
    glViewport(0, 0, h->w, h->h);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    gk_err e = {0};
    gk_timer *timer = gk_timer_create(false); /* the renderer's clock, as it would time the passes */
    gk_pass_ctx ctx = {.timer = timer, .budget = &h->budget};
    f.pass = &ctx;
    gk_timer_frame_begin(timer);
    int rc = h->m->render(h->self, &f, &e);
    gk_timer_frame_end(timer, &h->times);
    gk_timer_destroy(timer);
    if (rc) {
        fprintf(stderr, "render: %s\n", e.msg);
        return -1;
    }
    gkt_read_rgba(&h->hdr, 0, GL_FLOAT, h->img);
    return glGetError() == GL_NO_ERROR ? 0 : -1;
}

static inline double h_lum(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

static inline double h_mean(const float *img, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += h_lum(&img[i * 4]);
    return s / n;
}

/* Relative RMSE of a against b (luminance), as `gikiosk compare` defines it. */
static inline double h_rel_rmse(const float *a, const float *b, int n)
{
    double se = 0, mb = h_mean(b, n);
    for (int i = 0; i < n; i++) {
        double d = h_lum(&a[i * 4]) - h_lum(&b[i * 4]);
        se += d * d;
    }
    return sqrt(se / n) / (mb > 0 ? mb : 1);
}

static inline void h_set_debug(vpl_h *h, void (*edit)(gk_vpl_debug *))
{
    gk_vpl_debug d;
    gk_vpl_default_debug(&d);
    if (edit)
        edit(&d);
    gk_vpl_set_debug(h->self, &d);
}

static inline void h_free(vpl_h *h)
{
    if (h->self)
        h->m->destroy(h->self);
    gk_target_destroy(&h->gbuf);
    gk_target_destroy(&h->hdr);
    gk_scene_gpu_free(&h->gpu);
    gk_program_cache_destroy(h->programs);
    gkt_scene_free(&h->box);
    free(h->img);
    gkt_gl_close(&h->gl);
}

/* The fixture most vpl tests share: one harness H over the box with its blocks at W x HH = 64 x 64,
 * set up once for the group (cmocka_run_group_tests(tests, setup, teardown)). */
#define VPL_H_BOX_GROUP                                                                                          \
    static vpl_h H;                                                                                              \
    enum { W = 64, HH = 64 };                                                                                    \
    static int setup(void **state)                                                                               \
    {                                                                                                            \
        (void)state;                                                                                             \
        return h_init(&H, true, W, HH);                                                                          \
    }                                                                                                            \
    static int teardown(void **state)                                                                            \
    {                                                                                                            \
        (void)state;                                                                                             \
        h_free(&H);                                                                                              \
        return 0;                                                                                                \
    }

#endif
