/* The radiosity geometry bundle and the CPU bounces (rad_solve.h). */
#include "rad_solve.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

int rad_geometry_build(rad_geometry *g, const gk_scene *s, float edge, int max_verts, int n_face, rad_weight weight,
                       gk_err *e)
{
    return rad_geometry_build_regions(g, s, NULL, edge, max_verts, n_face, weight, e);
}

int rad_geometry_build_regions(rad_geometry *g, const gk_scene *s, const gk_wall_regions *regions, float edge,
                               int max_verts, int n_face, rad_weight weight, gk_err *e)
{
    memset(g, 0, sizeof *g);
    g->edge = edge, g->n_face = n_face, g->weight = weight;
    if (rad_mesh_build_regions(&g->mesh, s, regions, edge, max_verts, e))
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

/* a copy of n elements of size sz (NULL for NULL) */
static void *dup_array(const void *src, size_t n, size_t sz, bool *fail)
{
    if (!src)
        return NULL;
    void *p = malloc(n * sz + 1);
    if (!p) {
        *fail = true;
        return NULL;
    }
    memcpy(p, src, n * sz);
    return p;
}

int rad_geometry_clone(rad_geometry *d, const rad_geometry *g)
{
    *d = *g;
    bool fail = false;
    const rad_mesh *m = &g->mesh;
    size_t nv = (size_t)m->n_verts, nc = (size_t)m->n_charts;
    d->mesh.pos = dup_array(m->pos, nv, sizeof *m->pos, &fail);
    d->mesh.area = dup_array(m->area, nv, sizeof *m->area, &fail);
    d->mesh.centre = dup_array(m->centre, nv, sizeof *m->centre, &fail);
    d->mesh.chart = dup_array(m->chart, nv, sizeof *m->chart, &fail);
    d->mesh.tris = dup_array(m->tris, 3 * (size_t)m->n_tris, sizeof *m->tris, &fail);
    d->mesh.charts = dup_array(m->charts, nc, sizeof *m->charts, &fail);
    d->mesh.rest_pos = dup_array(m->rest_pos, nv, sizeof *m->rest_pos, &fail);
    d->mesh.rest_centre = dup_array(m->rest_centre, nv, sizeof *m->rest_centre, &fail);
    d->mesh.rest_world_inv = dup_array(m->rest_world_inv, (size_t)m->n_scene_nodes, sizeof *m->rest_world_inv, &fail);
    const rad_tree *t = &g->tree;
    size_t nn = (size_t)t->n_nodes, tc = (size_t)t->n_charts + 1;
    d->tree.chart_levels = dup_array(t->chart_levels, tc, sizeof *t->chart_levels, &fail);
    d->tree.off = dup_array(t->off, tc, sizeof *t->off, &fail);
    d->tree.cnt = dup_array(t->cnt, tc, sizeof *t->cnt, &fail);
    d->tree.roots = dup_array(t->roots, tc, sizeof *t->roots, &fail);
    d->tree.node_chart = dup_array(t->node_chart, nn, sizeof *t->node_chart, &fail);
    d->tree.node_level = dup_array(t->node_level, nn, sizeof *t->node_level, &fail);
    d->tree.pos = dup_array(t->pos, nn, sizeof *t->pos, &fail);
    d->tree.nrm = dup_array(t->nrm, nn, sizeof *t->nrm, &fail);
    d->tree.area = dup_array(t->area, nn, sizeof *t->area, &fail);
    const rad_links *L = &g->links;
    size_t nl = L->offset ? L->offset[L->n_leaves] : 0;
    d->links.offset = dup_array(L->offset, (size_t)L->n_leaves + 1, sizeof *L->offset, &fail);
    d->links.target = dup_array(L->target, nl, sizeof *L->target, &fail);
    d->links.weight = dup_array(L->weight, nl, sizeof *L->weight, &fail);
    d->links.empty = dup_array(L->empty, (size_t)L->n_leaves * (size_t)L->empty_words, sizeof *L->empty, &fail);
    d->albedo = dup_array(g->albedo, 3 * nv, sizeof *g->albedo, &fail);
    d->emission = dup_array(g->emission, 3 * nv, sizeof *g->emission, &fail);
    if (fail) {
        rad_geometry_free(d);
        return -1;
    }
    return 0;
}

int rad_geometry_refit(rad_geometry *g, const mat4 *worlds, int n_worlds)
{
    int moved = rad_mesh_refit(&g->mesh, worlds, n_worlds);
    if (moved)
        rad_tree_refit(&g->tree, &g->mesh);
    return moved;
}

int rad_geometry_moving_charts(const rad_geometry *g)
{
    int n = 0;
    for (int c = 0; c < g->mesh.n_charts; c++)
        n += g->mesh.charts[c].moving;
    return n;
}

int rad_geometry_relink(rad_geometry *g, rad_link_cache *cache, gk_err *e)
{
    bool *moving = malloc(sizeof *moving * (size_t)(g->mesh.n_charts + 1));
    if (!moving)
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory relinking");
    for (int c = 0; c < g->mesh.n_charts; c++)
        moving[c] = g->mesh.charts[c].moving;
    rad_links fresh;
    int rc = rad_links_update(&fresh, &g->tree, g->n_face, g->weight, cache ? moving : NULL, cache, e);
    free(moving);
    if (rc)
        return -1;
    rad_links_free(&g->links);
    g->links = fresh;
    return 0;
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
