/* What a scene contains (gk_scene_features) and which GI methods it therefore needs
 * (gk_scene_methods): "model no more than a scene needs". The method names and what each needs
 * come from the catalogue (app/gi/gi_catalogue.h, a GL-free leaf the fuzz build links too); this
 * file only says which needs a scene has (gk_scene_gi_needs). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gi/gi_catalogue.h"
#include "scene_internal.h"

static bool material_drawn(const gk_scene *s, int mat)
{
    for (int i = 0; i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++)
            if (s->meshes[m].material == mat && s->meshes[m].n_triangles > 0)
                return true;
    return false;
}

static bool node_has_light(const gk_scene *s, enum gk_light_type type)
{
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].light >= 0 && s->lights[s->nodes[i].light].type == type &&
            s->lights[s->nodes[i].light].intensity > 0)
            return true;
    return false;
}

/* Welded world-space vertex key: positions rounded to 10 µm, so the corners that two separately
 * authored walls share compare equal. */
typedef struct { long long x, y, z; } vkey;
typedef struct { uint32_t a, b; } edge;

static int cmp_vkey_idx(const void *pa, const void *pb, void *ctx)
{
    const vkey *k = ctx, *a = &k[*(const uint32_t *)pa], *b = &k[*(const uint32_t *)pb];
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    if (a->z != b->z) return a->z < b->z ? -1 : 1;
    return 0;
}

static int cmp_edge(const void *pa, const void *pb)
{
    const edge *a = pa, *b = pb;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    if (a->b != b->b) return a->b < b->b ? -1 : 1;
    return 0;
}

/* Closed: every edge of the drawn triangles (after welding positions) is used by exactly two. */
static bool scene_is_closed(const gk_scene *s)
{
    size_t nv = 0, nt = 0;
    for (int i = 0; i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++)
            nt += s->meshes[m].n_triangles;
    if (nt == 0)
        return false;
    nv = nt * 3;
    vkey *keys = malloc(nv * sizeof *keys);
    uint32_t *idx = malloc(nv * sizeof *idx), *weld = malloc(nv * sizeof *weld);
    edge *edges = malloc(nv * sizeof *edges);
    bool closed = keys && idx && weld && edges;
    size_t k = 0;
    for (int i = 0; closed && i < s->n_nodes; i++)
        for (int m = s->nodes[i].mesh_first; m < s->nodes[i].mesh_first + s->nodes[i].mesh_count; m++) {
            const gk_mesh *mesh = &s->meshes[m];
            for (size_t t = 0; t < (size_t)mesh->n_triangles * 3; t++, k++) {
                const float *p = mesh->positions + 3 * (size_t)mesh->indices[t];
                vec3 w = m4_point(s->nodes[i].world, v3(p[0], p[1], p[2]));
                keys[k] = (vkey){llroundf(w.x * 1e5f), llroundf(w.y * 1e5f), llroundf(w.z * 1e5f)};
                idx[k] = (uint32_t)k;
            }
        }
    if (closed) {
        qsort_r(idx, nv, sizeof *idx, cmp_vkey_idx, keys);
        uint32_t id = 0;
        for (size_t i = 0; i < nv; i++) {
            if (i > 0 && cmp_vkey_idx(&idx[i - 1], &idx[i], keys) != 0)
                id++;
            weld[idx[i]] = id;
        }
        for (size_t t = 0; t < nt; t++)
            for (int j = 0; j < 3; j++) {
                uint32_t a = weld[3 * t + (size_t)j], b = weld[3 * t + (size_t)(j + 1) % 3];
                edges[3 * t + (size_t)j] = a < b ? (edge){a, b} : (edge){b, a};
            }
        qsort(edges, nv, sizeof *edges, cmp_edge);
        for (size_t i = 0; i < nv && closed;) {
            size_t j = i;
            while (j < nv && cmp_edge(&edges[i], &edges[j]) == 0)
                j++;
            closed = j - i == 2;
            i = j;
        }
    }
    free(keys), free(idx), free(weld), free(edges);
    return closed;
}

/* Light can bounce between diffuse surfaces: some source (light or emitter) and some drawn,
 * non-black, mostly non-metallic surface that is not a light proxy. */
