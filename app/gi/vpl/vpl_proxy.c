/* Tessellated position-only copy of the scene for paraboloid maps; see vpl_proxy.h. */
#include "vpl_proxy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_program.h"

static float node_scale(const gk_node *n)
{
    float s = 0.0f;
    for (int c = 0; c < 3; c++) {
        const float *m = &n->world.m[c * 4];
        s = fmaxf(s, sqrtf(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]));
    }
    if (s <= 0.0f) /* world not evaluated yet: the local scale is the best guess */
        s = fmaxf(fabsf(n->scale.x), fmaxf(fabsf(n->scale.y), fabsf(n->scale.z)));
    return s > 0.0f ? s : 1.0f;
}

static int tri_splits(const float *a, const float *b, const float *c, float max_edge)
{
    float e = 0.0f;
    const float *v[3] = {a, b, c};
    for (int i = 0; i < 3; i++) {
        const float *p = v[i], *q = v[(i + 1) % 3];
        float d = sqrtf((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
        e = fmaxf(e, d);
    }
    int k = (int)ceilf(e / max_edge);
    return k < 1 ? 1 : (k > 64 ? 64 : k);
}

static long count_mesh(const gk_mesh *m, float max_edge)
{
    long t = 0;
    for (uint32_t i = 0; i < m->n_triangles; i++) {
        const uint32_t *ix = &m->indices[i * 3];
        int k = tri_splits(&m->positions[ix[0] * 3], &m->positions[ix[1] * 3], &m->positions[ix[2] * 3], max_edge);
        t += (long)k * k;
    }
    return t;
}

static void lerp3(float *out, const float *a, const float *b, const float *c, float u, float v)
{
    float w = 1.0f - u - v;
    for (int j = 0; j < 3; j++)
        out[j] = w * a[j] + u * b[j] + v * c[j];
}

/* Uniform barycentric subdivision into k² triangles. Returns floats written. */
static long subdivide(const gk_mesh *m, float max_edge, float *out)
{
    long w = 0;
    for (uint32_t i = 0; i < m->n_triangles; i++) {
        const uint32_t *ix = &m->indices[i * 3];
        const float *a = &m->positions[ix[0] * 3], *b = &m->positions[ix[1] * 3], *c = &m->positions[ix[2] * 3];
        int k = tri_splits(a, b, c, max_edge);
        float s = 1.0f / (float)k;
        for (int r = 0; r < k; r++)
            for (int q = 0; q < k - r; q++) {
                /* upright triangle (q, r), (q+1, r), (q, r+1) */
                lerp3(&out[w], a, b, c, q * s, r * s), w += 3;
                lerp3(&out[w], a, b, c, (q + 1) * s, r * s), w += 3;
                lerp3(&out[w], a, b, c, q * s, (r + 1) * s), w += 3;
                if (q + r + 1 < k) { /* the inverted one next to it */
                    lerp3(&out[w], a, b, c, (q + 1) * s, r * s), w += 3;
                    lerp3(&out[w], a, b, c, (q + 1) * s, (r + 1) * s), w += 3;
                    lerp3(&out[w], a, b, c, q * s, (r + 1) * s), w += 3;
                }
            }
    }
    return w;
}

int vpl_proxy_build(vpl_proxy *p, const gk_scene *s, float max_edge, long max_triangles, gk_err *e)
{
    memset(p, 0, sizeof *p);
    /* Raise the edge bound until the whole scene fits the triangle cap. */
    for (int tries = 0; tries < 16; tries++) {
        long total = 0;
        for (int n = 0; n < s->n_nodes; n++) {
            float sc = node_scale(&s->nodes[n]);
            for (int k = 0; k < s->nodes[n].mesh_count; k++) {
                const gk_mesh *m = &s->meshes[s->nodes[n].mesh_first + k];
                if (!s->materials[m->material].light_proxy)
                    total += count_mesh(m, max_edge / sc);
            }
        }
        if (total <= max_triangles)
            break;
        max_edge *= 1.5f;
    }
    int cap = 0;
    for (int n = 0; n < s->n_nodes; n++)
        cap += s->nodes[n].mesh_count;
    p->draws = calloc((size_t)(cap > 0 ? cap : 1), sizeof *p->draws);
    if (!p->draws)
        return gk_fail(e, GK_ERUNTIME, "vpl: out of memory for proxy geometry");
    for (int n = 0; n < s->n_nodes; n++) {
        float sc = node_scale(&s->nodes[n]);
        for (int k = 0; k < s->nodes[n].mesh_count; k++) {
            const gk_mesh *m = &s->meshes[s->nodes[n].mesh_first + k];
            if (s->materials[m->material].light_proxy || m->n_triangles == 0)
                continue;
            long tris = count_mesh(m, max_edge / sc);
            float *buf = malloc((size_t)tris * 9 * sizeof(float));
            if (!buf) {
                vpl_proxy_free(p);
                return gk_fail(e, GK_ERUNTIME, "vpl: out of memory for proxy geometry (%ld triangles)", tris);
            }
            long floats = subdivide(m, max_edge / sc, buf);
            vpl_proxy_draw *d = &p->draws[p->n_draws++];
            d->node = n;
            d->vertices = (GLsizei)(floats / 3);
            glGenVertexArrays(1, &d->vao);
            glGenBuffers(1, &d->vbo);
            glBindVertexArray(d->vao);
            glBindBuffer(GL_ARRAY_BUFFER, d->vbo);
            glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(floats * sizeof(float)), buf, GL_STATIC_DRAW);
            glEnableVertexAttribArray(0);
            glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, 0);
            glBindVertexArray(0);
            free(buf);
            p->triangles += tris;
            p->bytes += floats * (long)sizeof(float);
        }
    }
    return 0;
}

void vpl_proxy_free(vpl_proxy *p)
{
    for (int i = 0; i < p->n_draws; i++) {
        glDeleteVertexArrays(1, &p->draws[i].vao);
        glDeleteBuffers(1, &p->draws[i].vbo);
    }
    free(p->draws);
    memset(p, 0, sizeof *p);
}

void vpl_proxy_draw_all(const vpl_proxy *p, const gk_scene *s, GLint u_model)
{
    for (int i = 0; i < p->n_draws; i++) {
        const vpl_proxy_draw *d = &p->draws[i];
        glUniformMatrix4fv(u_model, 1, GL_FALSE, s->nodes[d->node].world.m);
        glBindVertexArray(d->vao);
        glDrawArrays(GL_TRIANGLES, 0, d->vertices);
    }
    glBindVertexArray(0);
}
