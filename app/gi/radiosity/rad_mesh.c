/* Refinement, charts and surfels (rad_mesh.h). */
#include "rad_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define COPLANAR_COS 0.99984770f /* cos 1°: face normals this close are one plane */

typedef struct src_tri {
    vec3 p[3];
    vec3 n;          /* unit face normal, turned to the side the vertex normals face */
    float area;
    int material;
    int node;        /* the scene node that draws it: a chart moves with one node (refit) */
    uint32_t region; /* its side of the walls that cut its mesh (scene/wall_split.h; 0: uncut) */
} src_tri;

int rad_mesh_segments(float len, float edge)
{
    if (!(edge > 0.0f) || !(len > edge))
        return 1;
    float n = ceilf(len / edge - 1e-4f); /* an edge of exactly k targets is k segments */
    return n < 1.0f ? 1 : (int)n;
}

/* ---- welding by quantised position (sort, then equal keys are one vertex) ------------------- */
typedef struct qkey { int64_t k[3]; int idx; } qkey;

static int cmp_qkey(const void *a, const void *b)
{
    const qkey *x = a, *y = b;
    for (int i = 0; i < 3; i++)
        if (x->k[i] != y->k[i])
            return x->k[i] < y->k[i] ? -1 : 1;
    return x->idx - y->idx;
}

static qkey quantise(vec3 p, float q, int idx)
{
    return (qkey){{(int64_t)llroundf(p.x / q), (int64_t)llroundf(p.y / q), (int64_t)llroundf(p.z / q)}, idx};
}

/* ids[i] := the welded id of point i; returns the number of distinct points (-1: out of memory). */
static int weld(const vec3 *pts, int n, float q, int *ids)
{
    qkey *keys = malloc(sizeof *keys * (size_t)(n > 0 ? n : 1));
    if (!keys)
        return -1;
    for (int i = 0; i < n; i++)
        keys[i] = quantise(pts[i], q, i);
    qsort(keys, (size_t)n, sizeof *keys, cmp_qkey);
    int id = -1;
    for (int i = 0; i < n; i++) {
        if (i == 0 || memcmp(keys[i].k, keys[i - 1].k, sizeof keys[i].k))
            id++;
        ids[keys[i].idx] = id;
    }
    free(keys);
    return id + 1;
}

