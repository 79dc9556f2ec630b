/* Numeric validation of a freshly translated scene (after gltf_load.cpp checked the structure):
 * finite values, index ranges, degenerate triangles, normals, node hierarchy, lights, cameras,
 * animations, the methods list. Every message starts with the scene file's path. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gi/gi_catalogue.h"
#include "scene_internal.h"

static bool all_finite(const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

static vec3 vertex(const gk_mesh *m, uint32_t i)
{
    const float *p = m->positions + 3 * (size_t)i;
    return v3(p[0], p[1], p[2]);
}

/* A triangle is degenerate when its area is zero to float precision: twice its area (|cross|) is
 * at most 1e-7 of its longest edge squared, i.e. its height is below float rounding of that edge. */
static bool degenerate(vec3 a, vec3 b, vec3 c)
{
    vec3 e0 = v3_sub(b, a), e1 = v3_sub(c, a), e2 = v3_sub(c, b);
    float longest = fmaxf(v3_dot(e0, e0), fmaxf(v3_dot(e1, e1), v3_dot(e2, e2)));
    return !(v3_len(v3_cross(e0, e1)) > 1e-7f * longest);
}

/* Meshes without normals get flat ones: every triangle gets its own three vertices. */
static int flat_normals(gk_mesh *m)
{
    size_t nv = (size_t)m->n_triangles * 3;
    float *pos = malloc((nv ? nv : 1) * 3 * sizeof(float));
    float *nrm = malloc((nv ? nv : 1) * 3 * sizeof(float));
    float *uv = m->uvs ? malloc((nv ? nv : 1) * 2 * sizeof(float)) : NULL;
    float *uv1 = m->uvs1 ? malloc((nv ? nv : 1) * 2 * sizeof(float)) : NULL;
    float *col = m->colors ? malloc((nv ? nv : 1) * 4 * sizeof(float)) : NULL;
    float *tan = m->tangents ? malloc((nv ? nv : 1) * 4 * sizeof(float)) : NULL;
    if (!pos || !nrm || (m->uvs && !uv) || (m->uvs1 && !uv1) || (m->colors && !col) || (m->tangents && !tan)) {
        free(pos), free(nrm), free(uv), free(uv1), free(col), free(tan);
        return -1;
    }
    for (uint32_t t = 0; t < m->n_triangles; t++) {
        uint32_t *tri = m->indices + 3 * (size_t)t;
        vec3 a = vertex(m, tri[0]), b = vertex(m, tri[1]), c = vertex(m, tri[2]);
        vec3 n = v3_norm(v3_cross(v3_sub(b, a), v3_sub(c, a)));
        for (int k = 0; k < 3; k++) {
            size_t o = 3 * (size_t)t + (size_t)k;
            memcpy(pos + 3 * o, m->positions + 3 * (size_t)tri[k], 3 * sizeof(float));
            nrm[3 * o] = n.x, nrm[3 * o + 1] = n.y, nrm[3 * o + 2] = n.z;
            if (uv)
                memcpy(uv + 2 * o, m->uvs + 2 * (size_t)tri[k], 2 * sizeof(float));
            if (uv1)
                memcpy(uv1 + 2 * o, m->uvs1 + 2 * (size_t)tri[k], 2 * sizeof(float));
            if (col)
                memcpy(col + 4 * o, m->colors + 4 * (size_t)tri[k], 4 * sizeof(float));
            if (tan)
                memcpy(tan + 4 * o, m->tangents + 4 * (size_t)tri[k], 4 * sizeof(float));
            tri[k] = (uint32_t)o;
        }
    }
    free(m->positions), free(m->uvs), free(m->uvs1), free(m->colors), free(m->tangents);
    m->positions = pos, m->normals = nrm, m->uvs = uv, m->uvs1 = uv1, m->colors = col, m->tangents = tan;
    m->n_vertices = (uint32_t)nv;
    return 0;
}

