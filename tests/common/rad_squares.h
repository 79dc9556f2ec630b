/* A hand-made radiosity mesh of square charts for the unit tests (tests/unit/test_radiosity_*.c):
 * each chart a g x g grid of surfels (g a power of two) in Morton order, so the quadtree over it is
 * the exact one. Header-only: static functions. */
#ifndef GKT_RAD_SQUARES_H
#define GKT_RAD_SQUARES_H

#include <stdlib.h>
#include <string.h>

#include "gi/radiosity/rad_mesh.h"

/* A hand-made mesh of square charts, each a g x g grid of surfels (g a power of two) in Morton
   order, so the quadtree is the exact one. */
typedef struct square { vec3 centre, normal, tu; float side; int g; } square;

static inline uint32_t compact(uint32_t x)
{
    x &= 0x55555555u;
    x = (x | (x >> 1)) & 0x33333333u;
    x = (x | (x >> 2)) & 0x0F0F0F0Fu;
    x = (x | (x >> 4)) & 0x00FF00FFu;
    x = (x | (x >> 8)) & 0x0000FFFFu;
    return x;
}

static inline void squares_mesh(rad_mesh *m, const square *sq, int n)
{
    memset(m, 0, sizeof *m);
    int total = 0;
    for (int i = 0; i < n; i++)
        total += sq[i].g * sq[i].g;
    m->pos = calloc((size_t)total, sizeof *m->pos);
    m->area = calloc((size_t)total, sizeof *m->area);
    m->centre = calloc((size_t)total, sizeof *m->centre);
    m->chart = calloc((size_t)total, sizeof *m->chart);
    m->charts = calloc((size_t)n, sizeof *m->charts);
    m->n_charts = n;
    for (int c = 0; c < n; c++) {
        const square *s = &sq[c];
        vec3 tv = v3_cross(s->normal, s->tu);
        m->charts[c] = (rad_chart){.normal = s->normal, .tu = s->tu, .tv = tv, .first_vert = m->n_verts, .n_verts = s->g * s->g};
        float cell = s->side / (float)s->g;
        for (int k = 0; k < s->g * s->g; k++) {
            int i = (int)compact((uint32_t)k), j = (int)compact((uint32_t)k >> 1);
            float u = ((float)i + 0.5f) * cell - 0.5f * s->side, v = ((float)j + 0.5f) * cell - 0.5f * s->side;
            m->pos[m->n_verts] = v3_add(s->centre, v3_add(v3_scale(s->tu, u), v3_scale(tv, v)));
            m->centre[m->n_verts] = m->pos[m->n_verts]; /* cell centres */
            m->area[m->n_verts] = cell * cell;
            m->chart[m->n_verts] = c;
            m->n_verts++;
        }
    }
}

#endif
