/* Binned SAH BVH build and traversal (see bvh.h). */
#include "bvh.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#define BINS 12
#define LEAF_MAX 4
#define STACK_MAX 64

typedef struct box { vec3 lo, hi; } box;

static box box_empty(void) { return (box){v3(FLT_MAX, FLT_MAX, FLT_MAX), v3(-FLT_MAX, -FLT_MAX, -FLT_MAX)}; }
static box box_grow(box b, vec3 p) { return (box){v3_min(b.lo, p), v3_max(b.hi, p)}; }
static box box_union(box a, box b) { return (box){v3_min(a.lo, b.lo), v3_max(a.hi, b.hi)}; }
static float box_area(box b)
{
    if (b.lo.x > b.hi.x)
        return 0.0f;
    vec3 d = v3_sub(b.hi, b.lo);
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}
static float comp(vec3 v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

typedef struct build_ctx {
    box *tri_box;
    vec3 *centroid;
    uint32_t *idx;
    gk_bvh_node *nodes;
    uint32_t n_nodes;
} build_ctx;

/* Builds the subtree over idx[first, first+count) into node ni; recursion depth is bounded by the
 * tree depth, which binned SAH keeps logarithmic for any sane scene (and count shrinks each level). */
static void build_node(build_ctx *c, uint32_t ni, uint32_t first, uint32_t count, int depth)
{
    box bounds = box_empty(), cb = box_empty();
    for (uint32_t i = first; i < first + count; i++) {
        bounds = box_union(bounds, c->tri_box[c->idx[i]]);
        cb = box_grow(cb, c->centroid[c->idx[i]]);
    }
    gk_bvh_node *n = &c->nodes[ni];
    n->bmin[0] = bounds.lo.x; n->bmin[1] = bounds.lo.y; n->bmin[2] = bounds.lo.z;
    n->bmax[0] = bounds.hi.x; n->bmax[1] = bounds.hi.y; n->bmax[2] = bounds.hi.z;
    n->offset = first;
    n->count = (uint16_t)count;
    n->axis = 0;
    if (count <= 1 || depth >= STACK_MAX - 2)
        return;

    float best_cost = FLT_MAX;
    int best_axis = -1, best_split = 0;
    for (int a = 0; a < 3; a++) {
        float lo = comp(cb.lo, a), hi = comp(cb.hi, a);
        if (hi - lo < 1e-12f)
            continue;
        box bin_box[BINS];
        uint32_t bin_n[BINS] = {0};
        for (int k = 0; k < BINS; k++)
            bin_box[k] = box_empty();
        float scale = BINS / (hi - lo);
        for (uint32_t i = first; i < first + count; i++) {
            int k = (int)((comp(c->centroid[c->idx[i]], a) - lo) * scale);
            k = k < 0 ? 0 : (k >= BINS ? BINS - 1 : k);
            bin_n[k]++;
            bin_box[k] = box_union(bin_box[k], c->tri_box[c->idx[i]]);
        }
        float right_area[BINS];
        uint32_t right_n[BINS];
        box acc = box_empty();
        uint32_t an = 0;
        for (int k = BINS - 1; k > 0; k--) {
            acc = box_union(acc, bin_box[k]);
            an += bin_n[k];
            right_area[k] = box_area(acc);
            right_n[k] = an;
        }
        acc = box_empty();
        an = 0;
        for (int k = 0; k < BINS - 1; k++) {
            acc = box_union(acc, bin_box[k]);
            an += bin_n[k];
            if (an == 0 || right_n[k + 1] == 0)
                continue;
            float cost = box_area(acc) * an + right_area[k + 1] * right_n[k + 1];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = a;
                best_split = k;
            }
        }
    }
    /* SAH with traversal cost 1 and intersection cost 1 per triangle, relative to the parent area. */
    float leaf_cost = (float)count;
    float split_cost = best_axis >= 0 ? 1.0f + best_cost / fmaxf(box_area(bounds), 1e-30f) : FLT_MAX;
    if (best_axis < 0 && count <= LEAF_MAX * 4)
        return;   /* coincident centroids: a small leaf is cheaper than splitting by count */
    if (best_axis >= 0 && split_cost >= leaf_cost && count <= LEAF_MAX)
        return;
    uint32_t mid;
    if (best_axis >= 0) {
        float lo = comp(cb.lo, best_axis), scale = BINS / (comp(cb.hi, best_axis) - lo);
        uint32_t i = first, j = first + count;
        while (i < j) {
            int k = (int)((comp(c->centroid[c->idx[i]], best_axis) - lo) * scale);
            k = k < 0 ? 0 : (k >= BINS ? BINS - 1 : k);
            if (k <= best_split)
                i++;
            else {
                uint32_t t = c->idx[i];
                c->idx[i] = c->idx[--j];
                c->idx[j] = t;
            }
        }
        mid = i;
    } else {
        mid = first + count / 2;   /* all centroids coincide: split by count */
    }
    if (mid == first || mid == first + count)
        mid = first + count / 2;
    uint32_t left = c->n_nodes++, right = c->n_nodes++;
    n = &c->nodes[ni];
    n->count = 0;
    n->axis = (uint16_t)(best_axis < 0 ? 0 : best_axis);
    n->offset = left; /* children are allocated as a pair: left = offset, right = offset + 1 */
    build_node(c, left, first, mid - first, depth + 1);
    build_node(c, right, mid, first + count - mid, depth + 1);
}

