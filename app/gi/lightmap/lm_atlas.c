/* Light-map parameterisation: planar charts per (node, mesh), shelf packing, gutters (lm_atlas.h). */
#include "lm_atlas.h"

#define LM_CONTRIB_COS 0.906f /* cos 25 degrees */
#define LM_CONTRIB_MAX 64

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct tri_key {
    long long k[5];          /* quantised normal (3), plane offset, region (scene/wall_split.h) */
    int tri;
} tri_key;

static int cmp_key(const void *pa, const void *pb)
{
    const tri_key *a = pa, *b = pb;
    for (int i = 0; i < 5; i++)
        if (a->k[i] != b->k[i])
            return a->k[i] < b->k[i] ? -1 : 1;
    return a->tri < b->tri ? -1 : a->tri > b->tri;
}

static vec3 mesh_pos(const gk_mesh *m, uint32_t tri, int k)
{
    const float *p = &m->positions[3 * (size_t)m->indices[3 * (size_t)tri + (size_t)k]];
    return v3(p[0], p[1], p[2]);
}

static const gk_material *mesh_material(const gk_scene *s, const gk_mesh *m)
{
    return &s->materials[m->material >= 0 && m->material < s->n_materials ? m->material : 0];
}

/* A chart under construction: its triangles (indices into the mesh) and its frame. */
typedef struct proto {
    int node, mesh, tri_first, tri_count; /* into the key array of its mesh pass */
    vec3 n, tu, tv;
    float d;
    float umin, umax, vmin, vmax;
    float world_u, world_v;               /* world metres per object unit along tu, tv */
    float area;
    vec3 wmin, wmax, wn;
} proto;

static void frame_of(vec3 n, vec3 *tu, vec3 *tv)
{
    vec3 a = fabsf(n.x) <= fabsf(n.y) && fabsf(n.x) <= fabsf(n.z) ? v3(1, 0, 0)
             : fabsf(n.y) <= fabsf(n.z)                          ? v3(0, 1, 0)
                                                                 : v3(0, 0, 1);
    *tu = v3_norm(v3_cross(a, n));
    *tv = v3_cross(n, *tu);
}

static int cmp_height_desc(const void *pa, const void *pb, void *ctx)
{
    const lm_chart *c = ctx;
    int a = *(const int *)pa, b = *(const int *)pb;
    if (c[a].h != c[b].h)
        return c[b].h - c[a].h;
    return a - b;
}

/* Shelf packing of the charts' rects (+ gutters) into a width chosen from their total area. */
static int pack(lm_atlas *a, gk_err *e)
{
    long total = 0;
    int widest = 0;
    for (int i = 0; i < a->n_charts; i++) {
        int w = a->charts[i].w + 2 * LM_GUTTER, h = a->charts[i].h + 2 * LM_GUTTER;
        total += (long)w * h;
        widest = w > widest ? w : widest;
    }
    int width = (int)ceil(sqrt((double)total) * 1.1);
    width = width < widest ? widest : width;
    int *order = malloc(sizeof *order * (size_t)(a->n_charts > 0 ? a->n_charts : 1));
    if (!order)
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory packing the atlas");
    for (int i = 0; i < a->n_charts; i++)
        order[i] = i;
    qsort_r(order, (size_t)a->n_charts, sizeof *order, cmp_height_desc, a->charts);
    int x = 0, y = 0, shelf = 0;
    for (int k = 0; k < a->n_charts; k++) {
        lm_chart *c = &a->charts[order[k]];
        int w = c->w + 2 * LM_GUTTER, h = c->h + 2 * LM_GUTTER;
        if (x + w > width) {
            y += shelf;
            x = 0, shelf = 0;
        }
        c->x = x + LM_GUTTER, c->y = y + LM_GUTTER;
        x += w;
        shelf = h > shelf ? h : shelf;
    }
    free(order);
    a->width = width;
    a->height = y + shelf;
    if (a->width > LM_MAX_ATLAS || a->height > LM_MAX_ATLAS)
        return 1; /* the caller coarsens the texel */
    return 0;
}

