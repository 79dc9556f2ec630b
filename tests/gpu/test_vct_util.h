/* Helpers shared by the vct GPU tests (tests/gpu/test_vct*.c), on the shared fixture
 * (tests/common/gl_fixture.h: context, targets, scene builders): small in-memory scenes (quads
 * and boxes, one node per object), a test G-buffer rendered with
 * tests/shaders/vct/test/gbuf.*, an RGBA32F HDR target to read the method's contribution back, and
 * one call that renders a frame through gk_gi_vct. Header-only (static functions) because each
 * GPU test is one program. */
#ifndef TEST_VCT_UTIL_H
#define TEST_VCT_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "gi/vct/vct.h"
#include "gl/gl.h"
#include "gl/gl_program.h"

/* ---- context ------------------------------------------------------------------------------- */
typedef struct vt_gl {
    gkt_gl gl;
    gk_program_cache *programs;
} vt_gl;

static inline int vt_gl_init(vt_gl *g)
{
    if (gkt_gl_open(&g->gl) != 0)
        return -1;
    /* #version 310 es: the portable GLES 3.1 path is what is tested; the tests' shader root has
       the method's shaders and the test-only ones (tests/shaders/) */
    g->programs = gkt_programs(31);
    return g->programs ? 0 : -3;
}

static inline void vt_gl_fini(vt_gl *g)
{
    gk_program_cache_destroy(g->programs);
    gkt_gl_close(&g->gl);
}

/* ---- scenes: the shared builder, one node and one material per object ---------------------- */
typedef gkt_scene vt_scene;

static inline void vt_scene_init(vt_scene *v) { gkt_scene_init(v, "vct-test"); }
static inline void vt_scene_free(vt_scene *v) { gkt_scene_free(v); }
/* Bounds and counts after objects were added (node world matrices applied). */
static inline void vt_scene_finish(vt_scene *v) { gkt_scene_bounds(v); }

/* Adds an object made of quads (corner, edge u, edge v each; normal u x v), one node; returns the
   node index. */
static inline int vt_add_quads(vt_scene *v, int nq, const float (*q)[9], vec3 albedo, vec3 emission, bool animated)
{
    gkw_geom geom = {0};
    for (int k = 0; k < nq; k++) {
        vec3 c = v3(q[k][0], q[k][1], q[k][2]), u = v3(q[k][3], q[k][4], q[k][5]), w = v3(q[k][6], q[k][7], q[k][8]);
        gkb_quad(&geom, c, v3_add(c, u), v3_add(v3_add(c, u), w), v3_add(c, w), v3_cross(u, w));
    }
    int mat = gkt_material_lambert(v, albedo);
    v->mats[mat].emissive[0] = emission.x, v->mats[mat].emissive[1] = emission.y, v->mats[mat].emissive[2] = emission.z;
    int n = gkt_object(v, &geom, mat);
    v->nodes[n].animated = animated;
    return n;
}

static inline int vt_add_quad(vt_scene *v, vec3 c, vec3 u, vec3 w, vec3 albedo)
{
    float q[1][9] = {{c.x, c.y, c.z, u.x, u.y, u.z, w.x, w.y, w.z}};
    return vt_add_quads(v, 1, (const float(*)[9])q, albedo, v3(0, 0, 0), false);
}

/* Axis-aligned box [lo, lo + size] with outward faces. */
static inline int vt_add_box(vt_scene *v, vec3 lo, vec3 sz, vec3 albedo, bool animated)
{
    vec3 hi = v3_add(lo, sz);
    float q[6][9] = {
        {lo.x, lo.y, lo.z, 0, 0, sz.z, 0, sz.y, 0}, {hi.x, lo.y, lo.z, 0, sz.y, 0, 0, 0, sz.z},
        {lo.x, lo.y, lo.z, sz.x, 0, 0, 0, 0, sz.z}, {lo.x, hi.y, lo.z, 0, 0, sz.z, sz.x, 0, 0},
        {lo.x, lo.y, lo.z, 0, sz.y, 0, sz.x, 0, 0}, {lo.x, lo.y, hi.z, sz.x, 0, 0, 0, sz.y, 0},
    };
    return vt_add_quads(v, 6, (const float(*)[9])q, albedo, v3(0, 0, 0), animated);
}

/* ---- G-buffer + HDR target ------------------------------------------------------------------ */
/* gbuf: position (RGBA32F, w = window depth; for test masks only), normal (RGBA16F), albedo
   (RGBA8), specular (RGBA8, zero: Lambertian test surfaces, as the analytic answers assume) and
   depth, the renderer's layout (gi.h); hdr: RGBA32F. */