int gk_bvh_build(gk_bvh *b, const vec3 *verts, uint32_t n_tris, gk_err *e)
{
    memset(b, 0, sizeof *b);
    b->n_tris = n_tris;
    if (n_tris == 0)
        return 0;
    build_ctx c = {0};
    c.tri_box = malloc(sizeof(box) * n_tris);
    c.centroid = malloc(sizeof(vec3) * n_tris);
    c.idx = malloc(sizeof(uint32_t) * n_tris);
    c.nodes = malloc(sizeof(gk_bvh_node) * 2 * (size_t)n_tris);
    b->v0 = malloc(sizeof(vec3) * n_tris);
    b->e1 = malloc(sizeof(vec3) * n_tris);
    b->e2 = malloc(sizeof(vec3) * n_tris);
    if (!c.tri_box || !c.centroid || !c.idx || !c.nodes || !b->v0 || !b->e1 || !b->e2) {
        free(c.tri_box); free(c.centroid); free(c.idx); free(c.nodes);
        gk_bvh_free(b);
        return gk_fail(e, GK_ERUNTIME, "reference: out of memory building the BVH (%u triangles)", n_tris);
    }
    for (uint32_t i = 0; i < n_tris; i++) {
        box bx = box_empty();
        for (int k = 0; k < 3; k++)
            bx = box_grow(bx, verts[3 * i + k]);
        c.tri_box[i] = bx;
        c.centroid[i] = v3_scale(v3_add(bx.lo, bx.hi), 0.5f);
        c.idx[i] = i;
    }
    c.n_nodes = 1;
    build_node(&c, 0, 0, n_tris, 0);
    b->nodes = c.nodes;
    b->n_nodes = c.n_nodes;
    b->prim = c.idx;
    for (uint32_t i = 0; i < n_tris; i++) {
        const vec3 *v = &verts[3 * (size_t)b->prim[i]];
        b->v0[i] = v[0];
        b->e1[i] = v3_sub(v[1], v[0]);
        b->e2[i] = v3_sub(v[2], v[0]);
    }
    free(c.tri_box);
    free(c.centroid);
    return 0;
}

void gk_bvh_free(gk_bvh *b)
{
    free(b->nodes);
    free(b->prim);
    free(b->v0);
    free(b->e1);
    free(b->e2);
    memset(b, 0, sizeof *b);
}

/* Slab test; returns the entry distance or FLT_MAX when the box is missed within [tmin, tmax]. */
static inline float hit_box(const gk_bvh_node *n, vec3 o, vec3 inv, float tmin, float tmax)
{
    float tx1 = (n->bmin[0] - o.x) * inv.x, tx2 = (n->bmax[0] - o.x) * inv.x;
    float t0 = fminf(tx1, tx2), t1 = fmaxf(tx1, tx2);
    float ty1 = (n->bmin[1] - o.y) * inv.y, ty2 = (n->bmax[1] - o.y) * inv.y;
    t0 = fmaxf(t0, fminf(ty1, ty2));
    t1 = fminf(t1, fmaxf(ty1, ty2));
    float tz1 = (n->bmin[2] - o.z) * inv.z, tz2 = (n->bmax[2] - o.z) * inv.z;
    t0 = fmaxf(t0, fminf(tz1, tz2));
    t1 = fminf(t1, fmaxf(tz1, tz2));
    t0 = fmaxf(t0, tmin);
    t1 = fminf(t1, tmax);
    return t0 <= t1 ? t0 : FLT_MAX;
}

