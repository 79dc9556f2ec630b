/* The GPU tests' shared GL/EGL fixture (see gl_fixture.h). */
#include "gl_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef GK_TEST_SHADERS
#define GK_TEST_SHADERS "build/tests/shaders"
#endif

int gkt_gl_open(gkt_gl *g)
{
    memset(g, 0, sizeof *g);
    gk_err e = {0};
    EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (dpy == EGL_NO_DISPLAY || gk_egl_init_display(&g->egl, dpy, &e) ||
        gk_egl_create_context(&g->egl, EGL_NO_CONFIG_KHR, false, &e) || gk_egl_make_current(&g->egl, EGL_NO_SURFACE, &e)) {
        fprintf(stderr, "# EGL: %s\n", dpy == EGL_NO_DISPLAY ? "no surfaceless display" : e.msg);
        return -1;
    }
    return 0;
}

void gkt_gl_close(gkt_gl *g)
{
    gk_egl_terminate(&g->egl);
}

int gkt_target(gk_target *t, const char *what, int w, int h, int n_color, const GLenum *formats, bool depth)
{
    gk_err e = {0};
    if (gk_target_create(t, what, w, h, n_color, formats, GL_NEAREST, depth, &e) != 0) {
        fprintf(stderr, "# %s\n", e.msg);
        return -1;
    }
    return 0;
}

void gkt_read_rgba(const gk_target *t, int attachment, GLenum type, void *out)
{
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0 + (GLenum)attachment);
    glReadPixels(0, 0, t->width, t->height, GL_RGBA, type, out);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

const char *gkt_shader_dir(void)
{
    const char *d = getenv("GK_TEST_SHADER_DIR");
    return d && *d ? d : GK_TEST_SHADERS;
}

gk_program_cache *gkt_programs(int gles)
{
    return gk_program_cache_create(gkt_shader_dir(), gles);
}

void gkt_scene_init(gkt_scene *t, const char *name)
{
    memset(t, 0, sizeof *t);
    t->s.meshes = t->meshes;
    t->s.materials = t->mats;
    t->s.lights = t->lights;
    t->s.nodes = t->nodes;
    t->s.cameras = &t->cam;
    t->s.camera_node = -1;
    snprintf(t->s.name, sizeof t->s.name, "%s", name);
    snprintf(t->s.path, sizeof t->s.path, "(test fixture)");
}

void gkt_scene_free(gkt_scene *t)
{
    for (int i = 0; i < t->s.n_meshes; i++)
        gkb_free(&t->geom[i]);
    t->s.n_meshes = 0;
}

int gkt_material(gkt_scene *t, vec3 base, float metallic, float roughness)
{
    if (t->s.n_materials >= GKT_MAX_MESH) {
        fprintf(stderr, "# gkt_material: more than %d materials\n", GKT_MAX_MESH);
        abort();
    }
    gk_material *m = &t->mats[t->s.n_materials];
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "m%d", t->s.n_materials);
    m->base_color[0] = base.x, m->base_color[1] = base.y, m->base_color[2] = base.z;
    m->base_color[3] = 1;
    m->base_color_tex = m->metallic_roughness_tex = m->emissive_tex = m->normal_tex = m->occlusion_tex = -1;
    m->metallic = metallic;
    m->roughness = roughness;
    m->ior = 1.5f;
    m->specular = 1.0f; /* KHR_materials_specular's defaults */
    m->specular_color[0] = m->specular_color[1] = m->specular_color[2] = 1.0f;
    m->specular_tex = m->specular_color_tex = -1;
    return t->s.n_materials++;
}

int gkt_material_lambert(gkt_scene *t, vec3 base)
{
    int m = gkt_material(t, base, 0.0f, 1.0f);
    t->mats[m].specular = 0.0f;
    return m;
}

static int add_node(gkt_scene *t)
{
    gk_node *n = &t->nodes[t->s.n_nodes];
    memset(n, 0, sizeof *n);
    snprintf(n->name, sizeof n->name, "n%d", t->s.n_nodes);
    n->parent = -1;
    n->rotation = (quat){0, 0, 0, 1};
    n->scale = v3(1, 1, 1);
    n->world = m4_identity();
    n->light = n->camera = -1;
    return t->s.n_nodes++;
}

