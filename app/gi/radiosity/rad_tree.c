/* The pointer-less per-chart quadtrees (rad_tree.h). */
#include "rad_tree.h"

#include <stdlib.h>
#include <string.h>

int rad_tree_parent(const rad_tree *t, int node)
{
    int c = t->node_chart[node], l = t->node_level[node];
    if (l + 1 >= t->chart_levels[c])
        return -1;
    return t->off[c][l + 1] + (node - t->off[c][l]) / 4;
}

int rad_tree_children(const rad_tree *t, int node, int *first)
{
    int c = t->node_chart[node], l = t->node_level[node];
    *first = -1;
    if (l == 0)
        return 0;
    int j = node - t->off[c][l];
    int left = t->cnt[c][l - 1] - 4 * j;
    *first = t->off[c][l - 1] + 4 * j;
    return left < 4 ? left : 4;
}

int rad_tree_build(rad_tree *t, const rad_mesh *m, gk_err *e)
{
    memset(t, 0, sizeof *t);
    int nc = m->n_charts;
    t->n_charts = nc;
    t->n_leaves = m->n_verts;
    t->chart_levels = calloc((size_t)nc + 1, sizeof *t->chart_levels);
    t->off = calloc((size_t)nc + 1, sizeof *t->off);
    t->cnt = calloc((size_t)nc + 1, sizeof *t->cnt);
    t->roots = calloc((size_t)nc + 1, sizeof *t->roots);
    if (!t->chart_levels || !t->off || !t->cnt || !t->roots) {
        rad_tree_free(t);
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory for the hierarchy");
    }
    /* level counts per chart: ceil(n / 4) until one node is left */
    for (int c = 0; c < nc; c++) {
        int n = m->charts[c].n_verts, l = 0;
        t->cnt[c][l++] = n;
        while (n > 1 && l < RAD_MAX_LEVELS) {
            n = (n + 3) / 4;
            t->cnt[c][l++] = n;
        }
        if (n > 1) {
            rad_tree_free(t);
            return gk_fail(e, GK_EINPUT, "radiosity: chart %d has too many vertices (%d) for %d levels", c,
                           m->charts[c].n_verts, RAD_MAX_LEVELS);
        }
        t->chart_levels[c] = l;
        if (l > t->n_levels)
            t->n_levels = l;
    }
    /* offsets: level by level, chart after chart (leaves: the mesh's own vertex ranges) */
    int next = 0;
    for (int l = 0; l < t->n_levels; l++) {
        t->level_first[l] = next;
        for (int c = 0; c < nc; c++)
            if (l < t->chart_levels[c]) {
                t->off[c][l] = l == 0 ? m->charts[c].first_vert : next;
                next += t->cnt[c][l];
            }
    }
    t->level_first[t->n_levels] = next;
    t->n_nodes = next;
    size_t nn = (size_t)next;
    t->node_chart = malloc(sizeof *t->node_chart * nn);
    t->node_level = malloc(nn);
    t->pos = malloc(sizeof *t->pos * nn);
    t->nrm = malloc(sizeof *t->nrm * nn);
    t->area = malloc(sizeof *t->area * nn);
    if (!t->node_chart || !t->node_level || !t->pos || !t->nrm || !t->area) {
        rad_tree_free(t);
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory for %d nodes", next);
    }
    for (int c = 0; c < nc; c++)
        for (int l = 0; l < t->chart_levels[c]; l++)
            for (int j = 0; j < t->cnt[c][l]; j++) {
                t->node_chart[t->off[c][l] + j] = c;
                t->node_level[t->off[c][l] + j] = (unsigned char)l;
            }
    for (int i = 0; i < m->n_verts; i++)
        t->area[i] = m->area[i];
    /* inner areas: sums, once (the refit keeps them) */
    for (int i = m->n_verts; i < next; i++) {
        int first, k = rad_tree_children(t, i, &first);
        float a = 0.0f;
        for (int q = first; q < first + k; q++)
            a += t->area[q];
        t->area[i] = a;
    }
    rad_tree_refit(t, m);
    for (int c = 0; c < nc; c++)
        t->roots[c] = t->off[c][t->chart_levels[c] - 1];
    return 0;
}

void rad_tree_refit(rad_tree *t, const rad_mesh *m)
{
    for (int i = 0; i < m->n_verts; i++) {
        t->pos[i] = m->centre[i];
        t->nrm[i] = m->charts[m->chart[i]].normal;
    }
    /* bottom-up: children precede their parents in the index */
    for (int i = m->n_verts; i < t->n_nodes; i++) {
        int first, k = rad_tree_children(t, i, &first);
        vec3 p = v3(0, 0, 0), n = v3(0, 0, 0);
        for (int q = first; q < first + k; q++)
            p = v3_add(p, t->pos[q]), n = v3_add(n, t->nrm[q]);
        t->pos[i] = v3_scale(p, 1.0f / (float)k);
        t->nrm[i] = v3_norm(n);
    }
}

void rad_tree_free(rad_tree *t)
{
    free(t->chart_levels), free(t->off), free(t->cnt), free(t->node_chart), free(t->node_level);
    free(t->pos), free(t->nrm), free(t->area), free(t->roots);
    memset(t, 0, sizeof *t);
}