int gk_scene_validate_meshes(gk_scene *s, gk_err *e)
{
    for (int mi = 0; mi < s->n_meshes; mi++) {
        gk_mesh *m = &s->meshes[mi];
        if (!all_finite(m->positions, (size_t)m->n_vertices * 3))
            return gk_fail(e, GK_EINPUT, "%s: mesh %d: POSITION has NaN or infinite values", s->path, mi);
        if (m->normals && !all_finite(m->normals, (size_t)m->n_vertices * 3))
            return gk_fail(e, GK_EINPUT, "%s: mesh %d: NORMAL has NaN or infinite values", s->path, mi);
        if (m->uvs && !all_finite(m->uvs, (size_t)m->n_vertices * 2))
            return gk_fail(e, GK_EINPUT, "%s: mesh %d: TEXCOORD_0 has NaN or infinite values", s->path, mi);
        if (m->uvs1 && !all_finite(m->uvs1, (size_t)m->n_vertices * 2))
            return gk_fail(e, GK_EINPUT, "%s: mesh %d: TEXCOORD_1 has NaN or infinite values", s->path, mi);
        if (m->colors && !all_finite(m->colors, (size_t)m->n_vertices * 4))
            return gk_fail(e, GK_EINPUT, "%s: mesh %d: COLOR_0 has NaN or infinite values", s->path, mi);
        if (m->tangents && !all_finite(m->tangents, (size_t)m->n_vertices * 4))
            return gk_fail(e, GK_EINPUT, "%s: mesh %d: TANGENT has NaN or infinite values", s->path, mi);
        uint32_t kept = 0;
        for (uint32_t t = 0; t < m->n_triangles; t++) {
            uint32_t *tri = m->indices + 3 * (size_t)t;
            for (int k = 0; k < 3; k++)
                if (tri[k] >= m->n_vertices)
                    return gk_fail(e, GK_EINPUT, "%s: mesh %d: index %u of triangle %u is out of range (%u vertices)",
                                   s->path, mi, tri[k], t, m->n_vertices);
            if (degenerate(vertex(m, tri[0]), vertex(m, tri[1]), vertex(m, tri[2]))) {
                s->n_degenerate_dropped++;
                continue;
            }
            memmove(m->indices + 3 * (size_t)kept, tri, 3 * sizeof(uint32_t));
            kept++;
        }
        m->n_triangles = kept;
        if (!m->normals && flat_normals(m) != 0)
            return gk_fail(e, GK_ERUNTIME, "%s: mesh %d: out of memory", s->path, mi);
        for (uint32_t v = 0; v < m->n_vertices; v++) {
            float *n = m->normals + 3 * (size_t)v;
            float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (l > 0.0f)
                n[0] /= l, n[1] /= l, n[2] /= l;
        }
        /* A normal map needs a tangent frame: generated when the file gives none. */
        const gk_material *mat = m->material >= 0 && m->material < s->n_materials ? &s->materials[m->material] : NULL;
        const float *normal_uvs = mat && mat->tex_uv[GK_SLOT_NORMAL].texcoord == 1 && m->uvs1 ? m->uvs1 : m->uvs;
        if (mat && mat->normal_tex >= 0 && !m->tangents && gk_mesh_generate_tangents(m, normal_uvs) != 0)
            return gk_fail(e, GK_ERUNTIME, "%s: mesh %d: out of memory", s->path, mi);
        if (m->tangents) /* unit xyz, w exactly +-1 (glTF); a file's zero tangent stays zero */
            for (uint32_t v = 0; v < m->n_vertices; v++) {
                float *t = m->tangents + 4 * (size_t)v;
                float l = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
                if (l > 0.0f)
                    t[0] /= l, t[1] /= l, t[2] /= l;
                t[3] = t[3] < 0.0f ? -1.0f : 1.0f;
            }
        m->bmin = m->bmax = m->n_vertices ? vertex(m, 0) : v3(0, 0, 0);
        for (uint32_t v = 1; v < m->n_vertices; v++) {
            m->bmin = v3_min(m->bmin, vertex(m, v));
            m->bmax = v3_max(m->bmax, vertex(m, v));
        }
    }
    return 0;
}

/* Checks the TRS values and the hierarchy, then orders the nodes parents first (by depth, stable)
 * and renumbers every reference to a node (parents, animation channels). */