static int build_protos(const gk_scene *s, const gk_wall_regions *regions, proto **out, int *n_out, tri_key **keys_out,
                        gk_err *e)
{
    size_t total = 0;
    for (int i = 0; i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++)
            total += s->meshes[m].n_triangles;
    tri_key *keys = malloc(sizeof *keys * (total ? total : 1));
    proto *ps = NULL;
    int n = 0, cap = 0;
    if (!keys)
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory charting the scene");
    vec3 ext = v3_sub(s->bmax, s->bmin);
    size_t at = 0;
    for (int i = 0; i < s->n_nodes; i++) {
        const gk_node *nd = &s->nodes[i];
        for (int m = nd->mesh_first; m < nd->mesh_first + nd->mesh_count; m++) {
            const gk_mesh *mesh = &s->meshes[m];
            if (mesh->n_triangles == 0 || mesh_material(s, mesh)->light_proxy)
                continue;
            /* plane offsets equal within 1e-4 of the mesh's (object) diagonal */
            float diag = v3_len(v3_sub(mesh->bmax, mesh->bmin));
            float dq = 1e-4f * (diag > 0 ? diag : (v3_len(ext) > 0 ? v3_len(ext) : 1.0f));
            size_t first = at;
            for (uint32_t t = 0; t < mesh->n_triangles; t++) {
                vec3 p0 = mesh_pos(mesh, t, 0), p1 = mesh_pos(mesh, t, 1), p2 = mesh_pos(mesh, t, 2);
                vec3 c = v3_cross(v3_sub(p1, p0), v3_sub(p2, p0));
                float len = v3_len(c);
                if (!(len > 0.0f))
                    continue;
                vec3 nn = v3_scale(c, 1.0f / len);
                keys[at].k[0] = llroundf(nn.x * 1e4f);
                keys[at].k[1] = llroundf(nn.y * 1e4f);
                keys[at].k[2] = llroundf(nn.z * 1e4f);
                keys[at].k[3] = llroundf(v3_dot(nn, p0) / dq);
                keys[at].k[4] = regions && m < regions->n_meshes && regions->tri[m] ? regions->tri[m][t] : 0;
                keys[at].tri = (int)t;
                at++;
            }
            qsort(keys + first, at - first, sizeof *keys, cmp_key);
            for (size_t k = first; k < at;) {
                size_t j = k;
                while (j < at && !memcmp(keys[j].k, keys[k].k, sizeof keys[k].k))
                    j++;
                if (n == cap) {
                    cap = cap ? 2 * cap : 64;
                    proto *np = realloc(ps, sizeof *ps * (size_t)cap);
                    if (!np) {
                        free(ps), free(keys);
                        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory charting the scene");
                    }
                    ps = np;
                }
                proto *p = &ps[n++];
                memset(p, 0, sizeof *p);
                p->node = i, p->mesh = m, p->tri_first = (int)k, p->tri_count = (int)(j - k);
                vec3 t0 = mesh_pos(mesh, (uint32_t)keys[k].tri, 0);
                p->n = v3_norm(v3_cross(v3_sub(mesh_pos(mesh, (uint32_t)keys[k].tri, 1), t0),
                                        v3_sub(mesh_pos(mesh, (uint32_t)keys[k].tri, 2), t0)));
                p->d = v3_dot(p->n, t0);
                frame_of(p->n, &p->tu, &p->tv);
                p->umin = p->vmin = INFINITY, p->umax = p->vmax = -INFINITY;
                p->wmin = v3(INFINITY, INFINITY, INFINITY), p->wmax = v3(-INFINITY, -INFINITY, -INFINITY);
                p->wn = v3_norm(m4_dir(m4_transpose(m4_inverse(nd->world)), p->n));
                for (size_t q = k; q < j; q++) {
                    vec3 w[3];
                    for (int v = 0; v < 3; v++) {
                        vec3 pv = mesh_pos(mesh, (uint32_t)keys[q].tri, v);
                        float u = v3_dot(pv, p->tu), vv = v3_dot(pv, p->tv);
                        p->umin = fminf(p->umin, u), p->umax = fmaxf(p->umax, u);
                        p->vmin = fminf(p->vmin, vv), p->vmax = fmaxf(p->vmax, vv);
                        w[v] = m4_point(nd->world, pv);
                        p->wmin = v3_min(p->wmin, w[v]), p->wmax = v3_max(p->wmax, w[v]);
                    }
                    p->area += 0.5f * v3_len(v3_cross(v3_sub(w[1], w[0]), v3_sub(w[2], w[0])));
                }
                p->world_u = v3_len(m4_dir(nd->world, p->tu));
                p->world_v = v3_len(m4_dir(nd->world, p->tv));
                k = j;
            }
        }
    }
    *out = ps, *n_out = n, *keys_out = keys;
    return 0;
}