/* Moller-Trumbore, two-sided. */
static inline bool hit_tri(const gk_bvh *b, uint32_t i, vec3 o, vec3 d, float tmin, float tmax, float *t, float *u, float *v)
{
    vec3 p = v3_cross(d, b->e2[i]);
    float det = v3_dot(b->e1[i], p);
    if (fabsf(det) < 1e-20f)
        return false;
    float inv = 1.0f / det;
    vec3 s = v3_sub(o, b->v0[i]);
    float uu = v3_dot(s, p) * inv;
    if (uu < 0.0f || uu > 1.0f)
        return false;
    vec3 q = v3_cross(s, b->e1[i]);
    float vv = v3_dot(d, q) * inv;
    if (vv < 0.0f || uu + vv > 1.0f)
        return false;
    float tt = v3_dot(b->e2[i], q) * inv;
    if (tt <= tmin || tt >= tmax)
        return false;
    *t = tt;
    *u = uu;
    *v = vv;
    return true;
}

static inline vec3 safe_inv(vec3 d)
{
    return v3(1.0f / (fabsf(d.x) > 1e-30f ? d.x : copysignf(1e-30f, d.x)),
              1.0f / (fabsf(d.y) > 1e-30f ? d.y : copysignf(1e-30f, d.y)),
              1.0f / (fabsf(d.z) > 1e-30f ? d.z : copysignf(1e-30f, d.z)));
}

static bool traverse(const gk_bvh *b, vec3 o, vec3 d, float tmin, float tmax, bool any, gk_bvh_hit *hit)
{
    if (b->n_tris == 0)
        return false;
    vec3 inv = safe_inv(d);
    int neg[3] = {d.x < 0, d.y < 0, d.z < 0};
    uint32_t stack[STACK_MAX];
    int sp = 0;
    bool found = false;
    float best = tmax;
    if (hit_box(&b->nodes[0], o, inv, tmin, best) == FLT_MAX)
        return false;
    stack[sp++] = 0;
    while (sp > 0) {
        const gk_bvh_node *n = &b->nodes[stack[--sp]];
        if (n->count > 0) {
            for (uint32_t i = n->offset; i < n->offset + n->count; i++) {
                float t, u, v;
                if (hit_tri(b, i, o, d, tmin, best, &t, &u, &v)) {
                    if (b->tested && b->tested[b->prim[i]] && !b->accept(b->accept_ctx, b->prim[i], u, v))
                        continue;
                    found = true;
                    if (any)
                        return true;
                    best = t;
                    hit->t = t;
                    hit->u = u;
                    hit->v = v;
                    hit->tri = b->prim[i];
                }
            }
            continue;
        }
        uint32_t near = n->offset, far = n->offset + 1;
        if (neg[n->axis]) {
            uint32_t t = near;
            near = far;
            far = t;
        }
        float tn = hit_box(&b->nodes[near], o, inv, tmin, best);
        float tf = hit_box(&b->nodes[far], o, inv, tmin, best);
        /* Push the far child first so the near one is popped first. */
        if (tf != FLT_MAX)
            stack[sp++] = far;
        if (tn != FLT_MAX)
            stack[sp++] = near;
    }
    return found;
}

bool gk_bvh_intersect(const gk_bvh *b, vec3 o, vec3 d, float tmin, float tmax, gk_bvh_hit *hit)
{
    return traverse(b, o, d, tmin, tmax, false, hit);
}

bool gk_bvh_occluded(const gk_bvh *b, vec3 o, vec3 d, float tmin, float tmax)
{
    gk_bvh_hit h;
    return traverse(b, o, d, tmin, tmax, true, &h);
}
