/* Walls split the surfaces they stand on (scene/wall_split.h). */
#include "scene/wall_split.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LM_SPLIT_PERP 0.05f      /* |cos| of a wall against the surface: within ~3 degrees of 90 */
#define LM_SPLIT_MAX_TRIS 4096   /* meshes finer than this are not cut (their charts are small) */
#define LM_SPLIT_MAX_CUTS 30     /* per mesh: the region label is a bit mask */

typedef struct wtri {
    vec3 p[3];
    vec3 lo, hi;
} wtri;

typedef struct plane {
    vec3 n;
    float d;
} plane;

static vec3 mpos(const gk_mesh *m, uint32_t v) { return v3(m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]); }

static bool proxy(const gk_scene *s, const gk_mesh *m)
{
    return s->materials[m->material >= 0 && m->material < s->n_materials ? m->material : 0].light_proxy;
}

/* Appends a vertex between a and b at t (every attribute interpolated); returns its index or -1. */
static int64_t lerp_vertex(gk_mesh *m, uint32_t a, uint32_t b, float t)
{
    uint32_t n = m->n_vertices + 1;
    float *pos = realloc(m->positions, sizeof(float) * 3 * n);
    if (!pos)
        return -1;
    m->positions = pos;
    float *nor = realloc(m->normals, sizeof(float) * 3 * n);
    if (!nor)
        return -1;
    m->normals = nor;
    for (int k = 0; k < 3; k++) {
        pos[3 * (n - 1) + k] = pos[3 * a + k] + t * (pos[3 * b + k] - pos[3 * a + k]);
        nor[3 * (n - 1) + k] = nor[3 * a + k] + t * (nor[3 * b + k] - nor[3 * a + k]);
    }
    vec3 nn = v3_norm(v3(nor[3 * (n - 1)], nor[3 * (n - 1) + 1], nor[3 * (n - 1) + 2]));
    nor[3 * (n - 1)] = nn.x, nor[3 * (n - 1) + 1] = nn.y, nor[3 * (n - 1) + 2] = nn.z;
    if (m->uvs) {
        float *uv = realloc(m->uvs, sizeof(float) * 2 * n);
        if (!uv)
            return -1;
        m->uvs = uv;
        for (int k = 0; k < 2; k++)
            uv[2 * (n - 1) + k] = uv[2 * a + k] + t * (uv[2 * b + k] - uv[2 * a + k]);
    }
    float **four[2] = {&m->colors, &m->tangents};
    for (int q = 0; q < 2; q++) {
        if (!*four[q])
            continue;
        float *c = realloc(*four[q], sizeof(float) * 4 * n);
        if (!c)
            return -1;
        *four[q] = c;
        for (int k = 0; k < 4; k++)
            c[4 * (n - 1) + k] = c[4 * a + k] + t * (c[4 * b + k] - c[4 * a + k]);
        if (q == 1) { /* tangent: unit xyz, the handedness of a */
            vec3 tt = v3_norm(v3(c[4 * (n - 1)], c[4 * (n - 1) + 1], c[4 * (n - 1) + 2]));
            c[4 * (n - 1)] = tt.x, c[4 * (n - 1) + 1] = tt.y, c[4 * (n - 1) + 2] = tt.z, c[4 * (n - 1) + 3] = c[4 * a + 3];
        }
    }
    m->n_vertices = n;
    return (int64_t)(n - 1);
}

static int add_triangle(gk_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t *idx = realloc(m->indices, sizeof *idx * 3 * (m->n_triangles + 1));
    if (!idx)
        return -1;
    m->indices = idx;
    idx[3 * m->n_triangles] = a, idx[3 * m->n_triangles + 1] = b, idx[3 * m->n_triangles + 2] = c;
    m->n_triangles++;
    return 0;
}

/* Cuts triangle t of m by the object-space plane c (points with |distance| < eps are on it): the
   part on each side becomes its own triangles (t keeps the first). Returns the triangles added or -1. */
