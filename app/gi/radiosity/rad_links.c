/* Link creation, refinement and push-down (rad_links.h). */
#include "rad_links.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int rad_cube_bin(vec3 d, int n)
{
    float ax = fabsf(d.x), ay = fabsf(d.y), az = fabsf(d.z);
    int face;
    float u, v, m;
    if (ax >= ay && ax >= az)
        face = d.x >= 0.0f ? 0 : 1, m = ax, u = d.y, v = d.z;
    else if (ay >= az)
        face = d.y >= 0.0f ? 2 : 3, m = ay, u = d.x, v = d.z;
    else
        face = d.z >= 0.0f ? 4 : 5, m = az, u = d.x, v = d.y;
    if (!(m > 0.0f))
        return 0;
    int iu = (int)((u / m + 1.0f) * 0.5f * (float)n), iv = (int)((v / m + 1.0f) * 0.5f * (float)n);
    iu = iu < 0 ? 0 : iu >= n ? n - 1 : iu;
    iv = iv < 0 ? 0 : iv >= n ? n - 1 : iv;
    return (face * n + iv) * n + iu;
}

vec3 rad_bin_direction(int bin, int n, float s, float t)
{
    int iu = bin % n, iv = (bin / n) % n, face = bin / (n * n);
    float u = 2.0f * ((float)iu + s) / (float)n - 1.0f, v = 2.0f * ((float)iv + t) / (float)n - 1.0f;
    float m = face & 1 ? -1.0f : 1.0f; /* faces +x, -x, +y, -y, +z, -z: the major axis' sign */
    vec3 d;
    switch (face >> 1) {
    case 0: d = v3(m, u, v); break;
    case 1: d = v3(u, m, v); break;
    default: d = v3(u, v, m); break;
    }
    return v3_norm(d);
}

float rad_bin_solid_angle(int bin, int n)
{
    int iu = bin % n, iv = (bin / n) % n;
    float u = 2.0f * ((float)iu + 0.5f) / (float)n - 1.0f, v = 2.0f * ((float)iv + 0.5f) / (float)n - 1.0f;
    float s = 2.0f / (float)n, q = 1.0f + u * u + v * v;
    return s * s / (q * sqrtf(q));
}

typedef struct builder {
    const rad_tree *t;
    int n, bins;
    int32_t *target;  /* n_nodes x bins, -1 empty */
    float *len;
    float *omega;     /* per bin */
    rad_weight weight;
    rad_links *L;
} builder;

static void store(builder *b, int node, int bin, int other, float r)
{
    size_t k = (size_t)node * (size_t)b->bins + (size_t)bin;
    if (b->target[k] >= 0) {
        if (b->len[k] <= r)
            return;
        b->L->displaced++;
    }
    b->target[k] = other;
    b->len[k] = r;
    b->L->created++;
}

/* The area whose solid angle decides subdivision (times 1/r²): the whole area (rad_links.h). */
static float extent(const builder *b, int node, vec3 w)
{
    (void)w;
    return b->t->area[node];
}

static void link_nodes(builder *b, int a, int c)
{
    const rad_tree *t = b->t;
    vec3 d = v3_sub(t->pos[c], t->pos[a]);
    float r2 = v3_dot(d, d);
    if (!(r2 > 1e-20f))
        return; /* coincident (two charts' vertices at one corner): no direction */
    float r = sqrtf(r2);
    vec3 w = v3_scale(d, 1.0f / r);
    int bin_a = rad_cube_bin(w, b->n), bin_c = rad_cube_bin(v3_scale(w, -1.0f), b->n);
    int first, k;
    if (extent(b, c, w) / r2 > b->omega[bin_a] && (k = rad_tree_children(t, c, &first)) > 0) {
        for (int i = first; i < first + k; i++)
            link_nodes(b, a, i);
        return;
    }
    if (extent(b, a, w) / r2 > b->omega[bin_c] && (k = rad_tree_children(t, a, &first)) > 0) {
        for (int i = first; i < first + k; i++)
            link_nodes(b, i, c);
        return;
    }
    if (v3_dot(t->nrm[a], w) > 0.0f)
        store(b, a, bin_a, c, r);
    if (v3_dot(t->nrm[c], w) < 0.0f)
        store(b, c, bin_c, a, r);
}

/* growable leaf lists */
typedef struct lists {
    uint32_t *target;
    float *weight;
    size_t n, cap;
} lists;

