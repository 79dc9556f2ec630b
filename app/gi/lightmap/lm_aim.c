/* AIMs: per-surface kd-trees and k-nearest-photon irradiance (lm_aim.h). */
#include "lm_aim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static float axis_of(vec3 v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

typedef struct kd_item { vec3 p, pw; } kd_item;
static _Thread_local int tl_axis;

static int cmp_item(const void *pa, const void *pb)
{
    float a = axis_of(((const kd_item *)pa)->p, tl_axis), b = axis_of(((const kd_item *)pb)->p, tl_axis);
    return a < b ? -1 : a > b;
}

/* Balanced tree in array order: node at mid of [lo, hi), children in the two halves. */
static void build(kd_item *it, unsigned char *axis, int lo, int hi)
{
    if (hi - lo <= 1) {
        if (hi - lo == 1)
            axis[lo] = 0;
        return;
    }
    vec3 mn = it[lo].p, mx = it[lo].p;
    for (int i = lo + 1; i < hi; i++)
        mn = v3_min(mn, it[i].p), mx = v3_max(mx, it[i].p);
    vec3 ext = v3_sub(mx, mn);
    int a = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    tl_axis = a;
    qsort(it + lo, (size_t)(hi - lo), sizeof *it, cmp_item);
    int mid = (lo + hi) / 2;
    axis[mid] = (unsigned char)a;
    build(it, axis, lo, mid);
    build(it, axis, mid + 1, hi);
}

void lm_kdtree_build(lm_kdtree *t, const lm_store *const *stores, int n_stores, unsigned kind_mask)
{
    int n = 0;
    for (int q = 0; q < n_stores; q++)
        for (int i = 0; i < stores[q]->n; i++)
            n += (kind_mask >> stores[q]->hits[i].kind) & 1u;
    if (n > t->cap) {
        int nc = n + n / 2 + 16;
        vec3 *p = realloc(t->pts, sizeof *p * (size_t)nc), *w = p ? realloc(t->pow, sizeof *w * (size_t)nc) : NULL;
        if (p)
            t->pts = p;
        if (w)
            t->pow = w;
        unsigned char *ax = w ? realloc(t->axis, (size_t)nc) : NULL;
        if (!ax) {
            t->n = 0;
            return;
        }
        t->axis = ax, t->cap = nc;
    }
    kd_item *it = malloc(sizeof *it * (size_t)(n > 0 ? n : 1));
    if (!it) {
        t->n = 0;
        return;
    }
    int k = 0;
    for (int q = 0; q < n_stores; q++) {
        const lm_store *s = stores[q];
        for (int i = 0; i < s->n; i++)
            if ((kind_mask >> s->hits[i].kind) & 1u)
                it[k++] = (kd_item){s->hits[i].pos, s->hits[i].power};
    }
    build(it, t->axis, 0, n);
    for (int i = 0; i < n; i++)
        t->pts[i] = it[i].p, t->pow[i] = it[i].pw;
    t->n = n;
    free(it);
}

void lm_kdtree_free(lm_kdtree *t)
{
    free(t->pts), free(t->pow), free(t->axis);
    memset(t, 0, sizeof *t);
}

/* A max-heap of the k best squared distances. */
typedef struct knn {
    float *d2;
    int *idx;
    int n, k;
} knn;

static void heap_push(knn *h, float d2, int i)
{
    if (h->n < h->k) {
        int c = h->n++;
        while (c > 0 && h->d2[(c - 1) / 2] < d2) {
            h->d2[c] = h->d2[(c - 1) / 2], h->idx[c] = h->idx[(c - 1) / 2];
            c = (c - 1) / 2;
        }
        h->d2[c] = d2, h->idx[c] = i;
        return;
    }
    if (d2 >= h->d2[0])
        return;
    int c = 0;
    for (;;) {
        int l = 2 * c + 1, r = l + 1, m = c;
        float big = d2;
        if (l < h->n && h->d2[l] > big)
            m = l, big = h->d2[l];
        if (r < h->n && h->d2[r] > big)
            m = r;
        if (m == c)
            break;
        h->d2[c] = h->d2[m], h->idx[c] = h->idx[m];
        c = m;
    }
    h->d2[c] = d2, h->idx[c] = i;
}

static void search(const lm_kdtree *t, vec3 p, int lo, int hi, knn *h)
{
    if (lo >= hi)
        return;
    int mid = (lo + hi) / 2;
    vec3 d = v3_sub(t->pts[mid], p);
    heap_push(h, v3_dot(d, d), mid);
    if (hi - lo == 1)
        return;
    int a = t->axis[mid];
    float diff = axis_of(p, a) - axis_of(t->pts[mid], a);
    int nlo = diff < 0 ? lo : mid + 1, nhi = diff < 0 ? mid : hi;
    int flo = diff < 0 ? mid + 1 : lo, fhi = diff < 0 ? hi : mid;
    search(t, p, nlo, nhi, h);
    if (h->n < h->k || diff * diff < h->d2[0])
        search(t, p, flo, fhi, h);
}

