/* The radiosity geometry bundle and the CPU bounces (rad_solve.h). */
#include "rad_solve.h"

#include <stdlib.h>
#include <string.h>

int rad_geometry_build(rad_geometry *g, const gk_scene *s, float edge, int max_verts, int n_face, rad_weight weight,
                       gk_err *e)
{
    memset(g, 0, sizeof *g);
    g->edge = edge, g->n_face = n_face, g->weight = weight;
    if (rad_mesh_build(&g->mesh, s, edge, max_verts, e))
        return -1;
    if (rad_tree_build(&g->tree, &g->mesh, e) || rad_links_build(&g->links, &g->tree, n_face, weight, e)) {
        rad_geometry_free(g);
        return -1;
    }
    int n = g->mesh.n_verts;
    g->albedo = malloc(sizeof *g->albedo * 3 * (size_t)n);
    g->emission = malloc(sizeof *g->emission * 3 * (size_t)n);
    if (!g->albedo || !g->emission) {
        rad_geometry_free(g);
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory for %d surfels", n);
    }
    for (int i = 0; i < n; i++) {
        const gk_material *mt = &s->materials[g->mesh.charts[g->mesh.chart[i]].material];
        float k = 1.0f - mt->metallic;
        for (int c = 0; c < 3; c++) {
            g->albedo[3 * i + c] = mt->base_color[c] * k;
            g->emission[3 * i + c] = mt->emissive[c];
        }
    }
    return 0;
}

void rad_geometry_free(rad_geometry *g)
{
    rad_links_free(&g->links);
    rad_tree_free(&g->tree);
    rad_mesh_free(&g->mesh);
    free(g->albedo), free(g->emission);
    g->albedo = g->emission = NULL;
}

void rad_pullup(const rad_tree *t, float *v)
{
    for (int i = t->n_leaves; i < t->n_nodes; i++) {
        int first, k = rad_tree_children(t, i, &first);
        float s[3] = {0, 0, 0};
        for (int c = first; c < first + k; c++)
            for (int j = 0; j < 3; j++)
                s[j] += v[3 * c + j] * t->area[c];
        for (int j = 0; j < 3; j++)
            v[3 * i + j] = t->area[i] > 0.0f ? s[j] / t->area[i] : 0.0f;
    }
}

void rad_initial_radiance(const rad_geometry *g, const float *e_direct, float *b0)
{
    for (int i = 0; i < g->tree.n_leaves; i++)
        for (int j = 0; j < 3; j++)
            b0[3 * i + j] = g->emission[3 * i + j] + g->albedo[3 * i + j] / (float)M_PI * e_direct[3 * i + j];
    rad_pullup(&g->tree, b0);
}

int rad_solve_cpu(const rad_geometry *g, const float *b0, int bounces, float *e_ind)
{
    const rad_tree *t = &g->tree;
    const rad_links *L = &g->links;
    float *unshot = malloc(sizeof *unshot * 3 * (size_t)t->n_nodes);
    float *next = malloc(sizeof *next * 3 * (size_t)t->n_nodes);
    if (!unshot || !next) {
        free(unshot), free(next);
        return -1;
    }
    memcpy(unshot, b0, sizeof *unshot * 3 * (size_t)t->n_nodes);
    memset(e_ind, 0, sizeof *e_ind * 3 * (size_t)t->n_leaves);
    for (int b = 0; b < bounces; b++) {
        for (int i = 0; i < t->n_leaves; i++) {
            double E[3] = {0, 0, 0};
            for (uint32_t k = L->offset[i]; k < L->offset[i + 1]; k++)
                for (int j = 0; j < 3; j++)
                    E[j] += (double)L->weight[k] * unshot[3 * L->target[k] + j];
            for (int j = 0; j < 3; j++) {
                e_ind[3 * i + j] += (float)E[j];
                next[3 * i + j] = g->albedo[3 * i + j] / (float)M_PI * (float)E[j];
            }
        }
        rad_pullup(t, next);
        float *tmp = unshot;
        unshot = next, next = tmp;
    }
    free(unshot), free(next);
    return 0;
}