static int push(lists *l, uint32_t target, float weight)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 4096;
        uint32_t *t = realloc(l->target, sizeof *t * cap);
        if (!t)
            return -1;
        l->target = t;
        float *w = realloc(l->weight, sizeof *w * cap);
        if (!w)
            return -1;
        l->weight = w;
        l->cap = cap;
    }
    l->target[l->n] = target, l->weight[l->n] = weight, l->n++;
    return 0;
}

/* The refinement + push-down traversal under `node`, whose inherited links are in[]. eff[] has
 * room for the node's resolved bins and, after it, its descendants' levels. */
static int descend(builder *b, int node, const int32_t *in_t, const float *in_l, int32_t *eff_t, float *eff_l,
                   lists *out)
{
    const rad_tree *t = b->t;
    size_t base = (size_t)node * (size_t)b->bins;
    for (int k = 0; k < b->bins; k++) {
        int32_t own = b->target[base + (size_t)k];
        eff_t[k] = in_t ? in_t[k] : -1;
        eff_l[k] = in_t ? in_l[k] : 0.0f;
        if (own < 0)
            continue;
        if (eff_t[k] >= 0) {
            b->L->inconsistent++;
            if (eff_l[k] <= b->len[base + (size_t)k])
                continue; /* the ancestor's is shorter: the node's link goes */
        }
        eff_t[k] = own, eff_l[k] = b->len[base + (size_t)k];
    }
    int first, nc = rad_tree_children(t, node, &first);
    if (nc == 0) {
        vec3 x = t->pos[node], n = t->nrm[node];
        uint64_t *empty = b->L->empty + (size_t)node * (size_t)b->L->empty_words;
        for (int k = 0; k < b->bins; k++) {
            int32_t y = eff_t[k];
            if (y < 0) {
                empty[k >> 6] |= (uint64_t)1 << (k & 63);
                continue;
            }
            vec3 d = v3_sub(t->pos[y], x);
            float r2 = v3_dot(d, d);
            float w = 0.0f;
            if (r2 > 1e-20f) {
                vec3 u = v3_scale(d, 1.0f / sqrtf(r2));
                float cx = v3_dot(n, u), cy = -v3_dot(t->nrm[y], u);
                if (cx > 0.0f && cy > 0.0f) {
                    /* the element's solid angle: a disc of its area, seen at cy (exact on its axis,
                       bounded by 2π cy however near it is) */
                    float disc = 2.0f * (float)M_PI * cy * (1.0f - sqrtf(r2 / (r2 + t->area[y] / (float)M_PI)));
                    switch (b->weight) {
                    case RAD_WEIGHT_BIN: w = cx * b->omega[k]; break;
                    case RAD_WEIGHT_ELEMENT: w = cx * t->area[y] * cy / r2; break;
                    case RAD_WEIGHT_SPILL: w = cx * fmaxf(b->omega[k], disc); break;
                    }
                }
            }
            if (w > 0.0f) {
                if (push(out, (uint32_t)y, w))
                    return -1;
                b->L->leaf_links++;
            } else
                b->L->occluder_links++;
        }
        b->L->offset[node + 1] = (uint32_t)out->n;
        return 0;
    }
    for (int c = first; c < first + nc; c++)
        if (descend(b, c, eff_t, eff_l, eff_t + b->bins, eff_l + b->bins, out))
            return -1;
    return 0;
}

/* Links the pairs of chart roots: all of them (moving NULL), or those with a moving chart
   (want_moving) or those without. */
static void link_roots(builder *b, const bool *moving, bool want_moving, long *pairs)
{
    const rad_tree *t = b->t;
    for (int i = 0; i < t->n_charts; i++)
        for (int j = i + 1; j < t->n_charts; j++) {
            bool m = moving && (moving[i] || moving[j]);
            if (moving && m != want_moving)
                continue;
            link_nodes(b, t->roots[i], t->roots[j]);
            (*pairs)++;
        }
}

/* cache->target/len := the bins of the static pairs (made once; the caller frees with
   rad_link_cache_free). */