typedef struct vt_frame {
    int w, h;
    gk_target gbuf, hdr;
    mat4 view, proj, view_proj, inv_view_proj;
    vec3 eye;
    bool count_work;   /* frames are the bench's counting frames (gk_gi_frame.count_work) */
} vt_frame;

static const GLenum vt_gbuf_formats[4] = {GL_RGBA32F, GL_RGBA16F, GL_RGBA8, GL_RGBA8};

static inline void vt_frame_create(vt_frame *f, int w, int h, vec3 eye, vec3 target, vec3 up, float yfov)
{
    const GLenum hdr[1] = {GL_RGBA32F};
    memset(f, 0, sizeof *f);
    f->w = w, f->h = h, f->eye = eye;
    gkt_target(&f->gbuf, "test gbuffer", w, h, 4, vt_gbuf_formats, true);
    gkt_target(&f->hdr, "test hdr", w, h, 1, hdr, false);
    f->view = m4_look_at(eye, target, up);
    f->proj = m4_perspective(yfov, (float)w / (float)h, 0.05f, 20.0f);
    f->view_proj = m4_mul(f->proj, f->view);
    f->inv_view_proj = m4_inverse(f->view_proj);
}

static inline void vt_frame_destroy(vt_frame *f)
{
    gk_target_destroy(&f->gbuf);
    gk_target_destroy(&f->hdr);
}

/* Rasterizes the scene (current node matrices) into the G-buffer. */
static inline int vt_gbuffer(vt_gl *g, vt_frame *f, const vt_scene *v)
{
    gk_err e = {0};
    GLuint prog = gk_program_get(g->programs, "vct/test/gbuf.vert", "vct/test/gbuf.frag", NULL, &e);
    if (!prog) {
        fprintf(stderr, "# %s\n", e.msg);
        return -1;
    }
    int nt = (int)v->s.n_triangles;
    float *vb = calloc((size_t)nt * 3 * 9, sizeof(float));
    int k = 0;
    for (int n = 0; n < v->s.n_nodes; n++) {
        const gk_node *nd = &v->nodes[n];
        const gk_mesh *m = &v->meshes[nd->mesh_first];
        const float *alb = v->mats[m->material].base_color;
        for (uint32_t t = 0; t < m->n_triangles * 3; t++, k++) {
            uint32_t i = m->indices[t];
            vec3 p = m4_point(nd->world, v3(m->positions[i * 3], m->positions[i * 3 + 1], m->positions[i * 3 + 2]));
            vec3 nn = v3_norm(m4_dir(nd->world, v3(m->normals[i * 3], m->normals[i * 3 + 1], m->normals[i * 3 + 2])));
            float row[9] = {p.x, p.y, p.z, nn.x, nn.y, nn.z, alb[0], alb[1], alb[2]};
            memcpy(vb + (size_t)k * 9, row, sizeof row);
        }
    }
    GLuint vao, vbo;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)k * 9 * sizeof(float)), vb, GL_STATIC_DRAW);
    for (int a = 0; a < 3; a++) {
        glEnableVertexAttribArray((GLuint)a);
        glVertexAttribPointer((GLuint)a, 3, GL_FLOAT, GL_FALSE, 9 * sizeof(float), (void *)(size_t)(a * 3 * sizeof(float)));
    }
    glBindFramebuffer(GL_FRAMEBUFFER, f->gbuf.fbo);
    GLenum bufs[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glDrawBuffers(4, bufs);
    glViewport(0, 0, f->w, f->h);
    glClearColor(0, 0, 0, 0);
    glClearDepthf(1.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE, f->view_proj.m);
    glUniform3f(glGetUniformLocation(prog, "u_eye"), f->eye.x, f->eye.y, f->eye.z);
    glDrawArrays(GL_TRIANGLES, 0, k);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    free(vb);
    return glGetError() == GL_NO_ERROR ? 0 : -1;
}

/* Point/spot light for gk_gi_frame (no shadow map). */
static inline gk_gi_light vt_light(vt_scene *v, enum gk_light_type type, vec3 pos, vec3 dir, vec3 radiant, float outer)
{
    int i = v->s.n_lights++;
    gk_light *l = &v->lights[i];
    memset(l, 0, sizeof *l);
    l->type = type;
    l->shape = GK_SHAPE_POINT;
    l->color[0] = l->color[1] = l->color[2] = 1;
    l->intensity = 1;
    l->inner_cone = outer * 0.8f;
    l->outer_cone = outer;
    gk_gi_light L;
    memset(&L, 0, sizeof L);
    L.scene_light = i;
    L.node = -1;
    L.position = pos;
    L.direction = v3_norm(dir);
    L.radiant = radiant;
    return L;
}

