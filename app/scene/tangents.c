/* Tangents for normal-mapped meshes that bring none (glTF 2.0 §3.7.2.1 asks for MikkTSpace when
 * TANGENT is absent). Per-vertex tangents by Lengyel's method: each triangle's dP/du and dP/dv from
 * its UV derivatives, summed over the triangles of a vertex (weighted by their area in UV-space
 * terms, as the unnormalised sums weigh them), made orthogonal to the vertex normal
 * (Gram-Schmidt), with the handedness w = sign(dot(N x T, dP/dv)) so B = (N x T) w points along
 * increasing v, the glTF UVs as given. MikkTSpace differs in how it splits vertices at UV seams
 * and weighs corners by angle; on meshes whose UV charts are not mirrored the frames agree up to
 * those weights. Both renderers read the same tangents, so they agree with each other either way. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

int gk_mesh_generate_tangents(gk_mesh *m, const float *uvs)
{
    if (!uvs || m->tangents)
        return 0;
    size_t nv = m->n_vertices;
    float *tan = calloc((nv ? nv : 1) * 4, sizeof(float));
    float *bit = calloc((nv ? nv : 1) * 3, sizeof(float));
    if (!tan || !bit) {
        free(tan), free(bit);
        return -1;
    }
    for (uint32_t t = 0; t < m->n_triangles; t++) {
        const uint32_t *i = &m->indices[3 * (size_t)t];
        const float *p0 = &m->positions[3 * i[0]], *p1 = &m->positions[3 * i[1]], *p2 = &m->positions[3 * i[2]];
        const float *w0 = &uvs[2 * i[0]], *w1 = &uvs[2 * i[1]], *w2 = &uvs[2 * i[2]];
        float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        float e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        float du1 = w1[0] - w0[0], dv1 = w1[1] - w0[1], du2 = w2[0] - w0[0], dv2 = w2[1] - w0[1];
        float det = du1 * dv2 - du2 * dv1;
        if (!(fabsf(det) > 1e-20f))
            continue; /* no UV area: no direction to give */
        float r = 1.0f / det;
        for (int k = 0; k < 3; k++) {
            float sdir = (e1[k] * dv2 - e2[k] * dv1) * r; /* dP/du */
            float tdir = (e2[k] * du1 - e1[k] * du2) * r; /* dP/dv */
            for (int c = 0; c < 3; c++) {
                tan[4 * i[c] + (size_t)k] += sdir;
                bit[3 * i[c] + (size_t)k] += tdir;
            }
        }
    }
    for (size_t v = 0; v < nv; v++) {
        vec3 n = v3(m->normals[3 * v], m->normals[3 * v + 1], m->normals[3 * v + 2]);
        vec3 t = v3(tan[4 * v], tan[4 * v + 1], tan[4 * v + 2]);
        t = v3_sub(t, v3_scale(n, v3_dot(n, t)));
        if (!(v3_len(t) > 1e-12f)) { /* no UV gradient here: any direction across the normal */
            vec3 a = fabsf(n.x) < 0.9f ? v3(1, 0, 0) : v3(0, 1, 0);
            t = v3_sub(a, v3_scale(n, v3_dot(n, a)));
        }
        t = v3_norm(t);
        vec3 b = v3(bit[3 * v], bit[3 * v + 1], bit[3 * v + 2]);
        float w = v3_dot(v3_cross(n, t), b) < 0.0f ? -1.0f : 1.0f;
        tan[4 * v] = t.x, tan[4 * v + 1] = t.y, tan[4 * v + 2] = t.z, tan[4 * v + 3] = w;
    }
    free(bit);
    m->tangents = tan;
    return 0;
}