/* ---- charts: union-find over shared edges of coplanar triangles of one material ------------- */
static int find(int *parent, int i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

typedef struct edge_ref { int a, b, tri; } edge_ref;

static int cmp_edge(const void *x, const void *y)
{
    const edge_ref *p = x, *q = y;
    if (p->a != q->a)
        return p->a - q->a;
    if (p->b != q->b)
        return p->b - q->b;
    return p->tri - q->tri;
}

static int collect(const gk_scene *s, const gk_wall_regions *regions, src_tri **out, int *n_out, double *area_out)
{
    int cap = 0, n = 0;
    src_tri *t = NULL;
    double area = 0.0;
    for (int ni = 0; ni < s->n_nodes; ni++) {
        const gk_node *nd = &s->nodes[ni];
        mat4 w = nd->world, nw = m4_transpose(m4_inverse(w));
        for (int mi = nd->mesh_first; mi < nd->mesh_first + nd->mesh_count; mi++) {
            const gk_mesh *m = &s->meshes[mi];
            int mat = m->material >= 0 && m->material < s->n_materials ? m->material : 0;
            if (s->materials[mat].light_proxy)
                continue; /* the area light stands in for it (scene.h) */
            for (uint32_t k = 0; k < m->n_triangles; k++) {
                src_tri st;
                vec3 ns = v3(0, 0, 0);
                for (int c = 0; c < 3; c++) {
                    uint32_t vi = m->indices[3 * k + (uint32_t)c];
                    const float *p = &m->positions[3 * vi], *q = &m->normals[3 * vi];
                    st.p[c] = m4_point(w, v3(p[0], p[1], p[2]));
                    ns = v3_add(ns, m4_dir(nw, v3(q[0], q[1], q[2])));
                }
                vec3 c = v3_cross(v3_sub(st.p[1], st.p[0]), v3_sub(st.p[2], st.p[0]));
                float len = v3_len(c);
                if (!(len > 0.0f))
                    continue;
                if (v3_dot(c, ns) < 0.0f) { /* wound against its normals: turn it to face them */
                    vec3 tmp = st.p[1];
                    st.p[1] = st.p[2], st.p[2] = tmp;
                    c = v3_scale(c, -1.0f);
                }
                st.n = v3_scale(c, 1.0f / len);
                st.area = 0.5f * len;
                st.material = mat;
                st.node = ni;
                st.region = regions && mi < regions->n_meshes && regions->tri[mi] ? regions->tri[mi][k] : 0;
                if (n == cap) {
                    cap = cap ? 2 * cap : 256;
                    src_tri *g = realloc(t, sizeof *t * (size_t)cap);
                    if (!g) {
                        free(t);
                        return -1;
                    }
                    t = g;
                }
                t[n++] = st;
                area += st.area;
            }
        }
    }
    *out = t, *n_out = n, *area_out = area;
    return 0;
}

/* chart_of[i] for every source triangle; returns the chart count (-1: out of memory). */
static int make_charts(const src_tri *t, int n, float q, int *chart_of)
{
    int *ids = malloc(sizeof *ids * (size_t)(3 * n + 1)), *parent = malloc(sizeof *parent * (size_t)(n + 1));
    vec3 *pts = malloc(sizeof *pts * (size_t)(3 * n + 1));
    edge_ref *edges = malloc(sizeof *edges * (size_t)(3 * n + 1));
    int charts = -1;
    if (!ids || !parent || !pts || !edges)
        goto out;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            pts[3 * i + c] = t[i].p[c];
    if (weld(pts, 3 * n, q, ids) < 0)
        goto out;
    for (int i = 0; i < n; i++) {
        parent[i] = i;
        for (int c = 0; c < 3; c++) {
            int a = ids[3 * i + c], b = ids[3 * i + (c + 1) % 3];
            edges[3 * i + c] = (edge_ref){a < b ? a : b, a < b ? b : a, i};
        }
    }
    qsort(edges, (size_t)(3 * n), sizeof *edges, cmp_edge);
    for (int i = 0; i + 1 < 3 * n; i++)
        for (int j = i + 1; j < 3 * n && edges[j].a == edges[i].a && edges[j].b == edges[i].b; j++) {
            const src_tri *x = &t[edges[i].tri], *y = &t[edges[j].tri];
            if (x->material == y->material && x->node == y->node && x->region == y->region &&
                v3_dot(x->n, y->n) > COPLANAR_COS) {
                int rx = find(parent, edges[i].tri), ry = find(parent, edges[j].tri);
                if (rx != ry)
                    parent[rx > ry ? rx : ry] = rx < ry ? rx : ry;
            }
        }
    charts = 0;
    for (int i = 0; i < n; i++)
        chart_of[i] = find(parent, i) == i ? charts++ : -1;
    for (int i = 0; i < n; i++)
        chart_of[i] = chart_of[find(parent, i)];
out:
    free(ids), free(parent), free(pts), free(edges);
    return charts;
}

static uint32_t spread_bits(uint32_t x)
{
    x &= 0xFFFFu;
    x = (x | (x << 8)) & 0x00FF00FFu;
    x = (x | (x << 4)) & 0x0F0F0F0Fu;
    x = (x | (x << 2)) & 0x33333333u;
    x = (x | (x << 1)) & 0x55555555u;
    return x;
}

typedef struct morton_ref { uint32_t code; int idx; } morton_ref;

static int cmp_morton(const void *a, const void *b)
{
    const morton_ref *x = a, *y = b;
    if (x->code != y->code)
        return x->code < y->code ? -1 : 1;
    return x->idx - y->idx;
}

/* Refines the triangles of one chart into m (appending vertices and triangles). */
static int refine_chart(rad_mesh *m, const src_tri *t, const int *tris, int n_tris, float edge, float q,
                        int max_verts, int ci)
{
    /* candidate points (with duplicates along shared edges) and triangles over them */
    size_t n_pts = 0, n_sub = 0;
    for (int k = 0; k < n_tris; k++) {
        const src_tri *st = &t[tris[k]];
        float longest = fmaxf(v3_len(v3_sub(st->p[1], st->p[0])),
                              fmaxf(v3_len(v3_sub(st->p[2], st->p[1])), v3_len(v3_sub(st->p[0], st->p[2]))));
        size_t s = (size_t)rad_mesh_segments(longest, edge);
        n_pts += (s + 1) * (s + 2) / 2;
        n_sub += s * s;
        if (n_pts > (size_t)max_verts * 8u)
            return -2; /* far past the budget already */
    }
    vec3 *pts = malloc(sizeof *pts * (n_pts + 1));
    int *ids = malloc(sizeof *ids * (n_pts + 1));
    uint32_t *sub = malloc(sizeof *sub * 3 * (n_sub + 1));
    if (!pts || !ids || !sub) {
        free(pts), free(ids), free(sub);
        return -1;
    }
    size_t np = 0, ns = 0;
    for (int k = 0; k < n_tris; k++) {
        const src_tri *st = &t[tris[k]];
        float longest = fmaxf(v3_len(v3_sub(st->p[1], st->p[0])),
                              fmaxf(v3_len(v3_sub(st->p[2], st->p[1])), v3_len(v3_sub(st->p[0], st->p[2]))));
        int s = rad_mesh_segments(longest, edge);
        vec3 e1 = v3_sub(st->p[1], st->p[0]), e2 = v3_sub(st->p[2], st->p[0]);
        size_t base = np;
        /* point (i, j), i + j <= s, at base + row offset: rows of j, each s + 1 - j long */
        for (int j = 0; j <= s; j++)
            for (int i = 0; i <= s - j; i++)
                pts[np++] = v3_add(st->p[0], v3_add(v3_scale(e1, (float)i / (float)s), v3_scale(e2, (float)j / (float)s)));
#define AT(i, j) (uint32_t)(base + (size_t)((j) * (s + 1) - (j) * ((j) - 1) / 2 + (i)))
        for (int j = 0; j < s; j++)
            for (int i = 0; i < s - j; i++) {
                sub[3 * ns] = AT(i, j), sub[3 * ns + 1] = AT(i + 1, j), sub[3 * ns + 2] = AT(i, j + 1), ns++;
                if (i + j < s - 1)
                    sub[3 * ns] = AT(i + 1, j), sub[3 * ns + 1] = AT(i + 1, j + 1), sub[3 * ns + 2] = AT(i, j + 1), ns++;
            }
#undef AT
    }
    int nv = weld(pts, (int)np, q, ids);
    if (nv < 0 || m->n_verts + nv > max_verts) {
        free(pts), free(ids), free(sub);
        return nv < 0 ? -1 : -2;
    }
    /* Morton order of the chart's plane coordinates */
    const rad_chart *c = &m->charts[ci];
    vec3 *uniq = calloc((size_t)nv, sizeof *uniq), *cen = calloc((size_t)nv, sizeof *cen);
    float *area = calloc((size_t)nv, sizeof *area);
    morton_ref *order = malloc(sizeof *order * (size_t)nv);
    int *rank = malloc(sizeof *rank * (size_t)nv);
    if (!uniq || !cen || !area || !order || !rank) {
        free(pts), free(ids), free(sub), free(uniq), free(cen), free(area), free(order), free(rank);
        return -1;
    }
    for (size_t i = 0; i < np; i++)
        uniq[ids[i]] = pts[i];
    for (size_t k = 0; k < ns; k++) {
        vec3 a = pts[sub[3 * k]], b = pts[sub[3 * k + 1]], d = pts[sub[3 * k + 2]];
        float third = v3_len(v3_cross(v3_sub(b, a), v3_sub(d, a))) / 6.0f;
        vec3 g = v3_scale(v3_add(a, v3_add(b, d)), 1.0f / 3.0f);
        for (int v = 0; v < 3; v++) {
            area[ids[sub[3 * k + (size_t)v]]] += third;
            cen[ids[sub[3 * k + (size_t)v]]] = v3_add(cen[ids[sub[3 * k + (size_t)v]]], v3_scale(g, third));
        }
    }
    float u0 = INFINITY, v0 = INFINITY, u1 = -INFINITY, v1 = -INFINITY;
    for (int i = 0; i < nv; i++) {
        float u = v3_dot(uniq[i], c->tu), v = v3_dot(uniq[i], c->tv);
        u0 = fminf(u0, u), u1 = fmaxf(u1, u), v0 = fminf(v0, v), v1 = fmaxf(v1, v);
    }
    float side = fmaxf(u1 - u0, v1 - v0);
    float scale = side > 0.0f ? 65535.0f / side : 0.0f;
    for (int i = 0; i < nv; i++) {
        uint32_t qu = (uint32_t)((v3_dot(uniq[i], c->tu) - u0) * scale + 0.5f);
        uint32_t qv = (uint32_t)((v3_dot(uniq[i], c->tv) - v0) * scale + 0.5f);
        order[i] = (morton_ref){spread_bits(qu) | (spread_bits(qv) << 1), i};
    }
    qsort(order, (size_t)nv, sizeof *order, cmp_morton);
    int first = m->n_verts;
    for (int r = 0; r < nv; r++) {
        int i = order[r].idx;
        rank[i] = r;
        m->pos[first + r] = uniq[i];
        m->area[first + r] = area[i];
        m->centre[first + r] = area[i] > 0.0f ? v3_scale(cen[i], 1.0f / area[i]) : uniq[i];
        m->chart[first + r] = ci;
    }
    for (size_t k = 0; k < ns; k++)
        for (int v = 0; v < 3; v++)
            m->tris[3 * ((size_t)m->n_tris + k) + (size_t)v] = (uint32_t)(first + rank[ids[sub[3 * k + (size_t)v]]]);
    m->n_tris += (int)ns;
    m->n_verts += nv;
    m->charts[ci].first_vert = first;
    m->charts[ci].n_verts = nv;
    free(pts), free(ids), free(sub), free(uniq), free(cen), free(area), free(order), free(rank);
    return 0;
}

/* The pose the mesh was built at, which every refit starts from (no drift over frames). */
static int keep_rest_pose(rad_mesh *m, const gk_scene *s)
{
    size_t nv = (size_t)(m->n_verts > 0 ? m->n_verts : 1);
    m->rest_pos = malloc(sizeof *m->rest_pos * nv);
    m->rest_centre = malloc(sizeof *m->rest_centre * nv);
    m->n_scene_nodes = s->n_nodes;
    m->rest_world_inv = malloc(sizeof *m->rest_world_inv * (size_t)(s->n_nodes > 0 ? s->n_nodes : 1));
    if (!m->rest_pos || !m->rest_centre || !m->rest_world_inv)
        return -1;
    memcpy(m->rest_pos, m->pos, sizeof *m->pos * (size_t)m->n_verts);
    memcpy(m->rest_centre, m->centre, sizeof *m->centre * (size_t)m->n_verts);
    for (int i = 0; i < s->n_nodes; i++)
        m->rest_world_inv[i] = m4_inverse(s->nodes[i].world);
    /* the pose as rad_mesh_refit computes it (world x world^-1 need not be exactly the identity in
       floats): a refit at the build pose then moves nothing */
    for (int c = 0; c < m->n_charts; c++)
        m->charts[c].pose = m4_mul(s->nodes[m->charts[c].node].world, m->rest_world_inv[m->charts[c].node]);
    return 0;
}

int rad_mesh_refit(rad_mesh *m, const mat4 *worlds, int n_worlds)
{
    int moved = 0;
    for (int c = 0; c < m->n_charts; c++) {
        rad_chart *ch = &m->charts[c];
        ch->refit_moved = false;
        if (!ch->moving || ch->node >= n_worlds || ch->node >= m->n_scene_nodes)
            continue;
        mat4 d = m4_mul(worlds[ch->node], m->rest_world_inv[ch->node]);
        if (memcmp(&d, &ch->pose, sizeof d) == 0)
            continue; /* the same pose as the last refit */
        ch->pose = d;
        ch->normal = v3_norm(m4_dir(m4_transpose(m4_inverse(d)), ch->rest_normal));
        for (int i = ch->first_vert; i < ch->first_vert + ch->n_verts; i++)
            m->pos[i] = m4_point(d, m->rest_pos[i]), m->centre[i] = m4_point(d, m->rest_centre[i]);
        ch->refit_moved = true;
        moved++;
    }
    return moved;
}

int rad_mesh_build(rad_mesh *m, const gk_scene *s, float edge, int max_verts, gk_err *e)
{
    return rad_mesh_build_regions(m, s, NULL, edge, max_verts, e);
}

int rad_mesh_build_regions(rad_mesh *m, const gk_scene *s, const gk_wall_regions *regions, float edge, int max_verts,
                           gk_err *e)
{
    memset(m, 0, sizeof *m);
    m->edge = edge;
    src_tri *t = NULL;
    int n = 0;
    if (collect(s, regions, &t, &n, &m->surface_area))
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory reading %s's triangles", s->name);
    m->n_source_tris = n;
    if (n == 0) {
        free(t);
        return gk_fail(e, GK_EINPUT, "radiosity: %s has no triangles to exchange light between", s->name);
    }
    vec3 ext = v3_sub(s->bmax, s->bmin);
    float diag = v3_len(ext) > 0.0f ? v3_len(ext) : 1.0f;
    float q = fminf(edge, diag) * 1e-3f; /* weld tolerance: far below any edge we make */
    int *chart_of = malloc(sizeof *chart_of * (size_t)n);
    int nc = chart_of ? make_charts(t, n, q, chart_of) : -1;
    if (nc < 0) {
        free(t), free(chart_of);
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory making charts");
    }
    m->n_charts = nc;
    m->charts = calloc((size_t)nc, sizeof *m->charts);
    /* triangles bucketed by chart */
    int *count = calloc((size_t)nc + 1, sizeof *count), *bucket = malloc(sizeof *bucket * (size_t)n);
    size_t sub_cap = 0;
    for (int i = 0; i < n; i++) {
        float longest = fmaxf(v3_len(v3_sub(t[i].p[1], t[i].p[0])),
                              fmaxf(v3_len(v3_sub(t[i].p[2], t[i].p[1])), v3_len(v3_sub(t[i].p[0], t[i].p[2]))));
        size_t sg = (size_t)rad_mesh_segments(longest, edge);
        sub_cap += sg * sg;
    }
    if (!m->charts || !count || !bucket || sub_cap > (size_t)max_verts * 16u) {
        bool big = m->charts && count && bucket;
        free(t), free(chart_of), free(count), free(bucket);
        rad_mesh_free(m);
        if (big)
            return gk_fail(e, GK_EINPUT, "radiosity: %s refined to edge %.3g would have ~%zu triangles, over the limit of %d vertices; use a longer edge",
                           s->name, (double)edge, sub_cap, max_verts);
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory making charts");
    }
    for (int i = 0; i < n; i++)
        count[chart_of[i] + 1]++;
    for (int c = 0; c < nc; c++)
        count[c + 1] += count[c];
    int *fill = calloc((size_t)nc, sizeof *fill);
    for (int i = 0; i < n && fill; i++)
        bucket[count[chart_of[i]] + fill[chart_of[i]]++] = i;
    m->pos = malloc(sizeof *m->pos * (size_t)max_verts);
    m->area = malloc(sizeof *m->area * (size_t)max_verts);
    m->centre = malloc(sizeof *m->centre * (size_t)max_verts);
    m->chart = malloc(sizeof *m->chart * (size_t)max_verts);
    m->tris = malloc(sizeof *m->tris * 3 * (sub_cap + 1));
    int rc = (!fill || !m->pos || !m->area || !m->centre || !m->chart || !m->tris) ? -1 : 0;
    for (int c = 0; c < nc && rc == 0; c++) {
        rad_chart *ch = &m->charts[c];
        vec3 nsum = v3(0, 0, 0);
        for (int k = count[c]; k < count[c + 1]; k++)
            nsum = v3_add(nsum, v3_scale(t[bucket[k]].n, t[bucket[k]].area));
        ch->normal = v3_norm(nsum);
        ch->material = t[bucket[count[c]]].material;
        ch->node = t[bucket[count[c]]].node;
        ch->moving = s->nodes[ch->node].animated;
        ch->rest_normal = ch->normal;
        vec3 a = fabsf(ch->normal.x) < 0.9f ? v3(1, 0, 0) : v3(0, 1, 0);
        ch->tu = v3_norm(v3_cross(a, ch->normal));
        ch->tv = v3_cross(ch->normal, ch->tu);
        rc = refine_chart(m, t, bucket + count[c], count[c + 1] - count[c], edge, q, max_verts, c);
    }
    free(t), free(chart_of), free(count), free(bucket), free(fill);
    if (rc == 0)
        rc = keep_rest_pose(m, s);
    if (rc) {
        int nv = m->n_verts;
        rad_mesh_free(m);
        if (rc == -2)
            return gk_fail(e, GK_EINPUT, "radiosity: %s refined to edge %.3g m has more than %d vertices (%d in the charts before the one that went over); use a longer edge",
                           s->name, (double)edge, max_verts, nv);
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory refining %s", s->name);
    }
    return 0;
}

void rad_mesh_free(rad_mesh *m)
{
    free(m->pos), free(m->area), free(m->centre), free(m->chart), free(m->tris), free(m->charts);
    free(m->rest_pos), free(m->rest_centre), free(m->rest_world_inv);
    memset(m, 0, sizeof *m);
}