int gk_scene_validate_nodes(gk_scene *s, gk_err *e)
{
    int n = s->n_nodes;
    for (int i = 0; i < n; i++) {
        const gk_node *d = &s->nodes[i];
        float trs[10] = {d->translation.x, d->translation.y, d->translation.z, d->rotation.x, d->rotation.y,
                         d->rotation.z,    d->rotation.w,    d->scale.x,       d->scale.y,    d->scale.z};
        if (!all_finite(trs, 10))
            return gk_fail(e, GK_EINPUT, "%s: node %d ('%s'): translation, rotation or scale is NaN or infinite",
                           s->path, i, d->name);
        if (fabsf(d->rotation.x) + fabsf(d->rotation.y) + fabsf(d->rotation.z) + fabsf(d->rotation.w) == 0.0f)
            return gk_fail(e, GK_EINPUT, "%s: node %d ('%s'): rotation is the zero quaternion", s->path, i, d->name);
        s->nodes[i].rotation = q_normalize(d->rotation);
    }
    int *depth = calloc((size_t)n + 1, sizeof(int)), *order = calloc((size_t)n + 1, sizeof(int));
    int *remap = calloc((size_t)n + 1, sizeof(int));
    gk_node *sorted = calloc((size_t)n + 1, sizeof(gk_node));
    if (!depth || !order || !remap || !sorted) {
        free(depth), free(order), free(remap), free(sorted);
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory", s->path);
    }
    /* depth of every node in O(n): walk up to the first node whose depth is known, then fill the
     * path; a walk longer than n nodes is a cycle. */
    int rc = 0, max_depth = 0;
    for (int i = 0; i < n; i++)
        depth[i] = -1;
    for (int i = 0; i < n && rc == 0; i++) {
        int steps = 0, p = i;
        while (p >= 0 && depth[p] < 0 && rc == 0) {
            p = s->nodes[p].parent;
            if (++steps > n)
                rc = gk_fail(e, GK_EINPUT, "%s: node %d is part of a cycle in the node hierarchy", s->path, i);
        }
        int base = p >= 0 ? depth[p] : -1;
        p = i;
        for (int j = 0; j < steps && rc == 0; j++, p = s->nodes[p].parent) {
            depth[p] = base + steps - j;
            max_depth = depth[p] > max_depth ? depth[p] : max_depth;
        }
    }
    if (rc == 0) {
        /* counting sort by depth (stable): parents before children */
        int *start = calloc((size_t)max_depth + 2, sizeof(int));
        if (!start) {
            free(depth), free(order), free(remap), free(sorted);
            return gk_fail(e, GK_ERUNTIME, "%s: out of memory", s->path);
        }
        for (int i = 0; i < n; i++)
            start[depth[i] + 1]++;
        for (int d = 1; d <= max_depth + 1; d++)
            start[d] += start[d - 1];
        for (int i = 0; i < n; i++) {
            int k = start[depth[i]]++;
            remap[i] = k, order[k] = i;
        }
        free(start);
        for (int k2 = 0; k2 < n; k2++) {
            sorted[k2] = s->nodes[order[k2]];
            if (sorted[k2].parent >= 0)
                sorted[k2].parent = remap[sorted[k2].parent];
        }
        memcpy(s->nodes, sorted, (size_t)n * sizeof(gk_node));
        for (int c = 0; c < s->n_channels; c++)
            s->channels[c].node = remap[s->channels[c].node];
    }
    free(depth), free(order), free(remap), free(sorted);
    return rc;
}

int gk_scene_validate_lights(gk_scene *s, gk_err *e)
{
    for (int i = 0; i < s->n_lights; i++) {
        const gk_light *l = &s->lights[i];
        float v[10] = {l->color[0], l->color[1], l->color[2], l->intensity, l->range,
                       l->inner_cone, l->outer_cone, l->radius, l->size[0], l->size[1]};
        if (!all_finite(v, 10))
            return gk_fail(e, GK_EINPUT, "%s: light %d ('%s'): NaN or infinite values", s->path, i, l->name);
        if (l->color[0] < 0 || l->color[1] < 0 || l->color[2] < 0 || l->intensity < 0 || l->range < 0)
            return gk_fail(e, GK_EINPUT, "%s: light %d ('%s'): colour, intensity and range must not be negative",
                           s->path, i, l->name);
        if (l->type == GK_LIGHT_SPOT &&
            !(l->inner_cone >= 0 && l->inner_cone <= l->outer_cone && l->outer_cone > 0 && l->outer_cone <= M_PI / 2))
            return gk_fail(e, GK_EINPUT, "%s: light %d ('%s'): spot cone angles need 0 <= inner <= outer <= pi/2",
                           s->path, i, l->name);
        if (l->shape == GK_SHAPE_RECT && !(l->size[0] > 0 && l->size[1] > 0))
            return gk_fail(e, GK_EINPUT, "%s: light %d ('%s'): extras size must be positive", s->path, i, l->name);
        if ((l->shape == GK_SHAPE_SPHERE || l->shape == GK_SHAPE_DISC) && !(l->radius > 0))
            return gk_fail(e, GK_EINPUT, "%s: light %d ('%s'): extras radius must be positive", s->path, i, l->name);
        if (l->type == GK_LIGHT_DIRECTIONAL && l->radius > 0.5f)
            return gk_fail(e, GK_EINPUT, "%s: light %d ('%s'): a sun's angular radius is in radians (<= 0.5)",
                           s->path, i, l->name);
    }
    return 0;
}

