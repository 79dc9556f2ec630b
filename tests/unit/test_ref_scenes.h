/* In-memory scenes for the reference path tracer's oracle tests: quads, boxes, lights and a
 * camera, built straight into the gk_scene model (no loader needed), then flattened with
 * gk_ref_scene_build. Header-only, shared by tests/unit/test_ref*.c. */
#ifndef TEST_REF_SCENES_H
#define TEST_REF_SCENES_H

#include <string.h>

#include "ref/ref_scene.h"

#define TS_MAX 32

typedef struct test_scene {
    gk_scene s;
    gk_mesh meshes[TS_MAX];
    gk_material mats[TS_MAX];
    gk_light lights[4];
    gk_node nodes[TS_MAX + 4];
    float pos[TS_MAX][12], nrm[TS_MAX][12];
    uint32_t idx[TS_MAX][6];
    vec3 eye, target;
    float yfov;
} test_scene;

static inline void ts_init(test_scene *t)
{
    memset(t, 0, sizeof *t);
    t->s.meshes = t->meshes;
    t->s.materials = t->mats;
    t->s.lights = t->lights;
    t->s.nodes = t->nodes;
    t->s.camera_node = -1;
    t->yfov = 0.8f;
}

static inline int ts_material(test_scene *t, float r, float g, float b, float metallic, float roughness)
{
    gk_material *m = &t->mats[t->s.n_materials];
    memset(m, 0, sizeof *m);
    m->base_color[0] = r; m->base_color[1] = g; m->base_color[2] = b; m->base_color[3] = 1;
    m->base_color_tex = -1;
    m->metallic_roughness_tex = -1;
    m->metallic = metallic;
    m->roughness = roughness;
    m->ior = 1.5f;
    m->specular = 1.0f; /* KHR_materials_specular's defaults */
    m->specular_color[0] = m->specular_color[1] = m->specular_color[2] = 1.0f;
    m->specular_tex = m->specular_color_tex = -1;
    return t->s.n_materials++;
}

static inline gk_node *ts_node(test_scene *t)
{
    gk_node *n = &t->nodes[t->s.n_nodes++];
    memset(n, 0, sizeof *n);
    n->parent = -1;
    n->light = -1;
    n->camera = -1;
    n->world = m4_identity();
    return n;
}

/* A one-sided quad c, c+eu, c+eu+ev, c+ev facing cross(eu, ev). */
static inline void ts_quad(test_scene *t, vec3 c, vec3 eu, vec3 ev, int material)
{
    int i = t->s.n_meshes++;
    vec3 p[4] = {c, v3_add(c, eu), v3_add(v3_add(c, eu), ev), v3_add(c, ev)};
    vec3 n = v3_norm(v3_cross(eu, ev));
    for (int k = 0; k < 4; k++) {
        t->pos[i][3 * k] = p[k].x; t->pos[i][3 * k + 1] = p[k].y; t->pos[i][3 * k + 2] = p[k].z;
        t->nrm[i][3 * k] = n.x; t->nrm[i][3 * k + 1] = n.y; t->nrm[i][3 * k + 2] = n.z;
    }
    static const uint32_t q[6] = {0, 1, 2, 0, 2, 3};
    memcpy(t->idx[i], q, sizeof q);
    gk_mesh *m = &t->meshes[i];
    memset(m, 0, sizeof *m);
    m->positions = t->pos[i];
    m->normals = t->nrm[i];
    m->indices = t->idx[i];
    m->n_vertices = 4;
    m->n_triangles = 2;
    m->material = material;
    gk_node *nd = ts_node(t);
    nd->mesh_first = i;
    nd->mesh_count = 1;
}

