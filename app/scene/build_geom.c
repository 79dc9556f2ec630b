/* Geometry helpers for the procedural scenes (see build_geom.h). */
#include "scene/build_geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void gkb_free(gkw_geom *g)
{
    free(g->pos), free(g->nrm), free(g->uv), free(g->idx);
    memset(g, 0, sizeof *g);
}

static void *grow(void *p, uint32_t cap, size_t elem)
{
    void *q = realloc(p, (size_t)cap * elem);
    if (!q)
        abort(); /* the builders allocate a few MB at most; running out is not recoverable here */
    return q;
}

uint32_t gkb_vertex(gkw_geom *g, vec3 p, vec3 n, float u, float v)
{
    if (g->nv == g->cap_v) {
        g->cap_v = g->cap_v ? g->cap_v * 2 : 256;
        g->pos = grow(g->pos, g->cap_v, 3 * sizeof(float));
        g->nrm = grow(g->nrm, g->cap_v, 3 * sizeof(float));
        g->uv = grow(g->uv, g->cap_v, 2 * sizeof(float));
    }
    float *P = g->pos + 3 * (size_t)g->nv, *N = g->nrm + 3 * (size_t)g->nv, *T = g->uv + 2 * (size_t)g->nv;
    P[0] = p.x, P[1] = p.y, P[2] = p.z;
    n = v3_norm(n);
    N[0] = n.x, N[1] = n.y, N[2] = n.z;
    T[0] = u, T[1] = v;
    return g->nv++;
}

void gkb_tri(gkw_geom *g, uint32_t a, uint32_t b, uint32_t c)
{
    if (g->nt == g->cap_t) {
        g->cap_t = g->cap_t ? g->cap_t * 2 : 256;
        g->idx = grow(g->idx, g->cap_t, 3 * sizeof(uint32_t));
    }
    uint32_t *t = g->idx + 3 * (size_t)g->nt++;
    t[0] = a, t[1] = b, t[2] = c;
}

void gkb_quad_grid(gkw_geom *g, vec3 a, vec3 b, vec3 c, vec3 d, vec3 facing, int nu, int nv)
{
    vec3 n = v3_cross(v3_sub(b, a), v3_sub(d, a));
    if (v3_dot(n, facing) < 0) { /* reverse the order: a d c b */
        vec3 t = b;
        b = d, d = t;
        n = v3_scale(n, -1);
    }
    uint32_t first = g->nv;
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            float u = (float)i / (float)nu, v = (float)j / (float)nv;
            /* bilinear over the quad: a (0,0), b (1,0), c (1,1), d (0,1) */
            vec3 p = v3_add(v3_add(v3_scale(a, (1 - u) * (1 - v)), v3_scale(b, u * (1 - v))),
                            v3_add(v3_scale(c, u * v), v3_scale(d, (1 - u) * v)));
            gkb_vertex(g, p, n, u, v);
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t v00 = first + (uint32_t)(j * (nu + 1) + i), v10 = v00 + 1;
            uint32_t v01 = v00 + (uint32_t)(nu + 1), v11 = v01 + 1;
            gkb_tri(g, v00, v10, v11);
            gkb_tri(g, v00, v11, v01);
        }
}

void gkb_triangle(gkw_geom *g, vec3 a, vec3 b, vec3 c, vec3 facing)
{
    vec3 n = v3_cross(v3_sub(b, a), v3_sub(c, a));
    if (v3_dot(n, facing) < 0) {
        vec3 t = b;
        b = c, c = t;
        n = v3_scale(n, -1);
    }
    uint32_t i = gkb_vertex(g, a, n, 0, 0);
    gkb_vertex(g, b, n, 1, 0);
    gkb_vertex(g, c, n, 0, 1);
    gkb_tri(g, i, i + 1, i + 2);
}

void gkb_quad(gkw_geom *g, vec3 a, vec3 b, vec3 c, vec3 d, vec3 facing)
{
    gkb_quad_grid(g, a, b, c, d, facing, 1, 1);
}