int gkt_object(gkt_scene *t, gkw_geom *g, int material)
{
    if (t->s.n_meshes >= GKT_MAX_MESH || t->s.n_nodes >= GKT_MAX_NODE) {
        fprintf(stderr, "# gkt_object: more than %d objects\n", GKT_MAX_MESH);
        abort();
    }
    int k = t->s.n_meshes++;
    t->geom[k] = *g;
    memset(g, 0, sizeof *g);
    const gkw_geom *q = &t->geom[k];
    gk_mesh *m = &t->meshes[k];
    memset(m, 0, sizeof *m);
    m->positions = q->pos;
    m->normals = q->nrm;
    m->uvs = q->uv;
    m->indices = q->idx;
    m->n_vertices = q->nv;
    m->n_triangles = q->nt;
    m->material = material;
    vec3 lo = v3(1e30f, 1e30f, 1e30f), hi = v3(-1e30f, -1e30f, -1e30f);
    for (uint32_t i = 0; i < q->nv; i++) {
        vec3 p = v3(q->pos[3 * i], q->pos[3 * i + 1], q->pos[3 * i + 2]);
        lo = v3_min(lo, p);
        hi = v3_max(hi, p);
    }
    m->bmin = lo;
    m->bmax = hi;
    int n = add_node(t);
    t->nodes[n].mesh_first = k;
    t->nodes[n].mesh_count = 1;
    t->s.n_triangles += q->nt;
    return n;
}

int gkt_quad(gkt_scene *t, vec3 a, vec3 b, vec3 c, vec3 d, vec3 facing, int material)
{
    gkw_geom g = {0};
    gkb_quad(&g, a, b, c, d, facing);
    return gkt_object(t, &g, material);
}

quat gkt_look_rotation(vec3 dir)
{
    vec3 z = v3_norm(v3_scale(dir, -1.0f));
    return gkb_look_rotation(dir, fabsf(z.y) > 0.99f ? v3(0, 0, -1) : v3(0, 1, 0));
}

void gkt_camera(gkt_scene *t, vec3 eye, vec3 target, float yfov)
{
    t->cam = (gk_camera){.yfov = yfov, .aspect = 0, .znear = 0.05f, .zfar = 50.0f};
    t->s.n_cameras = 1;
    int c = add_node(t);
    t->nodes[c].camera = 0;
    t->nodes[c].translation = eye;
    t->nodes[c].rotation = gkt_look_rotation(v3_sub(target, eye));
    t->s.camera_node = c;
}

gk_light *gkt_light(gkt_scene *t, enum gk_light_type type, enum gk_light_shape shape, float intensity, vec3 pos,
                    vec3 dir)
{
    int i = t->s.n_lights++;
    gk_light *l = &t->lights[i];
    memset(l, 0, sizeof *l);
    l->type = type;
    l->shape = shape;
    l->color[0] = l->color[1] = l->color[2] = 1;
    l->intensity = intensity;
    l->outer_cone = 0.785398f;
    int n = add_node(t);
    t->nodes[n].light = i;
    t->nodes[n].translation = pos;
    t->nodes[n].rotation = gkt_look_rotation(dir);
    return l;
}

void gkt_scene_bounds(gkt_scene *t)
{
    vec3 lo = v3(1e30f, 1e30f, 1e30f), hi = v3(-1e30f, -1e30f, -1e30f);
    t->s.n_triangles = 0;
    for (int n = 0; n < t->s.n_nodes; n++) {
        const gk_node *nd = &t->nodes[n];
        for (int k = nd->mesh_first; k < nd->mesh_first + nd->mesh_count; k++) {
            const gk_mesh *m = &t->meshes[k];
            for (uint32_t i = 0; i < m->n_vertices; i++) {
                vec3 p = m4_point(nd->world, v3(m->positions[i * 3], m->positions[i * 3 + 1], m->positions[i * 3 + 2]));
                lo = v3_min(lo, p);
                hi = v3_max(hi, p);
            }
            t->s.n_triangles += m->n_triangles;
        }
    }
    t->s.bmin = lo;
    t->s.bmax = hi;
}

int gkt_shipped_open(gkt_shipped *t, const char *gltf, int w, int h)
{
    const GLenum rgba8[1] = {GL_RGBA8};
    if (gkt_gl_open(&t->gl) != 0 || gkt_target(&t->fb, "test framebuffer", w, h, 1, rgba8, false) != 0)
        return -1;
    gk_err e = {0};
    t->scene = gk_scene_load(gltf, &e);
    if (!t->scene) {
        fprintf(stderr, "%s\n", e.msg);
        return -1;
    }
    return 0;
}

void gkt_shipped_close(gkt_shipped *t)
{
    gk_scene_free(t->scene);
    gk_target_destroy(&t->fb);
    gkt_gl_close(&t->gl);
}