/* Axis-aligned box [lo, hi] with faces pointing inwards (inside = true) or outwards. */
static inline void ts_box(test_scene *t, vec3 lo, vec3 hi, int material, int inside)
{
    vec3 d = v3_sub(hi, lo);
    vec3 ex = v3(d.x, 0, 0), ey = v3(0, d.y, 0), ez = v3(0, 0, d.z);
    vec3 H = hi;
    /* Outward faces: each (corner, eu, ev) has cross(eu, ev) pointing out; swap to face in. */
    vec3 c[6] = {lo, lo, lo, H, H, H};
    vec3 u[6] = {ey, ez, ex, v3_scale(ez, -1), v3_scale(ex, -1), v3_scale(ey, -1)};
    vec3 v[6] = {ez, ex, ey, v3_scale(ey, -1), v3_scale(ez, -1), v3_scale(ex, -1)};
    for (int f = 0; f < 6; f++) {
        vec3 n = v3_cross(u[f], v[f]);
        vec3 centre = v3_add(c[f], v3_scale(v3_add(u[f], v[f]), 0.5f));
        vec3 mid = v3_scale(v3_add(lo, hi), 0.5f);
        int outward = v3_dot(n, v3_sub(centre, mid)) > 0.0f;
        if (outward == (inside != 0))
            ts_quad(t, c[f], v[f], u[f], material);
        else
            ts_quad(t, c[f], u[f], v[f], material);
    }
}

/* A light at pos emitting along axis (the node's -Z); u is the node's X axis. */
static inline gk_light *ts_light(test_scene *t, enum gk_light_type type, vec3 pos, vec3 axis, vec3 u, float intensity)
{
    int li = t->s.n_lights++;
    gk_light *l = &t->lights[li];
    memset(l, 0, sizeof *l);
    l->type = type;
    l->shape = GK_SHAPE_POINT;
    l->color[0] = l->color[1] = l->color[2] = 1.0f;
    l->intensity = intensity;
    l->outer_cone = 0.785398f;
    gk_node *n = ts_node(t);
    n->light = li;
    vec3 z = v3_scale(v3_norm(axis), -1.0f), x = v3_norm(u), y = v3_cross(z, x);
    mat4 w = m4_identity();
    w.m[0] = x.x; w.m[1] = x.y; w.m[2] = x.z;
    w.m[4] = y.x; w.m[5] = y.y; w.m[6] = y.z;
    w.m[8] = z.x; w.m[9] = z.y; w.m[10] = z.z;
    w.m[12] = pos.x; w.m[13] = pos.y; w.m[14] = pos.z;
    n->world = w;
    return l;
}

static inline int ts_build(test_scene *t, gk_ref_scene *rs, int w, int h)
{
    mat4 view = m4_look_at(t->eye, t->target, fabsf(v3_norm(v3_sub(t->target, t->eye)).y) > 0.99f ? v3(0, 0, -1) : v3(0, 1, 0));
    mat4 proj = m4_perspective(t->yfov, (float)w / (float)h, 0.05f, 100.0f);
    gk_err e = {0};
    return gk_ref_scene_build(rs, &t->s, view, proj, t->eye, w, h, &e);
}

/* brdf_spec.md transcribed independently of app/ref/materials.c: f for a dielectric-metal mix, grey
 * base, KHR_materials_specular weight w and grey F0 colour c0. */
static inline float ts_brdf_gltf(float base, float metallic, float roughness, float w, float c0, vec3 n, vec3 wo,
                                 vec3 wi)
{
    float a = roughness * roughness;
    a = a < 0.0025f ? 0.0025f : a;
    float a2 = a * a;
    vec3 h = v3_norm(v3_add(wo, wi));
    float nl = v3_dot(n, wi), nv = v3_dot(n, wo), nh = v3_dot(n, h), vh = v3_dot(wo, h);
    if (nl <= 0 || nv <= 0)
        return 0;
    float dd = nh * nh * (a2 - 1) + 1;
    float D = a2 / (3.14159265f * dd * dd);
    float V = 0.5f / (nl * sqrtf(nv * nv * (1 - a2) + a2) + nv * sqrtf(nl * nl * (1 - a2) + a2));
    float s5 = powf(1 - vh, 5);
    /* Appendix B as its normative form: mix(dielectric, metal, metallic). */
    float fd = c0 + (1 - c0) * s5;                                     /* fresnel_mix's Fresnel */
    float dielectric = (1 - w * fd) * base / 3.14159265f + w * fd * D * V;
    float metal = (base + (1 - base) * s5) * D * V;                   /* conductor_fresnel */
    return (1 - metallic) * dielectric + metallic * metal;
}

/* The default material (no KHR_materials_specular: weight 1, ior 1.5 so c0 = 0.04). */
static inline float ts_brdf_spec(float base, float metallic, float roughness, vec3 n, vec3 wo, vec3 wi)
{
    return ts_brdf_gltf(base, metallic, roughness, 1.0f, 0.04f, n, wo, wi);
}

#endif