/* The frame gk_gi_vct is lent for f's G-buffer (untimed: pass NULL). */
static inline gk_gi_frame vt_gi_frame(vt_frame *f, const vt_scene *v, const gk_budget *b, const gk_gi_light *lights,
                                      int n_lights)
{
    gk_gi_frame fr;
    memset(&fr, 0, sizeof fr);
    fr.scene = &v->s;
    fr.width = f->w, fr.height = f->h;
    fr.view = f->view, fr.proj = f->proj, fr.view_proj = f->view_proj, fr.inv_view_proj = f->inv_view_proj;
    fr.eye = f->eye;
    fr.gbuf_depth = f->gbuf.depth, fr.gbuf_normal = f->gbuf.color[1], fr.gbuf_albedo = f->gbuf.color[2];
    fr.gbuf_specular = f->gbuf.color[3];
    /* the renderer's layout (gi.h): positions from depth, metallic/roughness in albedo.a/normal.w */
    fr.hdr_fbo = f->hdr.fbo;
    fr.n_lights = n_lights;
    fr.lights = lights;
    fr.budget = b;
    fr.count_work = f->count_work;
    return fr;
}

/* Renders one frame through gk_gi_vct into a cleared HDR target and reads it back (RGBA floats). */
static inline int vt_render(void *vct, vt_frame *f, const vt_scene *v, const gk_budget *b, const gk_gi_light *lights,
                     int n_lights, float *out_rgba, gk_frame_report *report)
{
    gk_gi_frame fr = vt_gi_frame(f, v, b, lights, n_lights);
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr.fbo);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gk_err e = {0};
    /* With a report wanted, the method's passes run on a timer of their own (as the renderer's
       clock would time them: CPU time around a fence on llvmpipe). */
    gk_timer *timer = report ? gk_timer_create(false) : NULL;
    gk_pass_ctx ctx = {.timer = timer, .budget = b, .scene = &v->s};
    fr.pass = &ctx;
    if (timer)
        gk_timer_frame_begin(timer);
    int rc = gk_gi_vct.render(vct, &fr, &e);
    if (timer) {
        gk_timer_frame_end(timer, report);
        gk_timer_destroy(timer);
    }
    if (rc != 0) {
        fprintf(stderr, "# vct render: %s\n", e.msg);
        return -1;
    }
    if (out_rgba)
        gkt_read_rgba(&f->hdr, 0, GL_FLOAT, out_rgba);
    return glGetError() == GL_NO_ERROR ? 0 : -1;
}

/* Reads the G-buffer positions (RGBA32F: xyz world, w window depth, 0 where nothing) for masks. */
static inline void vt_read_positions(vt_frame *f, float *out_rgba)
{
    gkt_read_rgba(&f->gbuf, 0, GL_FLOAT, out_rgba);
}

/* A budget with the vct knobs at the given values (strings as on the command line). */
static inline void vt_budget(gk_budget *b, const char *pins)
{
    gk_budget_init(b);
    gk_gi_vct.declare_knobs(b);
    gk_err e = {0};
    if (pins && gk_budget_pin_list(b, pins, &e) != 0)
        fprintf(stderr, "# budget: %s\n", e.msg);
}

static inline void *vt_create(vt_gl *g)
{
    gk_gi_context ctx = {.programs = g->programs, .gles_version = 31};
    gk_err e = {0};
    void *v = gk_gi_vct.create(&ctx, &e);
    if (!v)
        fprintf(stderr, "# vct create: %s\n", e.msg);
    return v;
}

/* Copies the whole scratch buffer (res^3 x channels uints) into a malloc'd array. */
static inline unsigned *vt_read_scratch(void *vct, long *n_out)
{
    GLint64 size = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, gk_vct_scratch_buffer(vct));
    glGetBufferParameteri64v(GL_SHADER_STORAGE_BUFFER, GL_BUFFER_SIZE, &size);
    unsigned *out = malloc((size_t)size);
    const void *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)size, GL_MAP_READ_BIT);
    if (p && out)
        memcpy(out, p, (size_t)size);
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    *n_out = (long)(size / 4);
    return out;
}

/* Copies the level-0 radiance texture (RGBA16F, res^3) into a malloc'd array of RGBA floats, x fastest. */
static inline float *vt_read_radiance(void *vct, int res)
{
    float *out = malloc(sizeof(float) * 4 * (size_t)res * res * res);
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    for (int z = 0; out && z < res; z++) {
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, gk_vct_radiance_texture(vct), 0, z);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glReadPixels(0, 0, res, res, GL_RGBA, GL_FLOAT, out + (size_t)z * res * res * 4);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    return out;
}

static inline float vt_lum(const float *p) { return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]; }

#endif