vec3 lm_kdtree_knn(const lm_kdtree *t, vec3 p, int k, float *r_k)
{
    k = k < t->n ? k : t->n;
    *r_k = 0.0f;
    if (k <= 0)
        return v3(0, 0, 0);
    float d2[LM_KNN];
    int idx[LM_KNN];
    knn h = {d2, idx, 0, k < LM_KNN ? k : LM_KNN};
    search(t, p, 0, t->n, &h);
    vec3 sum = v3(0, 0, 0);
    for (int i = 0; i < h.n; i++)
        sum = v3_add(sum, t->pow[h.idx[i]]);
    *r_k = sqrtf(h.d2[0]);
    return sum;
}

void lm_aim_update_chart(const lm_atlas *a, const lm_photons *ph, int ci, mat4 world, lm_kdtree *tree, float *irr,
                         unsigned kind_mask)
{
    const lm_chart *c = &a->charts[ci];
    /* the photon map of the surface and of those that could contribute to it */
    int nc = a->contrib_first[ci + 1] - a->contrib_first[ci];
    const lm_store *local[64];
    const lm_store **stores = nc + 1 <= 64 ? local : malloc(sizeof *stores * (size_t)(nc + 1));
    if (!stores)
        return;
    stores[0] = &ph->stores[ci];
    float area = c->area;
    for (int k = 0; k < nc; k++) {
        int d = a->contrib[a->contrib_first[ci] + k];
        stores[k + 1] = &ph->stores[d];
        area += a->charts[d].area;
    }
    lm_kdtree_build(tree, stores, nc + 1, kind_mask);
    if (stores != local)
        free(stores);
    vec3 all = v3(0, 0, 0);
    for (int i = 0; i < tree->n; i++)
        all = v3_add(all, tree->pow[i]);
    area = area > 0.0f ? area : 1e-12f;
    for (int j = 0; j < c->h; j++)
        for (int i = 0; i < c->w; i++) {
            vec3 E;
            if (tree->n <= LM_KNN) {
                E = v3_scale(all, 1.0f / area);
            } else {
                float r;
                vec3 sum = lm_kdtree_knn(tree, m4_point(world, lm_chart_point(c, i, j)), LM_KNN, &r);
                float span = fminf(3.14159265f * r * r, area);
                E = v3_scale(sum, 1.0f / fmaxf(span, 1e-12f));
            }
            float *o = &irr[4 * ((size_t)(c->y + j) * (size_t)a->width + (size_t)(c->x + i))];
            o[0] = E.x, o[1] = E.y, o[2] = E.z, o[3] = 1.0f;
        }
    /* its gutter: copies of its border texels */
    for (int y = c->y - LM_GUTTER; y < c->y + c->h + LM_GUTTER; y++)
        for (int x = c->x - LM_GUTTER; x < c->x + c->w + LM_GUTTER; x++) {
            if (x >= c->x && x < c->x + c->w && y >= c->y && y < c->y + c->h)
                continue;
            int sx = x < c->x ? c->x : (x >= c->x + c->w ? c->x + c->w - 1 : x);
            int sy = y < c->y ? c->y : (y >= c->y + c->h ? c->y + c->h - 1 : y);
            memcpy(&irr[4 * ((size_t)y * (size_t)a->width + (size_t)x)],
                   &irr[4 * ((size_t)sy * (size_t)a->width + (size_t)sx)], sizeof(float) * 4);
        }
}

typedef struct prio { double key; int chart; } prio;

static int cmp_prio(const void *pa, const void *pb)
{
    const prio *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key > b->key ? -1 : 1;
    return a->chart - b->chart;
}

int lm_aim_select(const lm_atlas *a, const lm_photons *ph, int texel_budget, int *out)
{
    prio *p = malloc(sizeof *p * (size_t)(a->n_charts > 0 ? a->n_charts : 1));
    if (!p)
        return 0;
    int n = 0;
    for (int i = 0; i < a->n_charts; i++) {
        const lm_store *s = &ph->stores[i];
        if (s->delta_f <= 0.0 || s->delta_f <= LM_DELTA_REL * s->energy)
            continue;
        p[n++] = (prio){s->delta_f / (a->charts[i].area > 0 ? a->charts[i].area : 1e-12), i};
    }
    qsort(p, (size_t)n, sizeof *p, cmp_prio);
    int m = 0, used = 0;
    for (int k = 0; k < n; k++) {
        int texels = a->charts[p[k].chart].w * a->charts[p[k].chart].h;
        if (m > 0 && used + texels > texel_budget)
            continue; /* a smaller surface further down may still fit */
        out[m++] = p[k].chart;
        used += texels;
    }
    free(p);
    return m;
}