void gkb_box(gkw_geom *g, vec3 lo, vec3 hi, bool inward)
{
    float s = inward ? -1.0f : 1.0f;
    vec3 P[8];
    for (int i = 0; i < 8; i++)
        P[i] = v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    gkb_quad(g, P[0], P[2], P[6], P[4], v3(-s, 0, 0)); /* x = lo */
    gkb_quad(g, P[1], P[3], P[7], P[5], v3(s, 0, 0));
    gkb_quad(g, P[0], P[1], P[5], P[4], v3(0, -s, 0)); /* y = lo */
    gkb_quad(g, P[2], P[3], P[7], P[6], v3(0, s, 0));
    gkb_quad(g, P[0], P[1], P[3], P[2], v3(0, 0, -s)); /* z = lo */
    gkb_quad(g, P[4], P[5], P[7], P[6], v3(0, 0, s));
}

void gkb_cylinder(gkw_geom *g, vec3 base, float radius, float y0, float y1, int seg, int stacks, bool inward)
{
    uint32_t first = g->nv;
    for (int j = 0; j <= stacks; j++)
        for (int i = 0; i <= seg; i++) {
            float a = 2.0f * (float)M_PI * (float)(i % seg) / (float)seg;
            vec3 dir = v3(cosf(a), 0, sinf(a));
            float y = y0 + (y1 - y0) * (float)j / (float)stacks;
            gkb_vertex(g, v3(base.x + radius * dir.x, base.y + y, base.z + radius * dir.z),
                       inward ? v3_scale(dir, -1) : dir, (float)i / (float)seg, (float)j / (float)stacks);
        }
    for (int j = 0; j < stacks; j++)
        for (int i = 0; i < seg; i++) {
            uint32_t v00 = first + (uint32_t)(j * (seg + 1) + i), v10 = v00 + 1;
            uint32_t v01 = v00 + (uint32_t)(seg + 1), v11 = v01 + 1;
            /* Counter-clockwise seen from outside: angle grows from +x towards +z. */
            if (inward) {
                gkb_tri(g, v00, v10, v11);
                gkb_tri(g, v00, v11, v01);
            } else {
                gkb_tri(g, v00, v11, v10);
                gkb_tri(g, v00, v01, v11);
            }
        }
}

void gkb_annulus(gkw_geom *g, vec3 c, float y, float r0, float r1, int seg)
{
    uint32_t first = g->nv;
    for (int i = 0; i <= seg; i++) {
        float a = 2.0f * (float)M_PI * (float)(i % seg) / (float)seg;
        gkb_vertex(g, v3(c.x + r0 * cosf(a), c.y + y, c.z + r0 * sinf(a)), v3(0, 1, 0), 0, 0);
        gkb_vertex(g, v3(c.x + r1 * cosf(a), c.y + y, c.z + r1 * sinf(a)), v3(0, 1, 0), 1, 0);
    }
    for (int i = 0; i < seg; i++) {
        uint32_t i0 = first + 2 * (uint32_t)i, o0 = i0 + 1, i1 = i0 + 2, o1 = i0 + 3;
        gkb_tri(g, i0, i1, o1); /* normal +y: (i1 - i0) x (o1 - i0) points up for growing angle */
        gkb_tri(g, i0, o1, o0);
    }
}

quat gkb_axis_angle(vec3 axis, float radians)
{
    axis = v3_norm(axis);
    float s = sinf(radians * 0.5f);
    return (quat){axis.x * s, axis.y * s, axis.z * s, cosf(radians * 0.5f)};
}

quat gkb_look_rotation(vec3 forward, vec3 up)
{
    vec3 z = v3_scale(v3_norm(forward), -1.0f); /* the node's +Z points backwards */
    if (fabsf(v3_dot(z, v3_norm(up))) > 0.999f)
        up = fabsf(z.y) < 0.9f ? v3(0, 1, 0) : v3(1, 0, 0);
    vec3 x = v3_norm(v3_cross(up, z));
    vec3 y = v3_cross(z, x);
    /* rotation matrix columns x, y, z -> quaternion */
    float m00 = x.x, m11 = y.y, m22 = z.z, tr = m00 + m11 + m22;
    quat q;
    if (tr > 0) {
        float k = sqrtf(tr + 1.0f) * 2.0f;
        q = (quat){(y.z - z.y) / k, (z.x - x.z) / k, (x.y - y.x) / k, 0.25f * k};
    } else if (m00 > m11 && m00 > m22) {
        float k = sqrtf(1.0f + m00 - m11 - m22) * 2.0f;
        q = (quat){0.25f * k, (y.x + x.y) / k, (z.x + x.z) / k, (y.z - z.y) / k};
    } else if (m11 > m22) {
        float k = sqrtf(1.0f + m11 - m00 - m22) * 2.0f;
        q = (quat){(y.x + x.y) / k, 0.25f * k, (z.y + y.z) / k, (z.x - x.z) / k};
    } else {
        float k = sqrtf(1.0f + m22 - m00 - m11) * 2.0f;
        q = (quat){(z.x + x.z) / k, (z.y + y.z) / k, 0.25f * k, (x.y - y.x) / k};
    }
    return q_normalize(q);
}