static void size_charts(lm_atlas *a, const proto *ps, float texel)
{
    for (int i = 0; i < a->n_charts; i++) {
        const proto *p = &ps[i];
        lm_chart *c = &a->charts[i];
        float wu = (p->umax - p->umin) * p->world_u, wv = (p->vmax - p->vmin) * p->world_v;
        c->w = (int)ceilf(wu / texel - 1e-4f);
        c->h = (int)ceilf(wv / texel - 1e-4f);
        c->w = c->w < 1 ? 1 : c->w;
        c->h = c->h < 1 ? 1 : c->h;
        c->su = p->umax > p->umin ? (float)c->w / (p->umax - p->umin) : 1.0f;
        c->sv = p->vmax > p->vmin ? (float)c->h / (p->vmax - p->vmin) : 1.0f;
    }
}

/* Charts that touch (bounds within a hair of each other) and face the same way (25 degrees): the
   facets of one curved or split surface. */
static bool touches(const lm_chart *c, const lm_chart *d, float hair)
{
    if (v3_dot(c->wn, d->wn) < LM_CONTRIB_COS)
        return false;
    vec3 gap = v3_max(v3_sub(d->wmin, c->wmax), v3_sub(c->wmin, d->wmax));
    return gap.x <= hair && gap.y <= hair && gap.z <= hair;
}

/* The touching pairs through a uniform grid (64 cells along the longest side), then for each
   chart a breadth-first walk over touching charts that face within 25 degrees of it, until their
   area reaches a texel's (or LM_CONTRIB_MAX charts): its contributors. */