static int fill_cache(rad_link_cache *cache, const builder *proto, size_t cells, const bool *moving)
{
    cache->target = malloc(sizeof *cache->target * cells);
    cache->len = malloc(sizeof *cache->len * cells);
    if (!cache->target || !cache->len) {
        rad_link_cache_free(cache);
        return -1;
    }
    memset(cache->target, 0xFF, sizeof *cache->target * cells);
    cache->cells = cells;
    builder b = *proto;
    b.target = cache->target, b.len = cache->len;
    rad_links scratch = {0};
    b.L = &scratch;
    long pairs = 0;
    link_roots(&b, moving, false, &pairs);
    cache->static_pairs = pairs;
    return 0;
}

void rad_link_cache_free(rad_link_cache *c)
{
    free(c->target), free(c->len);
    memset(c, 0, sizeof *c);
}

int rad_links_build(rad_links *L, const rad_tree *t, int n_face, rad_weight weight, gk_err *e)
{
    return rad_links_update(L, t, n_face, weight, NULL, NULL, e);
}

int rad_links_update(rad_links *L, const rad_tree *t, int n_face, rad_weight weight, const bool *moving,
                     rad_link_cache *cache, gk_err *e)
{
    memset(L, 0, sizeof *L);
    L->n_face = n_face;
    L->n_leaves = t->n_leaves;
    builder b = {.t = t, .n = n_face, .bins = 6 * n_face * n_face, .weight = weight, .L = L};
    size_t cells = (size_t)t->n_nodes * (size_t)b.bins;
    b.target = malloc(sizeof *b.target * cells);
    b.len = malloc(sizeof *b.len * cells);
    b.omega = malloc(sizeof *b.omega * (size_t)b.bins);
    int32_t *eff_t = malloc(sizeof *eff_t * (size_t)b.bins * (RAD_MAX_LEVELS + 1));
    float *eff_l = malloc(sizeof *eff_l * (size_t)b.bins * (RAD_MAX_LEVELS + 1));
    L->offset = calloc((size_t)t->n_leaves + 1, sizeof *L->offset);
    L->empty_words = (b.bins + 63) / 64;
    /* +1: a tree without leaves still gets a valid pointer */
    L->empty = calloc((size_t)t->n_leaves * (size_t)L->empty_words + 1, sizeof *L->empty);
    lists out = {0};
    int rc = -1;
    if (!b.target || !b.len || !b.omega || !eff_t || !eff_l || !L->offset || !L->empty)
        goto done;
    L->bin_bytes = (long)(cells * 8);
    memset(b.target, 0xFF, sizeof *b.target * cells);
    for (int k = 0; k < b.bins; k++)
        b.omega[k] = rad_bin_solid_angle(k, n_face);
    if (moving && cache) {
        /* incremental: the static pairs' bins are the same at every pose (link() reads only the
           two subtrees' nodes, and a bin keeps the shortest of what is stored in it whatever the
           order), so they are made once and copied; only pairs with a moving chart are linked */
        if ((!cache->target || cache->cells != cells) && (rad_link_cache_free(cache), fill_cache(cache, &b, cells, moving)))
            goto done;
        memcpy(b.target, cache->target, sizeof *b.target * cells);
        memcpy(b.len, cache->len, sizeof *b.len * cells);
        link_roots(&b, moving, true, &L->pairs_linked);
        L->pairs_cached = cache->static_pairs;
    } else
        link_roots(&b, NULL, false, &L->pairs_linked);
    /* leaves are numbered chart by chart, so walking the charts in order fills the lists in leaf
       order; offset[i + 1] is written at each leaf */
    rc = 0;
    for (int c = 0; c < t->n_charts && rc == 0; c++)
        rc = descend(&b, t->roots[c], NULL, NULL, eff_t, eff_l, &out);
    for (int i = 0; i < t->n_leaves; i++) /* leaves of no chart walk (none) keep their start */
        if (L->offset[i + 1] < L->offset[i])
            L->offset[i + 1] = L->offset[i];
done:
    free(b.target), free(b.len), free(b.omega), free(eff_t), free(eff_l);
    if (rc) {
        free(out.target), free(out.weight);
        rad_links_free(L);
        return gk_fail(e, GK_ERUNTIME, "radiosity: out of memory building links (%d nodes x %d bins)", t->n_nodes,
                       6 * n_face * n_face);
    }
    L->target = out.target ? out.target : calloc(1, sizeof *L->target);
    L->weight = out.weight ? out.weight : calloc(1, sizeof *L->weight);
    return 0;
}

void rad_links_free(rad_links *L)
{
    free(L->offset), free(L->target), free(L->weight), free(L->empty);
    memset(L, 0, sizeof *L);
}
