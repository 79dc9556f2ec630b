/* Shared by tests/gpu/test_render*.c (header-only, no main): an EGL surfaceless GLES context,
 * hand-built scenes of quads and lights (no glTF files, so the tests pin exactly the geometry the
 * analytic answers assume), a renderer drawing into a small FBO, and an independent C version
 * of the BRDF (app/core/brdf_spec.md) and of the Lambert polygon irradiance. */
#ifndef TEST_RENDER_FIXTURE_H
#define TEST_RENDER_FIXTURE_H

#include "platform/egl.h"
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl32.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/image_io.h"
#include "render/renderer.h"
#include "scene/scene.h"

#define FX_MAX 8
#define FX_PI 3.14159265358979

typedef struct fx_quad_data {
    float pos[12], nrm[12], uv[8];
    uint32_t idx[6];
} fx_quad_data;

typedef struct fx_scene {
    gk_scene s;
    gk_mesh meshes[FX_MAX];
    fx_quad_data quads[FX_MAX];
    gk_material mats[FX_MAX];
    gk_light lights[FX_MAX];
    gk_node nodes[2 * FX_MAX];
    gk_camera cam;
} fx_scene;

typedef struct fx_gl {
    EGLDisplay dpy;
    EGLContext ctx;
    GLuint fbo, color;
    int w, h;
} fx_gl;

static inline int fx_gl_open(fx_gl *g, int w, int h)
{
    memset(g, 0, sizeof *g);
    g->dpy = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (g->dpy == EGL_NO_DISPLAY || !gk_egl_initialize(g->dpy, NULL, NULL) || !eglBindAPI(EGL_OPENGL_ES_API))
        return -1;
    EGLint ca[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2, EGL_NONE};
    g->ctx = eglCreateContext(g->dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ca);
    if (g->ctx == EGL_NO_CONTEXT || !eglMakeCurrent(g->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, g->ctx))
        return -2;
    g->w = w;
    g->h = h;
    glGenTextures(1, &g->color);
    glBindTexture(GL_TEXTURE_2D, g->color);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w, h);
    glGenFramebuffers(1, &g->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, g->color, 0);
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? 0 : -3;
}