int gkb_object(gkw_doc *d, const char *name, gkw_geom *g, int material)
{
    int node;
    int mesh = gkw_add_mesh(d, name, g, material);
    gkw_node *n = gkw_node_add(d, name, &node);
    if (n)
        n->mesh = mesh;
    gkb_free(g);
    return node;
}

int gkb_light_node(gkw_doc *d, const gkw_light *l, vec3 pos, vec3 dir, vec3 up)
{
    int node;
    int light = gkw_add_light(d, l);
    gkw_node *n = gkw_node_add(d, l->name, &node);
    if (n) {
        n->light = light;
        n->t = pos;
        n->r = gkb_look_rotation(dir, up);
    }
    return node;
}

int gkb_camera_node(gkw_doc *d, vec3 eye, vec3 target, double yfov, double znear, double zfar)
{
    int node;
    int cam = gkw_add_camera(d, yfov, znear, zfar);
    gkw_node *n = gkw_node_add(d, "camera", &node);
    if (n) {
        n->camera = cam;
        n->t = eye;
        n->r = gkb_look_rotation(v3_sub(target, eye), v3(0, 1, 0));
    }
    return node;
}

/* One triangle of a sphere, wound counter-clockwise seen from outside (its geometric normal points
   away from the centre, which the tracer's dielectric takes as the glass's outside). */
static void sphere_tri(gkw_geom *g, vec3 c, uint32_t a, uint32_t b, uint32_t d)
{
    vec3 pa = v3(g->pos[3 * a], g->pos[3 * a + 1], g->pos[3 * a + 2]);
    vec3 pb = v3(g->pos[3 * b], g->pos[3 * b + 1], g->pos[3 * b + 2]);
    vec3 pd = v3(g->pos[3 * d], g->pos[3 * d + 1], g->pos[3 * d + 2]);
    vec3 n = v3_cross(v3_sub(pb, pa), v3_sub(pd, pa));
    vec3 out = v3_sub(v3_scale(v3_add(v3_add(pa, pb), pd), 1.0f / 3.0f), c);
    if (v3_dot(n, out) >= 0.0f)
        gkb_tri(g, a, b, d);
    else
        gkb_tri(g, a, d, b);
}

void gkb_sphere(gkw_geom *g, vec3 c, float radius, int seg, int rings)
{
    uint32_t top = gkb_vertex(g, v3(c.x, c.y + radius, c.z), v3(0, 1, 0), 0.5f, 0.0f);
    uint32_t first = g->nv;
    for (int j = 1; j < rings; j++) {
        float th = (float)M_PI * (float)j / (float)rings;
        for (int i = 0; i <= seg; i++) {
            float ph = 2.0f * (float)M_PI * (float)(i % seg) / (float)seg;
            vec3 n = v3(sinf(th) * cosf(ph), cosf(th), sinf(th) * sinf(ph));
            gkb_vertex(g, v3_add(c, v3_scale(n, radius)), n, (float)i / (float)seg, (float)j / (float)rings);
        }
    }
    uint32_t bottom = gkb_vertex(g, v3(c.x, c.y - radius, c.z), v3(0, -1, 0), 0.5f, 1.0f);
    uint32_t row = (uint32_t)seg + 1;
    for (int i = 0; i < seg; i++) {
        sphere_tri(g, c, top, first + (uint32_t)i, first + (uint32_t)i + 1);
        uint32_t last = first + (uint32_t)(rings - 2) * row;
        sphere_tri(g, c, bottom, last + (uint32_t)i, last + (uint32_t)i + 1);
    }
    for (int j = 0; j < rings - 2; j++)
        for (int i = 0; i < seg; i++) {
            uint32_t v00 = first + (uint32_t)j * row + (uint32_t)i, v10 = v00 + 1, v01 = v00 + row, v11 = v01 + 1;
            sphere_tri(g, c, v00, v10, v11);
            sphere_tri(g, c, v00, v11, v01);
        }
}