static bool has_interreflection(const gk_scene *s, bool has_emissive)
{
    bool source = has_emissive;
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].light >= 0 && s->lights[s->nodes[i].light].intensity > 0)
            source = true;
    if (!source)
        return false;
    for (int m = 0; m < s->n_materials; m++) {
        const gk_material *mat = &s->materials[m];
        if (!mat->light_proxy && mat->metallic_mean < 0.5f && mat->transmission < 1.0f &&
            v3_maxc(v3(mat->base_color[0], mat->base_color[1], mat->base_color[2])) > 0 && material_drawn(s, m))
            return true;
    }
    return false;
}

void gk_scene_derive_features(gk_scene *s)
{
    gk_scene_features f = {0};
    bool specular_or_glass = false;
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].light >= 0 && s->lights[s->nodes[i].light].shape != GK_SHAPE_POINT)
            f.has_area_lights = true;
    for (int m = 0; m < s->n_materials; m++) {
        const gk_material *mat = &s->materials[m];
        if (!material_drawn(s, m))
            continue;
        /* A light proxy is the visible face of an area light, not an emitter of its own. */
        if (!mat->light_proxy && v3_maxc(v3(mat->emissive[0], mat->emissive[1], mat->emissive[2])) > 0)
            f.has_emissive = true;
        if (mat->roughness_mean < 0.2f && mat->metallic_mean > 0.5f)
            f.has_specular = true;
        if (mat->transmission > 0)
            f.has_transmission = true;
    }
    specular_or_glass = f.has_specular || f.has_transmission;
    f.has_caustics = specular_or_glass && (node_has_light(s, GK_LIGHT_POINT) || node_has_light(s, GK_LIGHT_SPOT));
    f.has_animation = s->n_channels > 0;
    f.is_closed = scene_is_closed(s);
    f.has_interreflection = has_interreflection(s, f.has_emissive);
    f.has_medium = s->medium.present;
    s->features = f;
}

static int add_method(const char **names, int n, int max, const char *name)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(names[i], name))
            return n;
    if (n < max)
        names[n++] = name;
    return n;
}

unsigned gk_scene_gi_needs(const gk_scene_features *f)
{
    unsigned needs = 0;
    if (f->has_interreflection)
        needs |= GK_GI_NEEDS_INTERREFLECTION;
    if (f->has_caustics)
        needs |= GK_GI_NEEDS_CAUSTICS;
    if (!f->has_animation)
        needs |= GK_GI_NEEDS_STATIC;
    if (f->has_medium)
        needs |= GK_GI_NEEDS_MEDIA;
    return needs;
}

int gk_scene_methods(const gk_scene *s, const char **names, int max)
{
    int count;
    const gk_gi_entry *cat = gk_gi_catalogue(&count);
    int n = add_method(names, 0, max, "none");
    if (s->methods[0]) {
        /* The scene's own list wins (names were checked at load); keep the catalogue's strings, in
           the catalogue's order. */
        for (int k = 0; k < count; k++) {
            char list[sizeof s->methods];
            memcpy(list, s->methods, sizeof list);
            for (char *save = NULL, *tok = strtok_r(list, ", ", &save); tok; tok = strtok_r(NULL, ", ", &save))
                if (!strcmp(tok, cat[k].name))
                    n = add_method(names, n, max, cat[k].name);
        }
        return n;
    }
    unsigned has = gk_scene_gi_needs(&s->features);
    for (int k = 0; k < count; k++)
        if (cat[k].needs && (cat[k].needs & has) == cat[k].needs)
            n = add_method(names, n, max, cat[k].name);
    return n;
}

void gk_scene_features_string(const gk_scene_features *f, char *out, int out_len)
{
    struct { bool on; const char *name; } items[] = {
        {f->has_area_lights, "area"}, {f->has_emissive, "emissive"},   {f->has_specular, "specular"},
        {f->has_transmission, "glass"}, {f->has_caustics, "caustics"}, {f->has_animation, "animated"},
        {f->is_closed, "closed"},
    };
    int len = 0;
    out[0] = '\0';
    for (size_t i = 0; i < sizeof items / sizeof items[0]; i++)
        if (items[i].on && len < out_len)
            len += snprintf(out + len, (size_t)(out_len - len), "%s%s", len ? "," : "", items[i].name);
    if (!out[0])
        snprintf(out, (size_t)out_len, "-");
}