static int clip_triangle(gk_mesh *m, uint32_t t, plane c, float eps)
{
    uint32_t v[3] = {m->indices[3 * t], m->indices[3 * t + 1], m->indices[3 * t + 2]};
    float sd[3];
    int pos = 0, neg = 0;
    for (int k = 0; k < 3; k++) {
        sd[k] = v3_dot(c.n, mpos(m, v[k])) - c.d;
        sd[k] = fabsf(sd[k]) < eps ? 0.0f : sd[k];
        pos += sd[k] > 0.0f, neg += sd[k] < 0.0f;
    }
    if (pos == 0 || neg == 0)
        return 0;
    /* Sutherland-Hodgman into the two sides' polygons (at most 4 vertices each) */
    uint32_t side[2][4];
    int ns[2] = {0, 0};
    for (int k = 0; k < 3; k++) {
        int j = (k + 1) % 3;
        if (sd[k] >= 0.0f)
            side[0][ns[0]++] = v[k];
        if (sd[k] <= 0.0f)
            side[1][ns[1]++] = v[k];
        if ((sd[k] > 0.0f && sd[j] < 0.0f) || (sd[k] < 0.0f && sd[j] > 0.0f)) {
            int64_t x = lerp_vertex(m, v[k], v[j], sd[k] / (sd[k] - sd[j]));
            if (x < 0)
                return -1;
            side[0][ns[0]++] = (uint32_t)x;
            side[1][ns[1]++] = (uint32_t)x;
        }
    }
    int added = 0;
    bool first = true;
    for (int s = 0; s < 2; s++)
        for (int k = 1; k + 1 < ns[s]; k++) { /* a fan keeps the winding */
            if (first) {
                m->indices[3 * t] = side[s][0], m->indices[3 * t + 1] = side[s][k], m->indices[3 * t + 2] = side[s][k + 1];
                first = false;
            } else if (add_triangle(m, side[s][0], side[s][k], side[s][k + 1])) {
                return -1;
            } else {
                added++;
            }
        }
    return added;
}

/* The world plane of triangle t of m under w (false when degenerate). */
static bool tri_plane(const gk_mesh *m, uint32_t t, mat4 w, plane *out)
{
    vec3 p0 = m4_point(w, mpos(m, m->indices[3 * t])), p1 = m4_point(w, mpos(m, m->indices[3 * t + 1])),
         p2 = m4_point(w, mpos(m, m->indices[3 * t + 2]));
    vec3 c = v3_cross(v3_sub(p1, p0), v3_sub(p2, p0));
    float len = v3_len(c);
    if (!(len > 0.0f))
        return false;
    out->n = v3_scale(c, 1.0f / len);
    out->d = v3_dot(out->n, p0);
    return true;
}

static bool same_plane(plane a, plane b, float eps) { return v3_dot(a.n, b.n) > 0.9999f && fabsf(a.d - b.d) < eps; }

/* Wall triangle T about perpendicular to the plane pg with an edge in it, rising on its front. */
static bool stands_on(const wtri *T, plane pg, float eps)
{
    vec3 tn = v3_cross(v3_sub(T->p[1], T->p[0]), v3_sub(T->p[2], T->p[0]));
    float tl = v3_len(tn);
    if (!(tl > 0.0f) || fabsf(v3_dot(tn, pg.n)) > LM_SPLIT_PERP * tl)
        return false;
    int n_on = 0, off = -1;
    for (int k = 0; k < 3; k++) {
        if (fabsf(v3_dot(pg.n, T->p[k]) - pg.d) <= eps)
            n_on++;
        else
            off = k;
    }
    return n_on == 2 && v3_dot(pg.n, T->p[off]) - pg.d > eps;
}

/* Does wall triangle T stand on the surface g (its world vertices lo..hi, plane pg) and cross it
   from border to border? Then *cut is T's plane. */
static bool crosses(const wtri *T, plane pg, const gk_mesh *m, mat4 w, const uint32_t *tris, int n_tris, float eps,
                    plane *cut)
{
    vec3 e1 = v3_sub(T->p[1], T->p[0]), e2 = v3_sub(T->p[2], T->p[0]);
    vec3 tn = v3_cross(e1, e2);
    float tl = v3_len(tn);
    if (!(tl > 0.0f))
        return false;
    tn = v3_scale(tn, 1.0f / tl);
    if (fabsf(v3_dot(tn, pg.n)) > LM_SPLIT_PERP)
        return false;
    int on[3], n_on = 0, off = -1;
    for (int k = 0; k < 3; k++) {
        if (fabsf(v3_dot(pg.n, T->p[k]) - pg.d) <= eps)
            on[n_on++] = k;
        else
            off = k;
    }
    /* an edge in the surface's plane, the wall rising on the surface's front side */
    if (n_on != 2 || v3_dot(pg.n, T->p[off]) - pg.d <= eps)
        return false;
    vec3 a = T->p[on[0]], b = T->p[on[1]];
    vec3 u = v3_sub(b, a);
    float L = v3_len(u);
    if (!(L > eps))
        return false;
    u = v3_scale(u, 1.0f / L);
    vec3 across = v3_cross(pg.n, u);
    float umin = INFINITY, umax = -INFINITY, amin = INFINITY, amax = -INFINITY;
    for (int i = 0; i < n_tris; i++)
        for (int k = 0; k < 3; k++) {
            vec3 p = v3_sub(m4_point(w, mpos(m, m->indices[3 * tris[i] + (uint32_t)k])), a);
            float pu = v3_dot(p, u), pa = v3_dot(p, across);
            umin = fminf(umin, pu), umax = fmaxf(umax, pu), amin = fminf(amin, pa), amax = fmaxf(amax, pa);
        }
    /* the edge covers the surface's whole extent along it, and surface lies on both sides of it */
    if (umin < -eps || umax > L + eps || !(amin < -eps && amax > eps))
        return false;
    cut->n = tn;
    cut->d = v3_dot(tn, T->p[0]);
    return true;
}