static int find_contributors(lm_atlas *a)
{
    int n = a->n_charts;
    a->contrib_first = calloc((size_t)n + 1, sizeof *a->contrib_first);
    if (!a->contrib_first)
        return -1;
    if (n == 0)
        return 0;
    vec3 lo = a->charts[0].wmin, hi = a->charts[0].wmax;
    for (int i = 1; i < n; i++)
        lo = v3_min(lo, a->charts[i].wmin), hi = v3_max(hi, a->charts[i].wmax);
    vec3 ext = v3_sub(hi, lo);
    float hair = 1e-4f * v3_len(ext);
    float cell = fmaxf(v3_maxc(ext) / 64.0f, 1e-6f);
    int gx = (int)(ext.x / cell) + 1, gy = (int)(ext.y / cell) + 1, gz = (int)(ext.z / cell) + 1;
    long cells = (long)gx * gy * gz;
    int *count = calloc((size_t)cells + 1, sizeof *count), *mark = malloc(sizeof *mark * (size_t)n);
    int *list = NULL, *adj = NULL, *adj_first = calloc((size_t)n + 1, sizeof *adj_first);
    int *queue = malloc(sizeof *queue * (LM_CONTRIB_MAX + 1)), *out = NULL;
    long total = 0, adj_n = 0, adj_cap = 0, out_n = 0, out_cap = 0;
#define CELL_RANGE(ch)                                                                                               \
    int x0 = (int)(((ch)->wmin.x - hair - lo.x) / cell), x1 = (int)(((ch)->wmax.x + hair - lo.x) / cell);           \
    int y0 = (int)(((ch)->wmin.y - hair - lo.y) / cell), y1 = (int)(((ch)->wmax.y + hair - lo.y) / cell);           \
    int z0 = (int)(((ch)->wmin.z - hair - lo.z) / cell), z1 = (int)(((ch)->wmax.z + hair - lo.z) / cell);           \
    x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0, z0 = z0 < 0 ? 0 : z0;                                             \
    x1 = x1 >= gx ? gx - 1 : x1, y1 = y1 >= gy ? gy - 1 : y1, z1 = z1 >= gz ? gz - 1 : z1;
    if (!count || !mark || !adj_first || !queue)
        goto fail;
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < n; i++) {
            CELL_RANGE(&a->charts[i]);
            for (int z = z0; z <= z1; z++)
                for (int y = y0; y <= y1; y++)
                    for (int x = x0; x <= x1; x++) {
                        long k = ((long)z * gy + y) * gx + x;
                        if (pass == 0)
                            count[k + 1]++;
                        else
                            list[count[k]++] = i;
                    }
        }
        if (pass == 0) {
            for (long k = 0; k < cells; k++)
                count[k + 1] += count[k];
            total = count[cells];
            list = malloc(sizeof *list * (size_t)(total > 0 ? total : 1));
            if (!list)
                goto fail;
        }
    }
    /* count[k] is now the end of cell k's list; its start is count[k - 1] (0 for the first) */
    for (int i = 0; i < n; i++)
        mark[i] = -1;
    for (int i = 0; i < n; i++) {
        const lm_chart *c = &a->charts[i];
        adj_first[i] = (int)adj_n;
        CELL_RANGE(c);
        for (int z = z0; z <= z1; z++)
            for (int y = y0; y <= y1; y++)
                for (int x = x0; x <= x1; x++) {
                    long k = ((long)z * gy + y) * gx + x;
                    for (long q = k > 0 ? count[k - 1] : 0; q < count[k]; q++) {
                        int j = list[q];
                        if (j == i || mark[j] == i || !touches(c, &a->charts[j], hair))
                            continue;
                        mark[j] = i;
                        if (adj_n == adj_cap) {
                            adj_cap = adj_cap ? 2 * adj_cap : 1024;
                            int *na = realloc(adj, sizeof *adj * (size_t)adj_cap);
                            if (!na)
                                goto fail;
                            adj = na;
                        }
                        adj[adj_n++] = j;
                    }
                }
    }
    adj_first[n] = (int)adj_n;
#undef CELL_RANGE
    float texel_area = a->texel_size * a->texel_size;
    for (int i = 0; i < n; i++)
        mark[i] = -1;
    for (int i = 0; i < n; i++) {
        const lm_chart *c = &a->charts[i];
        a->contrib_first[i] = (int)out_n;
        int head = 0, tail = 0;
        float area = c->area;
        queue[tail++] = i;
        mark[i] = i;
        while (head < tail && area < texel_area && tail <= LM_CONTRIB_MAX) {
            int u = queue[head++];
            for (int q = adj_first[u]; q < adj_first[u + 1] && area < texel_area && tail <= LM_CONTRIB_MAX; q++) {
                int d = adj[q];
                if (mark[d] == i || v3_dot(c->wn, a->charts[d].wn) < LM_CONTRIB_COS)
                    continue;
                mark[d] = i;
                queue[tail++] = d;
                area += a->charts[d].area;
                if (out_n == out_cap) {
                    out_cap = out_cap ? 2 * out_cap : 256;
                    int *no = realloc(out, sizeof *out * (size_t)out_cap);
                    if (!no)
                        goto fail;
                    out = no;
                }
                out[out_n++] = d;
            }
        }
    }
    a->contrib_first[n] = (int)out_n;
    a->contrib = out ? out : malloc(sizeof(int));
    free(count), free(mark), free(list), free(adj), free(adj_first), free(queue);
    return a->contrib ? 0 : -1;
fail:
    free(count), free(mark), free(list), free(adj), free(adj_first), free(queue), free(out);
    return -1;
}

int lm_atlas_build(lm_atlas *a, const gk_scene *s, int texels_across, gk_err *e)
{
    return lm_atlas_build_regions(a, s, texels_across, NULL, e);
}