static inline void fx_gl_close(fx_gl *g)
{
    glDeleteFramebuffers(1, &g->fbo);
    glDeleteTextures(1, &g->color);
    eglMakeCurrent(g->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(g->dpy, g->ctx);
    eglTerminate(g->dpy);
}

/* Rotation taking (0,0,-1) to dir, keeping x as close to world x as possible (quaternion). */
static inline quat fx_quat_from_axes(vec3 x, vec3 y, vec3 z)
{
    float m00 = x.x, m11 = y.y, m22 = z.z, tr = m00 + m11 + m22;
    quat q;
    if (tr > 0) {
        float s = sqrtf(tr + 1.0f) * 2;
        q = (quat){(y.z - z.y) / s, (z.x - x.z) / s, (x.y - y.x) / s, 0.25f * s};
    } else if (m00 > m11 && m00 > m22) {
        float s = sqrtf(1.0f + m00 - m11 - m22) * 2;
        q = (quat){0.25f * s, (y.x + x.y) / s, (z.x + x.z) / s, (y.z - z.y) / s};
    } else if (m11 > m22) {
        float s = sqrtf(1.0f + m11 - m00 - m22) * 2;
        q = (quat){(y.x + x.y) / s, 0.25f * s, (z.y + y.z) / s, (z.x - x.z) / s};
    } else {
        float s = sqrtf(1.0f + m22 - m00 - m11) * 2;
        q = (quat){(z.x + x.z) / s, (z.y + y.z) / s, 0.25f * s, (x.y - y.x) / s};
    }
    return q_normalize(q);
}

static inline quat fx_look_rotation(vec3 dir)
{
    vec3 z = v3_norm(v3_scale(dir, -1.0f));
    vec3 up = fabsf(z.y) > 0.99f ? v3(0, 0, -1) : v3(0, 1, 0);
    vec3 x = v3_norm(v3_cross(up, z));
    vec3 y = v3_cross(z, x);
    return fx_quat_from_axes(x, y, z);
}

static inline int fx_add_node(fx_scene *f)
{
    gk_node *n = &f->nodes[f->s.n_nodes];
    memset(n, 0, sizeof *n);
    n->parent = -1;
    n->rotation = (quat){0, 0, 0, 1};
    n->scale = v3(1, 1, 1);
    n->light = n->camera = -1;
    return f->s.n_nodes++;
}

static inline void fx_init(fx_scene *f, vec3 eye, vec3 target, float yfov)
{
    memset(f, 0, sizeof *f);
    f->s.meshes = f->meshes;
    f->s.materials = f->mats;
    f->s.lights = f->lights;
    f->s.nodes = f->nodes;
    f->s.cameras = &f->cam;
    f->s.n_cameras = 1;
    snprintf(f->s.name, sizeof f->s.name, "fixture");
    snprintf(f->s.path, sizeof f->s.path, "(test fixture)");
    f->cam = (gk_camera){.yfov = yfov, .aspect = 0, .znear = 0.05f, .zfar = 50.0f};
    int c = fx_add_node(f);
    f->nodes[c].camera = 0;
    f->nodes[c].translation = eye;
    f->nodes[c].rotation = fx_look_rotation(v3_sub(target, eye));
    f->s.camera_node = c;
    f->s.bmin = v3(-4, -1, -4);
    f->s.bmax = v3(4, 3, 4);
}

static inline int fx_material(fx_scene *f, float rho, float metallic, float roughness)
{
    gk_material *m = &f->mats[f->s.n_materials];
    memset(m, 0, sizeof *m);
    m->base_color[0] = m->base_color[1] = m->base_color[2] = rho;
    m->base_color[3] = 1;
    m->base_color_tex = m->metallic_roughness_tex = -1;
    m->metallic = metallic;
    m->roughness = roughness;
    m->ior = 1.5f;
    return f->s.n_materials++;
}

/* A horizontal quad (normal +y) from (x0, y, z0) to (x1, y, z1). */
static inline void fx_quad(fx_scene *f, float x0, float x1, float z0, float z1, float y, int material)
{
    int k = f->s.n_meshes++;
    fx_quad_data *q = &f->quads[k];
    const float p[12] = {x0, y, z0, x1, y, z0, x1, y, z1, x0, y, z1};
    memcpy(q->pos, p, sizeof p);
    for (int i = 0; i < 4; i++) {
        q->nrm[3 * i] = 0, q->nrm[3 * i + 1] = 1, q->nrm[3 * i + 2] = 0;
        q->uv[2 * i] = (float)(i == 1 || i == 2), q->uv[2 * i + 1] = (float)(i >= 2);
    }
    const uint32_t idx[6] = {0, 2, 1, 0, 3, 2}; /* counter-clockwise seen from +y */
    memcpy(q->idx, idx, sizeof idx);
    gk_mesh *m = &f->meshes[k];
    memset(m, 0, sizeof *m);
    m->positions = q->pos;
    m->normals = q->nrm;
    m->uvs = q->uv;
    m->indices = q->idx;
    m->n_vertices = 4;
    m->n_triangles = 2;
    m->material = material;
    m->bmin = v3(x0, y, z0);
    m->bmax = v3(x1, y, z1);
    int n = fx_add_node(f);
    f->nodes[n].mesh_first = k;
    f->nodes[n].mesh_count = 1;
    f->s.n_triangles += 2;
}

static inline gk_light *fx_light(fx_scene *f, enum gk_light_type type, enum gk_light_shape shape, float intensity, vec3 pos,
                          vec3 dir)
{
    int i = f->s.n_lights++;
    gk_light *l = &f->lights[i];
    memset(l, 0, sizeof *l);
    l->type = type;
    l->shape = shape;
    l->color[0] = l->color[1] = l->color[2] = 1;
    l->intensity = intensity;
    l->outer_cone = 0.785398f;
    int n = fx_add_node(f);
    f->nodes[n].light = i;
    f->nodes[n].translation = pos;
    f->nodes[n].rotation = fx_look_rotation(dir);
    return l;
}

/* Renders one frame with the given knobs (NULL: defaults) and reads the linear image back. */
static inline int fx_render(fx_gl *g, fx_scene *f, int gles, const char *budget, gk_image *out, gk_err *e)
{
    gk_render_opts o = {.width = g->w, .height = g->h, .gles_version = gles, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, e);
    if (!r)
        return -1;
    gk_budget b;
    gk_budget_init(&b);
    gk_renderer_declare_knobs(r, &b);
    int rc = budget ? gk_budget_pin_list(&b, budget, e) : 0;
    gk_frame_params fp = {.time_s = 0, .method = "none", .budget = &b};
    gk_frame_report t;
    if (rc == 0)
        rc = gk_renderer_set_scene(r, &f->s, e);
    if (rc == 0)
        rc = gk_renderer_draw(r, &fp, g->fbo, &t, e);
    if (rc == 0)
        rc = gk_renderer_read_linear(r, out, e);
    gk_renderer_destroy(r);
    return rc;
}

/* The world point on the plane y = plane_y seen through pixel (x, y) (top row first). */
static inline int fx_pixel_on_plane(fx_scene *f, int w, int h, int x, int y, float plane_y, vec3 *p, vec3 *eye_out)
{
    mat4 view, proj;
    vec3 eye;
    gk_scene_evaluate(&f->s, 0);
    gk_scene_camera(&f->s, (float)w / (float)h, &view, &proj, &eye);
    mat4 inv = m4_inverse(m4_mul(proj, view));
    float nx = ((float)x + 0.5f) / (float)w * 2 - 1, ny = 1 - ((float)y + 0.5f) / (float)h * 2;
    vec4 a = m4_vec4(inv, (vec4){nx, ny, -1, 1}), b = m4_vec4(inv, (vec4){nx, ny, 1, 1});
    vec3 pa = v3(a.x / a.w, a.y / a.w, a.z / a.w), pb = v3(b.x / b.w, b.y / b.w, b.z / b.w);
    vec3 d = v3_sub(pb, pa);
    if (fabs(d.y) < 1e-9)
        return -1;
    double t = (plane_y - pa.y) / d.y;
    if (t <= 0)
        return -1;
    *p = v3_add(pa, v3_scale(d, (float)t));
    *eye_out = eye;
    /* Only points well inside the test planes (x, z in [-3.9, 3.9]) count. */
    return fabsf(p->x) < 3.9f && fabsf(p->z) < 3.9f ? 0 : -1;
}

/* brdf_spec.md, written again in double precision: the specular term F D V. */
static inline double fx_spec(vec3 n, vec3 v, vec3 l, double f0, double roughness)
{
    double nl = v3_dot(n, l), nv = v3_dot(n, v);
    if (nl <= 0 || nv <= 0)
        return 0;
    vec3 h = v3_norm(v3_add(v, l));
    double a = fmax(roughness * roughness, 0.0025), a2 = a * a;
    double nh = v3_dot(n, h), vh = v3_dot(v, h);
    double F = f0 + (1 - f0) * pow(1 - vh, 5);
    double dd = nh * nh * (a2 - 1) + 1, D = a2 / (FX_PI * dd * dd);
    double V = 0.5 / (nl * sqrt(nv * nv * (1 - a2) + a2) + nv * sqrt(nl * nl * (1 - a2) + a2));
    return F * D * V;
}

/* Lambert polygon irradiance / radiance (the edge integral), polygon wholly above p's horizon. */
static inline double fx_polygon_irradiance(vec3 p, vec3 n, const vec3 *verts, int count)
{
    double sum = 0;
    for (int i = 0; i < count; i++) {
        vec3 a = v3_norm(v3_sub(verts[i], p)), b = v3_norm(v3_sub(verts[(i + 1) % count], p));
        vec3 c = v3_cross(a, b);
        double len = v3_len(c);
        if (len < 1e-12)
            continue;
        sum += atan2(len, v3_dot(a, b)) * v3_dot(c, n) / len;
    }
    return 0.5 * fabs(sum);
}

#endif