void gk_wall_regions_free(gk_wall_regions *r)
{
    for (int i = 0; r->tri && i < r->n_meshes; i++)
        free(r->tri[i]);
    free(r->tri);
    memset(r, 0, sizeof *r);
}

/* Sets bit `bit` of the labels of m's triangles in plane pg (world, under w) by their side of the
   object-space cut co. */
static int label(gk_wall_regions *r, int mi, const gk_mesh *m, mat4 w, plane pg, plane co, int bit, float eps,
                 uint32_t *labelled)
{
    uint32_t *lab = realloc(r->tri[mi], sizeof *lab * (m->n_triangles ? m->n_triangles : 1));
    if (!lab)
        return -1;
    /* triangles added since the last call start with no bit set */
    memset(lab + *labelled, 0, sizeof *lab * (m->n_triangles - *labelled));
    *labelled = m->n_triangles;
    r->tri[mi] = lab;
    for (uint32_t t = 0; t < m->n_triangles; t++) {
        plane pt;
        if (!tri_plane(m, t, w, &pt) || !same_plane(pt, pg, eps))
            continue;
        vec3 c = v3_scale(v3_add(mpos(m, m->indices[3 * t]), v3_add(mpos(m, m->indices[3 * t + 1]), mpos(m, m->indices[3 * t + 2]))),
                          1.0f / 3.0f);
        if (v3_dot(co.n, c) - co.d > 0.0f)
            lab[t] |= 1u << bit;
        else
            lab[t] &= ~(1u << bit);
    }
    return 0;
}