int lm_atlas_build_regions(lm_atlas *a, const gk_scene *s, int texels_across, const gk_wall_regions *regions, gk_err *e)
{
    memset(a, 0, sizeof *a);
    a->texels_across = texels_across < 1 ? 1 : texels_across;
    proto *ps = NULL;
    tri_key *keys = NULL;
    int np = 0;
    if (build_protos(s, regions, &ps, &np, &keys, e))
        return -1;
    a->n_charts = np;
    a->charts = calloc((size_t)(np > 0 ? np : 1), sizeof *a->charts);
    if (!a->charts)
        goto oom;
    float largest = 0.0f;
    for (int i = 0; i < np; i++) {
        const proto *p = &ps[i];
        lm_chart *c = &a->charts[i];
        c->node = p->node, c->mesh = p->mesh, c->material = s->meshes[p->mesh].material;
        c->n = p->n, c->tu = p->tu, c->tv = p->tv;
        c->u0 = p->umin, c->v0 = p->vmin;
        c->plane_d = p->d;
        c->area = p->area;
        c->wmin = p->wmin, c->wmax = p->wmax, c->wn = p->wn;
        largest = fmaxf(largest, fmaxf((p->umax - p->umin) * p->world_u, (p->vmax - p->vmin) * p->world_v));
    }
    /* The seed's rule: the largest surface gets texels_across texels along its longer side. */
    float texel = largest > 0.0f ? largest / (float)a->texels_across : 1.0f;
    for (;;) {
        size_charts(a, ps, texel);
        int rc = pack(a, e);
        if (rc < 0)
            goto fail;
        if (rc == 0)
            break;
        texel *= 1.5f; /* too many texels for one atlas: coarser, until it fits */
    }
    a->texel_size = texel;
    if (find_contributors(a))
        goto oom;

    /* Vertices: every drawn (node, mesh), charted or not, in node order. */
    int n_draws = 0, n_verts = 0;
    for (int i = 0; i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++)
            if (s->meshes[m].n_triangles > 0)
                n_draws++, n_verts += 3 * (int)s->meshes[m].n_triangles;
    a->draws = calloc((size_t)(n_draws > 0 ? n_draws : 1), sizeof *a->draws);
    a->verts = malloc(sizeof *a->verts * LM_VERT_FLOATS * (size_t)(n_verts > 0 ? n_verts : 1));
    a->vert_chart = malloc(sizeof *a->vert_chart * (size_t)(n_verts / 3 + 1));
    a->texel_chart = malloc(sizeof *a->texel_chart * (size_t)a->width * (size_t)(a->height ? a->height : 1));
    int *tri_chart = NULL;
    if (!a->draws || !a->verts || !a->vert_chart || !a->texel_chart)
        goto oom;
    for (long t = 0; t < (long)a->width * a->height; t++)
        a->texel_chart[t] = -1;
    for (int i = 0; i < np; i++) {
        const lm_chart *c = &a->charts[i];
        for (int y = c->y - LM_GUTTER; y < c->y + c->h + LM_GUTTER; y++)
            for (int x = c->x - LM_GUTTER; x < c->x + c->w + LM_GUTTER; x++)
                a->texel_chart[(long)y * a->width + x] = i;
    }
    /* ref order: as gk_ref_scene_build flattens (nodes, meshes, triangles; proxies and
       degenerate-after-transform triangles left out) */
    uint32_t n_ref = 0;
    for (int i = 0; i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++)
            n_ref += s->meshes[m].n_triangles;
    a->ref_chart = malloc(sizeof *a->ref_chart * (n_ref ? n_ref : 1));
    if (!a->ref_chart)
        goto oom;
    int pi = 0, v = 0;
    for (int i = 0; i < s->n_nodes; i++) {
        const gk_node *nd = &s->nodes[i];
        for (int m = nd->mesh_first; m < nd->mesh_first + nd->mesh_count; m++) {
            const gk_mesh *mesh = &s->meshes[m];
            if (mesh->n_triangles == 0)
                continue;
            bool proxy = mesh_material(s, mesh)->light_proxy;
            lm_draw *d = &a->draws[a->n_draws++];
            d->node = i, d->mesh = m, d->first_vert = v, d->n_verts = 3 * (int)mesh->n_triangles, d->charted = !proxy;
            free(tri_chart);
            tri_chart = malloc(sizeof *tri_chart * mesh->n_triangles);
            if (!tri_chart)
                goto oom;
            for (uint32_t t = 0; t < mesh->n_triangles; t++)
                tri_chart[t] = -1;
            while (!proxy && pi < np && ps[pi].node == i && ps[pi].mesh == m) {
                for (int q = ps[pi].tri_first; q < ps[pi].tri_first + ps[pi].tri_count; q++)
                    tri_chart[keys[q].tri] = pi;
                pi++;
            }
            mat4 w = nd->world;
            for (uint32_t t = 0; t < mesh->n_triangles; t++) {
                int ci = tri_chart[t];
                a->vert_chart[v / 3] = ci;
                vec3 wp[3];
                for (int k = 0; k < 3; k++) {
                    vec3 p = mesh_pos(mesh, t, k);
                    wp[k] = m4_point(w, p);
                    float *o = &a->verts[(size_t)v * LM_VERT_FLOATS];
                    o[0] = p.x, o[1] = p.y, o[2] = p.z;
                    if (ci >= 0) {
                        float tx, ty;
                        lm_chart_texel(&a->charts[ci], p, &tx, &ty);
                        o[3] = tx / (float)a->width, o[4] = ty / (float)a->height;
                    } else {
                        o[3] = o[4] = -1.0f;
                    }
                    v++;
                }
                if (proxy)
                    continue;
                vec3 c = v3_cross(v3_sub(wp[1], wp[0]), v3_sub(wp[2], wp[0]));
                float len = v3_len(c);
                if (!(len > 1e-20f) || !isfinite(len))
                    continue;
                a->ref_chart[a->n_ref++] = ci;
            }
        }
    }
    a->n_verts = v;
    free(tri_chart);
    free(ps), free(keys);
    return 0;
oom:
    gk_fail(e, GK_ERUNTIME, "lightmap: out of memory building the light-map atlas");
fail:
    free(ps), free(keys);
    lm_atlas_free(a);
    return -1;
}