int gk_scene_validate_cameras(gk_scene *s, gk_err *e)
{
    for (int i = 0; i < s->n_cameras; i++) {
        const gk_camera *c = &s->cameras[i];
        if (c->orthographic) {
            if (!(isfinite(c->xmag) && c->xmag != 0 && isfinite(c->ymag) && c->ymag != 0 && isfinite(c->znear) &&
                  c->znear >= 0 && isfinite(c->zfar) && c->zfar > c->znear))
                return gk_fail(e, GK_EINPUT, "%s: camera %d (orthographic): needs xmag, ymag != 0, 0 <= znear < zfar",
                               s->path, i);
            continue;
        }
        if (!(isfinite(c->yfov) && c->yfov > 0 && c->yfov < (float)M_PI) || !(isfinite(c->znear) && c->znear > 0) ||
            !(isfinite(c->zfar) && (c->zfar == 0 || c->zfar > c->znear)) || !(isfinite(c->aspect) && c->aspect >= 0))
            return gk_fail(e, GK_EINPUT, "%s: camera %d: needs 0 < yfov < pi, znear > 0, zfar 0 or > znear", s->path, i);
    }
    return 0;
}

int gk_scene_validate_animations(gk_scene *s, gk_err *e)
{
    s->anim_duration = 0.0f;
    for (int i = 0; i < s->n_channels; i++) {
        gk_anim_channel *c = &s->channels[i];
        int comps = c->path == GK_ANIM_ROTATION ? 4 : 3;
        if (c->n_keys == 0 || !all_finite(c->times, c->n_keys) || !all_finite(c->values, (size_t)c->n_keys * comps))
            return gk_fail(e, GK_EINPUT, "%s: animation channel %d: no keys, or NaN or infinite values", s->path, i);
        for (uint32_t k = 0; k < c->n_keys; k++) {
            if (c->times[k] < 0 || (k > 0 && !(c->times[k] > c->times[k - 1])))
                return gk_fail(e, GK_EINPUT, "%s: animation channel %d: key times must be >= 0 and increasing",
                               s->path, i);
            if (comps == 4) {
                float *q = c->values + 4 * (size_t)k;
                float l = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
                if (!(l > 0))
                    return gk_fail(e, GK_EINPUT, "%s: animation channel %d: zero rotation quaternion", s->path, i);
                for (int j = 0; j < 4; j++)
                    q[j] /= l;
            }
        }
        s->anim_duration = fmaxf(s->anim_duration, c->times[c->n_keys - 1]);
        s->nodes[c->node].animated = true;
    }
    /* Parents come first, so "it or an ancestor is animated" propagates in one pass. */
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].parent >= 0 && s->nodes[s->nodes[i].parent].animated)
            s->nodes[i].animated = true;
    return 0;
}

int gk_scene_validate_methods(const gk_scene *s, gk_err *e)
{
    char list[sizeof s->methods];
    memcpy(list, s->methods, sizeof list);
    for (char *save = NULL, *tok = strtok_r(list, ", ", &save); tok; tok = strtok_r(NULL, ", ", &save)) {
        if (!gk_gi_is_method(tok)) {
            char known[256];
            gk_gi_method_names(known, sizeof known, ", ");
            return gk_fail(e, GK_EINPUT, "%s: extras gikiosk.methods: unknown method '%s' (known: %s)", s->path, tok,
                           known);
        }
    }
    return 0;
}