int gk_split_walls(gk_scene *s, gk_wall_regions *r, gk_err *e)
{
    memset(r, 0, sizeof *r);
    r->tri = calloc((size_t)(s->n_meshes > 0 ? s->n_meshes : 1), sizeof *r->tri);
    r->n_meshes = s->n_meshes;
    if (!r->tri)
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory splitting surfaces along walls");
    float eps = 1e-4f * fmaxf(v3_len(v3_sub(s->bmax, s->bmin)), 1e-6f);
    int *users = calloc((size_t)(s->n_meshes > 0 ? s->n_meshes : 1), sizeof *users);
    size_t total = 0;
    if (!users)
        goto oom;
    /* labels grow with the triangles a cut adds: every mesh's array is made when first cut */
    for (int i = 0; i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++) {
            users[m]++;
            total += s->meshes[m].n_triangles;
        }
    /* every drawn triangle in world space: the walls that may cut */
    wtri *all = malloc(sizeof *all * (total ? total : 1));
    if (!all)
        goto oom;
    size_t n_all = 0;
    for (int i = 0; i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++) {
            const gk_mesh *mesh = &s->meshes[m];
            if (proxy(s, mesh))
                continue;
            for (uint32_t t = 0; t < mesh->n_triangles; t++) {
                wtri *T = &all[n_all++];
                for (int k = 0; k < 3; k++)
                    T->p[k] = m4_point(s->nodes[i].world, mpos(mesh, mesh->indices[3 * t + (uint32_t)k]));
                T->lo = v3_min(T->p[0], v3_min(T->p[1], T->p[2]));
                T->hi = v3_max(T->p[0], v3_max(T->p[1], T->p[2]));
            }
        }
    int cuts = 0;
    uint32_t *tris = NULL;
    for (int i = 0; i < s->n_nodes; i++) {
        mat4 w = s->nodes[i].world;
        mat4 wt = m4_transpose(w);
        for (int mi = s->nodes[i].mesh_first; mi < s->nodes[i].mesh_first + s->nodes[i].mesh_count; mi++) {
            gk_mesh *m = &s->meshes[mi];
            if (users[mi] != 1 || proxy(s, m) || m->n_triangles == 0 || m->n_triangles > LM_SPLIT_MAX_TRIS)
                continue;
            plane applied[LM_SPLIT_MAX_CUTS]; /* the mesh's cut planes (world): bit k of its labels */
            int n_applied = 0;
            uint32_t labelled = 0;
            vec3 tr = m4_point(w, v3(0, 0, 0));
            /* each surface (plane) of the mesh in turn: its triangles, then every wall crossing it */
            for (uint32_t seed = 0; seed < m->n_triangles; seed++) {
                plane pg;
                if (!tri_plane(m, seed, w, &pg))
                    continue;
                bool seen = false; /* the plane of an earlier triangle: done */
                for (uint32_t t = 0; t < seed && !seen; t++) {
                    plane pt;
                    seen = tri_plane(m, t, w, &pt) && same_plane(pt, pg, eps);
                }
                if (seen)
                    continue;
                int mine[LM_SPLIT_MAX_CUTS], n_mine = 0; /* the cuts made on this surface */
                int nt = -1;
                for (size_t q = 0; q < n_all; q++) {
                    const wtri *T = &all[q];
                    /* bounds: the wall must reach the surface's plane */
                    float dl = v3_dot(pg.n, T->lo) - pg.d, dh = v3_dot(pg.n, T->hi) - pg.d;
                    if (fminf(dl, dh) > eps || fmaxf(dl, dh) < -eps || !stands_on(T, pg, eps))
                        continue;
                    if (nt < 0) { /* the surface's triangles, again after each cut */
                        free(tris);
                        tris = malloc(sizeof *tris * m->n_triangles);
                        if (!tris)
                            goto oom_all;
                        nt = 0;
                        for (uint32_t t = 0; t < m->n_triangles; t++) {
                            plane pt;
                            if (tri_plane(m, t, w, &pt) && same_plane(pt, pg, eps))
                                tris[nt++] = t;
                        }
                    }
                    plane cut;
                    if (!crosses(T, pg, m, w, tris, nt, eps, &cut))
                        continue;
                    int bit = -1;
                    bool dup = false;
                    for (int k = 0; k < n_applied && bit < 0; k++)
                        if (same_plane(applied[k], cut, eps) ||
                            (v3_dot(applied[k].n, cut.n) < -0.9999f && fabsf(applied[k].d + cut.d) < eps))
                            bit = k;
                    for (int k = 0; k < n_mine && !dup; k++)
                        dup = mine[k] == bit;
                    if (dup || (bit < 0 && n_applied == LM_SPLIT_MAX_CUTS))
                        continue;
                    if (bit < 0)
                        bit = n_applied, applied[n_applied++] = cut;
                    mine[n_mine++] = bit;
                    /* the cut in object space: n_w . (M p + t) = d_w  <=>  (M^T n_w) . p = d_w - n_w . t */
                    vec3 no = m4_dir(wt, cut.n);
                    float nl = v3_len(no);
                    if (!(nl > 0.0f))
                        continue;
                    plane co = {v3_scale(no, 1.0f / nl), (cut.d - v3_dot(cut.n, tr)) / nl};
                    float eps_o = eps / fmaxf(v3_len(m4_dir(w, co.n)), 1e-12f);
                    for (int k = 0; k < nt; k++) {
                        int added = clip_triangle(m, tris[k], co, eps_o);
                        if (added < 0)
                            goto oom_all;
                        s->n_triangles += (uint32_t)added;
                    }
                    nt = -1;
                    /* the pieces of earlier cuts were cut again: label the surface by all of its cuts */
                    for (int k = 0; k < n_mine; k++) {
                        plane a = applied[mine[k]];
                        vec3 nk = m4_dir(wt, a.n);
                        float lk = v3_len(nk);
                        plane ck = {v3_scale(nk, 1.0f / lk), (a.d - v3_dot(a.n, tr)) / lk};
                        if (lk > 0.0f && label(r, mi, m, w, pg, ck, mine[k], eps, &labelled))
                            goto oom_all;
                    }
                    cuts++;
                }
            }
        }
    }
    free(tris), free(all), free(users);
    return cuts;
oom_all:
    free(tris), free(all);
oom:
    free(users);
    gk_wall_regions_free(r);
    return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory splitting surfaces along walls");
}