void lm_atlas_free(lm_atlas *a)
{
    free(a->charts), free(a->draws), free(a->verts), free(a->vert_chart), free(a->ref_chart), free(a->texel_chart);
    free(a->contrib_first), free(a->contrib);
    memset(a, 0, sizeof *a);
}

void lm_chart_texel(const lm_chart *c, vec3 p, float *tx, float *ty)
{
    /* the chart's points map onto [x, x + w] x [y, y + h]: clamped so rounding never reaches the
       gutter's outer half */
    float u = (v3_dot(p, c->tu) - c->u0) * c->su, v = (v3_dot(p, c->tv) - c->v0) * c->sv;
    u = fminf(fmaxf(u, 0.0f), (float)c->w), v = fminf(fmaxf(v, 0.0f), (float)c->h);
    *tx = (float)c->x + u, *ty = (float)c->y + v;
}

vec3 lm_chart_point(const lm_chart *c, int i, int j)
{
    float u = c->u0 + ((float)i + 0.5f) / c->su, v = c->v0 + ((float)j + 0.5f) / c->sv;
    /* on the plane: the frame's offset along n is that of the chart's triangles */
    return v3_add(v3_add(v3_scale(c->tu, u), v3_scale(c->tv, v)), v3_scale(c->n, c->plane_d));
}

void lm_atlas_dilate(const lm_atlas *a, float *tex, int ch)
{
    for (int i = 0; i < a->n_charts; i++) {
        const lm_chart *c = &a->charts[i];
        for (int y = c->y - LM_GUTTER; y < c->y + c->h + LM_GUTTER; y++)
            for (int x = c->x - LM_GUTTER; x < c->x + c->w + LM_GUTTER; x++) {
                if (x >= c->x && x < c->x + c->w && y >= c->y && y < c->y + c->h)
                    continue;
                int sx = x < c->x ? c->x : (x >= c->x + c->w ? c->x + c->w - 1 : x);
                int sy = y < c->y ? c->y : (y >= c->y + c->h ? c->y + c->h - 1 : y);
                memcpy(&tex[((size_t)y * (size_t)a->width + (size_t)x) * (size_t)ch],
                       &tex[((size_t)sy * (size_t)a->width + (size_t)sx) * (size_t)ch], sizeof(float) * (size_t)ch);
            }
    }
}
