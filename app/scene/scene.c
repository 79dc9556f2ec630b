/* The scene model's life cycle: finishing a load (gk_scene_finish), freeing, evaluating animations
 * into world matrices, light frames, params and file lookup. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/log.h"
#include "env_split.h"
#include "environment.h"
#include "scene_internal.h"

#define GK_SCENE_MAX_DRAWN 4000000ull

void gk_scene_free(gk_scene *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->n_meshes; i++) {
        free(s->meshes[i].positions);
        free(s->meshes[i].normals);
        free(s->meshes[i].uvs), free(s->meshes[i].uvs1), free(s->meshes[i].colors), free(s->meshes[i].tangents);
        free(s->meshes[i].indices);
    }
    for (int i = 0; i < s->n_textures; i++) {
        free(s->textures[i].rgba);
        free(s->textures[i].embedded);
    }
    for (int i = 0; i < s->n_channels; i++) {
        free(s->channels[i].times);
        free(s->channels[i].values);
    }
    free(s->meshes);
    free(s->materials);
    free(s->textures);
    free(s->lights);
    free(s->cameras);
    free(s->nodes);
    free(s->channels);
    gk_env_free(&s->environment);
    free(s);
}

/* Index of the last key at or before t (keys are strictly increasing; t within [first, last]). */
static uint32_t key_before(const float *times, uint32_t n, float t)
{
    uint32_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (times[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static void apply_channel(gk_scene *s, const gk_anim_channel *c, float t)
{
    gk_node *n = &s->nodes[c->node];
    int comps = c->path == GK_ANIM_ROTATION ? 4 : 3;
    const float *a, *b;
    float f = 0.0f;
    if (t <= c->times[0] || c->n_keys == 1) {
        a = b = c->values;
    } else if (t >= c->times[c->n_keys - 1]) {
        a = b = c->values + (size_t)(c->n_keys - 1) * comps;
    } else {
        uint32_t k = key_before(c->times, c->n_keys, t);
        a = c->values + (size_t)k * comps;
        b = a + comps;
        f = c->interp == GK_INTERP_STEP ? 0.0f : (t - c->times[k]) / (c->times[k + 1] - c->times[k]);
    }
    if (c->path == GK_ANIM_ROTATION) {
        quat qa = {a[0], a[1], a[2], a[3]}, qb = {b[0], b[1], b[2], b[3]};
        n->rotation = q_normalize(q_slerp(qa, qb, f));
        return;
    }
    vec3 v = v3_lerp(v3(a[0], a[1], a[2]), v3(b[0], b[1], b[2]), f);
    if (c->path == GK_ANIM_TRANSLATION)
        n->translation = v;
    else
        n->scale = v;
}

bool gk_node_mirrored(const gk_node *n)
{
    const float *m = n->world.m; /* the determinant of the 3x3 part (the same for its transpose) */
    float det = m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
                m[8] * (m[1] * m[6] - m[5] * m[2]);
    return det < 0.0f;
}

void gk_scene_evaluate(gk_scene *s, float t)
{
    if (s->anim_duration > 0.0f) {
        t = fmodf(t, s->anim_duration);
        if (t < 0.0f)
            t += s->anim_duration;
        for (int i = 0; i < s->n_channels; i++)
            apply_channel(s, &s->channels[i], t);
    }
    /* Nodes are ordered parents first (validate.c), so one pass suffices. */
    for (int i = 0; i < s->n_nodes; i++) {
        gk_node *n = &s->nodes[i];
        mat4 local = m4_trs(n->translation, n->rotation, n->scale);
        n->world = n->parent >= 0 ? m4_mul(s->nodes[n->parent].world, local) : local;
    }
}

void gk_scene_light_frame(const gk_scene *s, int light_node, vec3 *pos, vec3 *dir, vec3 *axis_u, vec3 *axis_v)
{
    mat4 w = s->nodes[light_node].world;
    if (pos)
        *pos = m4_point(w, v3(0, 0, 0));
    if (dir)
        *dir = v3_norm(m4_dir(w, v3(0, 0, -1)));
    if (axis_u)
        *axis_u = v3_norm(m4_dir(w, v3(1, 0, 0)));
    if (axis_v)
        *axis_v = v3_norm(m4_dir(w, v3(0, 1, 0)));
}

int gk_scene_param(const gk_scene *s, const char *key, float *out, int max)
{
    for (int i = 0; i < s->n_params; i++) {
        if (strcmp(s->params[i].key, key) != 0)
            continue;
        int n = s->params[i].n < max ? s->params[i].n : max;
        for (int k = 0; k < n; k++)
            out[k] = s->params[i].v[k];
        return n;
    }
    return -1;
}

int gk_scene_find(const char *dir, const char *name, char *path_out, int path_len)
{
    static const char *const exts[] = {".gltf", ".glb"};
    if (!name[0] || strchr(name, '/'))
        return -1;
    for (int i = 0; i < 2; i++) {
        struct stat st;
        int n = snprintf(path_out, (size_t)path_len, "%s/%s%s", dir, name, exts[i]);
        if (n > 0 && n < path_len && stat(path_out, &st) == 0 && S_ISREG(st.st_mode))
            return 0;
    }
    return -1;
}

/* World bounds at t = 0 over every vertex that a node draws, and the drawn triangle count. */
static void scene_bounds(gk_scene *s)
{
    bool any = false;
    s->n_triangles = 0;
    s->bmin = s->bmax = v3(0, 0, 0);
    for (int i = 0; i < s->n_nodes; i++) {
        const gk_node *n = &s->nodes[i];
        for (int m = n->mesh_first; m < n->mesh_first + n->mesh_count; m++) {
            const gk_mesh *mesh = &s->meshes[m];
            s->n_triangles += mesh->n_triangles;
            for (uint32_t v = 0; v < mesh->n_vertices; v++) {
                const float *p = mesh->positions + 3 * (size_t)v;
                vec3 w = m4_point(n->world, v3(p[0], p[1], p[2]));
                s->bmin = any ? v3_min(s->bmin, w) : w;
                s->bmax = any ? v3_max(s->bmax, w) : w;
                any = true;
            }
        }
    }
}

int gk_scene_finish(gk_scene *s, const char *base_dir, const int *tex_usage, gk_err *e)
{
    if (gk_scene_validate_meshes(s, e) || gk_scene_validate_nodes(s, e) || gk_scene_validate_lights(s, e) ||
        gk_scene_validate_cameras(s, e) || gk_scene_validate_animations(s, e) || gk_scene_validate_methods(s, e) ||
        gk_scene_load_textures(s, base_dir, tex_usage, e))
        return -1;
    if (s->environment.present && gk_env_load(&s->environment, s->path, base_dir, e) != 0)
        return -1;
    /* Instancing multiplies geometry: a small file can ask for billions of drawn triangles. Beyond
     * this limit (about 25x the atrium, our largest scene) a scene is refused rather than loaded. */
    uint64_t drawn = 0;
    for (int i = 0; i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++)
            drawn += s->meshes[m].n_triangles + (uint64_t)s->meshes[m].n_vertices;
    if (drawn > GK_SCENE_MAX_DRAWN)
        return gk_fail(e, GK_EINPUT, "%s: the nodes draw %llu triangles and vertices (instances included); the "
                       "limit is %llu", s->path, (unsigned long long)drawn, (unsigned long long)GK_SCENE_MAX_DRAWN);
    s->camera_node = -1;
    for (int i = 0; i < s->n_nodes && s->camera_node < 0; i++) {
        if (s->nodes[i].camera < 0)
            continue;
        if (s->cameras[s->nodes[i].camera].orthographic)
            gk_log("%s: camera node %d ('%s') is orthographic; gikiosk draws perspective only and passes it over",
                   s->path, i, s->nodes[i].name);
        else
            s->camera_node = i;
    }
    gk_scene_evaluate(s, 0.0f);
    scene_bounds(s);
    gk_scene_derive_features(s);
    /* A file without lights or emitters (most glTF assets) is lit by the default studio, placed
     * around the view camera chosen above; its lights change what light reaches, so re-derive. */
    if (gk_scene_add_default_studio(s, e) != 0)
        return -1;
    /* The environment's area lights for the rasterizer (the tracer samples the map itself). */
    if (gk_env_split(s, GK_ENV_MAX_LIGHTS, e) != 0)
        return -1;
    if (s->default_lighting || s->environment.n_env_lights > 0) {
        gk_scene_evaluate(s, 0.0f);
        gk_scene_derive_features(s);
    }
    return 0;
}
