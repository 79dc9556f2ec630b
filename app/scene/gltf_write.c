/* glTF 2.0 writer for the procedural scenes (see gltf_write.h). Numbers are printed with %.9g
 * (round-trips a float), buffers are appended 4-byte aligned: identical input, identical bytes. */
#include "scene/gltf_write.h"

#include "base/outfile.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct { char *s; size_t len, cap; } sbuf;

static void sb_printf(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_printf(sbuf *b, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        int n = vsnprintf(b->s ? b->s + b->len : NULL, b->s ? b->cap - b->len : 0, fmt, ap);
        va_end(ap);
        if (n < 0)
            return;
        if (b->s && b->len + (size_t)n < b->cap) {
            b->len += (size_t)n;
            return;
        }
        size_t cap = b->cap ? b->cap * 2 : 4096;
        while (cap < b->len + (size_t)n + 1)
            cap *= 2;
        char *p = realloc(b->s, cap);
        if (!p)
            return;
        b->s = p, b->cap = cap;
    }
}

/* A JSON number: %.9g, never nan/inf (the builders produce none; this keeps the file valid). */
static void sb_num(sbuf *b, double v) { sb_printf(b, "%.9g", isfinite(v) ? v : 0.0); }

static void sb_str(sbuf *b, const char *s)
{
    sb_printf(b, "\"");
    for (; s && *s; s++) {
        if (*s == '"' || *s == '\\')
            sb_printf(b, "\\%c", *s);
        else if ((unsigned char)*s < 0x20)
            sb_printf(b, "\\u%04x", (unsigned char)*s);
        else
            sb_printf(b, "%c", *s);
    }
    sb_printf(b, "\"");
}

static void sb_nums(sbuf *b, const double *v, int n)
{
    sb_printf(b, "[");
    for (int i = 0; i < n; i++) {
        if (i)
            sb_printf(b, ",");
        sb_num(b, v[i]);
    }
    sb_printf(b, "]");
}

typedef struct { int view, ctype, count, comps; bool minmax; double min[4], max[4]; } accessor;
typedef struct { size_t offset, length; int target; } bview;
typedef struct { char name[64]; int pos, nrm, uv, idx, material; } mesh;
typedef struct { gkw_material m; char name[64], uri[128]; } material;
typedef struct { gkw_light l; char name[64]; } light;
typedef struct { int node, input, output; char path[16], interp[8]; } channel;
typedef struct { char key[32]; int n; double v[4]; } param;

#define ARRAY(T, name) T *name; int n_##name, cap_##name
struct gkw_doc {
    char name[64];
    unsigned char *bin; size_t bin_len, bin_cap;
    ARRAY(accessor, accessors);
    ARRAY(bview, views);
    ARRAY(mesh, meshes);
    ARRAY(material, materials);
    ARRAY(light, lights);
    ARRAY(gkw_node, nodes);
    ARRAY(channel, channels);
    ARRAY(double, cameras); /* yfov, znear, zfar triples */
    char node_names[256][64];
    char description[512], methods[128];
    bool has_exposure; double exposure;
    param params[16]; int n_params;
    bool has_medium; double sigma_s[3], sigma_a[3], g;
    bool medium_bounded; double medium_lo[3], medium_hi[3];
    char environment_uri[256]; double environment_intensity; /* "" = none */
    bool oom;
};

static void *grow(gkw_doc *d, void **arr, int *n, int *cap, size_t elem)
{
    if (*n == *cap) {
        int nc = *cap ? *cap * 2 : 16;
        void *p = realloc(*arr, (size_t)nc * elem);
        if (!p) {
            d->oom = true;
            return NULL;
        }
        *arr = p, *cap = nc;
    }
    char *slot = (char *)*arr + (size_t)(*n)++ * elem;
    memset(slot, 0, elem);
    return slot;
}
#define PUSH(d, name) ((__typeof__((d)->name))grow(d, (void **)&(d)->name, &(d)->n_##name, &(d)->cap_##name, sizeof *(d)->name))

gkw_doc *gkw_new(const char *name)
{
    gkw_doc *d = calloc(1, sizeof *d);
    if (d)
        snprintf(d->name, sizeof d->name, "%s", name);
    return d;
}

void gkw_free(gkw_doc *d)
{
    if (!d)
        return;
    free(d->bin), free(d->accessors), free(d->views), free(d->meshes), free(d->materials);
    free(d->lights), free(d->nodes), free(d->channels), free(d->cameras);
    free(d);
}

/* Appends bytes (4-aligned) as a new bufferView; returns its index. */
static int add_view(gkw_doc *d, const void *data, size_t len, int target)
{
    size_t off = (d->bin_len + 3) & ~(size_t)3;
    if (off + len > d->bin_cap) {
        size_t cap = d->bin_cap ? d->bin_cap : 65536;
        while (cap < off + len)
            cap *= 2;
        unsigned char *p = realloc(d->bin, cap);
        if (!p) {
            d->oom = true;
            return 0;
        }
        d->bin = p, d->bin_cap = cap;
    }
    memset(d->bin + d->bin_len, 0, off - d->bin_len);
    memcpy(d->bin + off, data, len);
    d->bin_len = off + len;
    bview *v = PUSH(d, views);
    if (!v)
        return 0;
    *v = (bview){off, len, target};
    return d->n_views - 1;
}

static int add_float_accessor(gkw_doc *d, const float *data, int count, int comps, int target, bool minmax)
{
    int view = add_view(d, data, (size_t)count * (size_t)comps * sizeof(float), target);
    accessor *a = PUSH(d, accessors);
    if (!a)
        return 0;
    *a = (accessor){view, 5126, count, comps, minmax, {0}, {0}};
    for (int c = 0; minmax && c < comps; c++) {
        a->min[c] = a->max[c] = count ? data[c] : 0;
        for (int i = 1; i < count; i++) {
            a->min[c] = fmin(a->min[c], data[(size_t)i * comps + c]);
            a->max[c] = fmax(a->max[c], data[(size_t)i * comps + c]);
        }
    }
    return d->n_accessors - 1;
}

int gkw_add_material(gkw_doc *d, const gkw_material *m)
{
    material *dst = PUSH(d, materials);
    if (!dst)
        return 0;
    dst->m = *m;
    snprintf(dst->name, sizeof dst->name, "%s", m->name ? m->name : "");
    snprintf(dst->uri, sizeof dst->uri, "%s", m->base_color_uri ? m->base_color_uri : "");
    return d->n_materials - 1;
}

int gkw_add_mesh(gkw_doc *d, const char *name, const gkw_geom *g, int material_index)
{
    mesh m = {{0}, 0, 0, -1, 0, material_index};
    snprintf(m.name, sizeof m.name, "%s", name);
    m.pos = add_float_accessor(d, g->pos, (int)g->nv, 3, 34962, true);
    m.nrm = add_float_accessor(d, g->nrm, (int)g->nv, 3, 34962, false);
    if (g->with_uv)
        m.uv = add_float_accessor(d, g->uv, (int)g->nv, 2, 34962, false);
    size_t ni = (size_t)g->nt * 3;
    int view;
    int ctype;
    if (g->nv <= 65535) { /* u16 indices halve the index data of most meshes */
        uint16_t *s = malloc((ni ? ni : 1) * sizeof *s);
        if (!s) {
            d->oom = true;
            return 0;
        }
        for (size_t i = 0; i < ni; i++)
            s[i] = (uint16_t)g->idx[i];
        view = add_view(d, s, ni * sizeof *s, 34963);
        free(s);
        ctype = 5123;
    } else {
        view = add_view(d, g->idx, ni * sizeof(uint32_t), 34963);
        ctype = 5125;
    }
    accessor *a = PUSH(d, accessors);
    if (!a)
        return 0;
    *a = (accessor){view, ctype, (int)ni, 1, false, {0}, {0}};
    m.idx = d->n_accessors - 1;
    mesh *dst = PUSH(d, meshes);
    if (!dst)
        return 0;
    *dst = m;
    return d->n_meshes - 1;
}

int gkw_add_light(gkw_doc *d, const gkw_light *l)
{
    light *dst = PUSH(d, lights);
    if (!dst)
        return 0;
    dst->l = *l;
    snprintf(dst->name, sizeof dst->name, "%s", l->name ? l->name : "");
    return d->n_lights - 1;
}

int gkw_add_camera(gkw_doc *d, double yfov, double znear, double zfar)
{
    for (int k = 0; k < 3; k++) {
        double *v = PUSH(d, cameras);
        if (!v)
            return 0;
        *v = k == 0 ? yfov : k == 1 ? znear : zfar;
    }
    return d->n_cameras / 3 - 1;
}

gkw_node *gkw_node_add(gkw_doc *d, const char *name, int *index_out)
{
    if (d->n_nodes >= 256) {
        d->oom = true;
        return NULL;
    }
    gkw_node *n = PUSH(d, nodes);
    if (!n)
        return NULL;
    snprintf(d->node_names[d->n_nodes - 1], sizeof d->node_names[0], "%s", name);
    *n = (gkw_node){NULL, -1, v3(0, 0, 0), (quat){0, 0, 0, 1}, v3(1, 1, 1), -1, -1, -1};
    if (index_out)
        *index_out = d->n_nodes - 1;
    return n;
}

int gkw_add_channel(gkw_doc *d, int node, const char *path, const char *interp, int n, const float *times,
                const float *values)
{
    int comps = !strcmp(path, "rotation") ? 4 : 3;
    channel c = {node, 0, 0, {0}, {0}};
    c.input = add_float_accessor(d, times, n, 1, 0, true);
    c.output = add_float_accessor(d, values, n, comps, 0, false);
    snprintf(c.path, sizeof c.path, "%s", path);
    snprintf(c.interp, sizeof c.interp, "%s", interp);
    channel *dst = PUSH(d, channels);
    if (!dst)
        return -1;
    *dst = c;
    return 0;
}

void gkw_description(gkw_doc *d, const char *description, const char *methods)
{
    snprintf(d->description, sizeof d->description, "%s", description);
    snprintf(d->methods, sizeof d->methods, "%s", methods ? methods : "");
}

void gkw_exposure(gkw_doc *d, double ev)
{
    d->has_exposure = true;
    d->exposure = ev;
}

void gkw_medium(gkw_doc *d, const double sigma_s[3], const double sigma_a[3], double g)
{
    d->has_medium = true;
    memcpy(d->sigma_s, sigma_s, sizeof d->sigma_s);
    memcpy(d->sigma_a, sigma_a, sizeof d->sigma_a);
    d->g = g;
}

void gkw_environment(gkw_doc *d, const char *uri, double intensity)
{
    snprintf(d->environment_uri, sizeof d->environment_uri, "%s", uri);
    d->environment_intensity = intensity;
}

void gkw_medium_bounds(gkw_doc *d, const double lo[3], const double hi[3])
{
    d->medium_bounded = true;
    memcpy(d->medium_lo, lo, sizeof d->medium_lo);
    memcpy(d->medium_hi, hi, sizeof d->medium_hi);
}

void gkw_param(gkw_doc *d, const char *key, int n, const double *v)
{
    if (d->n_params >= 16 || n < 1 || n > 4)
        return;
    param *p = &d->params[d->n_params++];
    snprintf(p->key, sizeof p->key, "%s", key);
    p->n = n;
    memcpy(p->v, v, (size_t)n * sizeof(double));
}

static void write_materials(gkw_doc *d, sbuf *b, bool *ext_strength, bool *ext_trans, bool *ext_ior,
                            bool *ext_specular)
{
    sb_printf(b, ",\n\"materials\":[");
    int tex = 0;
    for (int i = 0; i < d->n_materials; i++) {
        const gkw_material *m = &d->materials[i].m;
        sb_printf(b, "%s\n {\"name\":", i ? "," : "");
        sb_str(b, d->materials[i].name);
        sb_printf(b, ",\"pbrMetallicRoughness\":{\"baseColorFactor\":");
        sb_nums(b, m->base, 4);
        if (d->materials[i].uri[0])
            sb_printf(b, ",\"baseColorTexture\":{\"index\":%d}", tex++);
        sb_printf(b, ",\"metallicFactor\":");
        sb_num(b, m->metallic);
        sb_printf(b, ",\"roughnessFactor\":");
        sb_num(b, m->roughness);
        sb_printf(b, "},\"emissiveFactor\":");
        sb_nums(b, m->emissive, 3);
        if (m->double_sided)
            sb_printf(b, ",\"doubleSided\":true");
        bool strength = m->emissive_strength > 0, trans = m->transmission > 0, ior = m->ior > 0;
        if (strength || trans || ior || m->with_specular) {
            sb_printf(b, ",\"extensions\":{");
            const char *sep = "";
            if (strength) {
                sb_printf(b, "\"KHR_materials_emissive_strength\":{\"emissiveStrength\":");
                sb_num(b, m->emissive_strength);
                sb_printf(b, "}");
                sep = ",";
                *ext_strength = true;
            }
            if (trans) {
                sb_printf(b, "%s\"KHR_materials_transmission\":{\"transmissionFactor\":", sep);
                sb_num(b, m->transmission);
                sb_printf(b, "}");
                sep = ",";
                *ext_trans = true;
            }
            if (ior) {
                sb_printf(b, "%s\"KHR_materials_ior\":{\"ior\":", sep);
                sb_num(b, m->ior);
                sb_printf(b, "}");
                sep = ",";
                *ext_ior = true;
            }
            if (m->with_specular) {
                sb_printf(b, "%s\"KHR_materials_specular\":{\"specularFactor\":", sep);
                sb_num(b, m->specular);
                sb_printf(b, ",\"specularColorFactor\":");
                sb_nums(b, m->specular_color, 3);
                sb_printf(b, "}");
                *ext_specular = true;
            }
            sb_printf(b, "}");
        }
        if (m->light_proxy)
            sb_printf(b, ",\"extras\":{\"gikiosk\":{\"light_proxy\":true}}");
        sb_printf(b, "}");
    }
    sb_printf(b, "]");
    if (tex) {
        sb_printf(b, ",\n\"textures\":[");
        for (int i = 0; i < tex; i++)
            sb_printf(b, "%s{\"source\":%d}", i ? "," : "", i);
        sb_printf(b, "],\n\"images\":[");
        for (int i = 0, k = 0; i < d->n_materials; i++)
            if (d->materials[i].uri[0]) {
                sb_printf(b, "%s{\"uri\":", k++ ? "," : "");
                sb_str(b, d->materials[i].uri);
                sb_printf(b, "}");
            }
        sb_printf(b, "]");
    }
}

static void write_nodes_and_scene(gkw_doc *d, sbuf *b)
{
    sb_printf(b, ",\n\"nodes\":[");
    for (int i = 0; i < d->n_nodes; i++) {
        const gkw_node *n = &d->nodes[i];
        sb_printf(b, "%s\n {\"name\":", i ? "," : "");
        sb_str(b, d->node_names[i]);
        double t[3] = {n->t.x, n->t.y, n->t.z}, r[4] = {n->r.x, n->r.y, n->r.z, n->r.w}, s[3] = {n->s.x, n->s.y, n->s.z};
        sb_printf(b, ",\"translation\":");
        sb_nums(b, t, 3);
        sb_printf(b, ",\"rotation\":");
        sb_nums(b, r, 4);
        sb_printf(b, ",\"scale\":");
        sb_nums(b, s, 3);
        if (n->mesh >= 0)
            sb_printf(b, ",\"mesh\":%d", n->mesh);
        if (n->camera >= 0)
            sb_printf(b, ",\"camera\":%d", n->camera);
        if (n->light >= 0)
            sb_printf(b, ",\"extensions\":{\"KHR_lights_punctual\":{\"light\":%d}}", n->light);
        int nc = 0;
        for (int c = 0; c < d->n_nodes; c++)
            if (d->nodes[c].parent == i)
                sb_printf(b, "%s%d", nc++ ? "," : ",\"children\":[", c);
        if (nc)
            sb_printf(b, "]");
        sb_printf(b, "}");
    }
    sb_printf(b, "],\n\"scene\":0,\n\"scenes\":[{\"name\":");
    sb_str(b, d->name);
    sb_printf(b, ",\"nodes\":[");
    for (int i = 0, k = 0; i < d->n_nodes; i++)
        if (d->nodes[i].parent < 0)
            sb_printf(b, "%s%d", k++ ? "," : "", i);
    sb_printf(b, "],\"extras\":{\"gikiosk\":{\"description\":");
    sb_str(b, d->description);
    if (d->methods[0]) {
        sb_printf(b, ",\"methods\":");
        sb_str(b, d->methods);
    }
    if (d->has_exposure) {
        sb_printf(b, ",\"exposure\":");
        sb_num(b, d->exposure);
    }
    if (d->n_params) {
        sb_printf(b, ",\"params\":{");
        for (int i = 0; i < d->n_params; i++) {
            sb_printf(b, "%s", i ? "," : "");
            sb_str(b, d->params[i].key);
            sb_printf(b, ":");
            if (d->params[i].n == 1)
                sb_num(b, d->params[i].v[0]);
            else
                sb_nums(b, d->params[i].v, d->params[i].n);
        }
        sb_printf(b, "}");
    }
    if (d->has_medium) {
        sb_printf(b, ",\"medium\":{\"sigma_s\":");
        sb_nums(b, d->sigma_s, 3);
        sb_printf(b, ",\"sigma_a\":");
        sb_nums(b, d->sigma_a, 3);
        sb_printf(b, ",\"g\":");
        sb_num(b, d->g);
        if (d->medium_bounded) {
            sb_printf(b, ",\"bounds\":[");
            sb_nums(b, d->medium_lo, 3);
            sb_printf(b, ",");
            sb_nums(b, d->medium_hi, 3);
            sb_printf(b, "]");
        }
        sb_printf(b, "}");
    }
    if (d->environment_uri[0]) {
        sb_printf(b, ",\"environment\":{\"uri\":");
        sb_str(b, d->environment_uri);
        sb_printf(b, ",\"intensity\":");
        sb_num(b, d->environment_intensity);
        sb_printf(b, "}");
    }
    sb_printf(b, "}}}]");
}

static void write_lights_cameras_anims(gkw_doc *d, sbuf *b)
{
    if (d->n_cameras) {
        sb_printf(b, ",\n\"cameras\":[");
        for (int i = 0; i < d->n_cameras / 3; i++) {
            sb_printf(b, "%s{\"type\":\"perspective\",\"perspective\":{\"yfov\":", i ? "," : "");
            sb_num(b, d->cameras[3 * i]);
            sb_printf(b, ",\"znear\":");
            sb_num(b, d->cameras[3 * i + 1]);
            sb_printf(b, ",\"zfar\":");
            sb_num(b, d->cameras[3 * i + 2]);
            sb_printf(b, "}}");
        }
        sb_printf(b, "]");
    }
    if (d->n_channels) {
        sb_printf(b, ",\n\"animations\":[{\"name\":\"loop\",\"channels\":[");
        for (int i = 0; i < d->n_channels; i++)
            sb_printf(b, "%s{\"sampler\":%d,\"target\":{\"node\":%d,\"path\":\"%s\"}}", i ? "," : "", i,
                      d->channels[i].node, d->channels[i].path);
        sb_printf(b, "],\"samplers\":[");
        for (int i = 0; i < d->n_channels; i++)
            sb_printf(b, "%s{\"input\":%d,\"output\":%d,\"interpolation\":\"%s\"}", i ? "," : "", d->channels[i].input,
                      d->channels[i].output, d->channels[i].interp);
        sb_printf(b, "]}]");
    }
    if (d->n_lights) {
        sb_printf(b, ",\n\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[");
        for (int i = 0; i < d->n_lights; i++) {
            const gkw_light *l = &d->lights[i].l;
            sb_printf(b, "%s\n {\"name\":", i ? "," : "");
            sb_str(b, d->lights[i].name);
            sb_printf(b, ",\"type\":\"%s\",\"color\":", l->type);
            sb_nums(b, l->color, 3);
            sb_printf(b, ",\"intensity\":");
            sb_num(b, l->intensity);
            if (!strcmp(l->type, "spot")) {
                sb_printf(b, ",\"spot\":{\"innerConeAngle\":");
                sb_num(b, l->inner_cone);
                sb_printf(b, ",\"outerConeAngle\":");
                sb_num(b, l->outer_cone);
                sb_printf(b, "}");
            }
            if (l->radius > 0) {
                sb_printf(b, ",\"extras\":{\"gikiosk\":{\"radius\":");
                sb_num(b, l->radius);
                sb_printf(b, "}}");
            } else if (l->size[0] > 0) {
                sb_printf(b, ",\"extras\":{\"gikiosk\":{\"size\":");
                sb_nums(b, l->size, 2);
                sb_printf(b, "}}");
            }
            sb_printf(b, "}");
        }
        sb_printf(b, "]}}");
    }
}

static void write_buffers(gkw_doc *d, sbuf *b)
{
    sb_printf(b, ",\n\"buffers\":[{\"uri\":\"%s.bin\",\"byteLength\":%zu}]", d->name, d->bin_len);
    sb_printf(b, ",\n\"bufferViews\":[");
    for (int i = 0; i < d->n_views; i++) {
        sb_printf(b, "%s\n {\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu", i ? "," : "", d->views[i].offset,
                  d->views[i].length);
        if (d->views[i].target)
            sb_printf(b, ",\"target\":%d", d->views[i].target);
        sb_printf(b, "}");
    }
    static const char *const types[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
    sb_printf(b, "],\n\"accessors\":[");
    for (int i = 0; i < d->n_accessors; i++) {
        const accessor *a = &d->accessors[i];
        sb_printf(b, "%s\n {\"bufferView\":%d,\"componentType\":%d,\"count\":%d,\"type\":\"%s\"", i ? "," : "", a->view,
                  a->ctype, a->count, types[a->comps]);
        if (a->minmax) {
            sb_printf(b, ",\"min\":");
            sb_nums(b, a->min, a->comps);
            sb_printf(b, ",\"max\":");
            sb_nums(b, a->max, a->comps);
        }
        sb_printf(b, "}");
    }
    sb_printf(b, "]");
}

int gkw_write(gkw_doc *d, const char *dir, gk_err *e)
{
    if (d->oom)
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory while building the scene", d->name);
    sbuf b = {0};
    bool ext_strength = false, ext_trans = false, ext_ior = false, ext_specular = false;
    sb_printf(&b, "{\n\"asset\":{\"version\":\"2.0\",\"generator\":\"gikiosk build-scenes\"}");
    write_materials(d, &b, &ext_strength, &ext_trans, &ext_ior, &ext_specular);
    sb_printf(&b, ",\n\"meshes\":[");
    for (int i = 0; i < d->n_meshes; i++) {
        const mesh *m = &d->meshes[i];
        sb_printf(&b, "%s\n {\"name\":", i ? "," : "");
        sb_str(&b, m->name);
        sb_printf(&b, ",\"primitives\":[{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d", m->pos, m->nrm);
        if (m->uv >= 0)
            sb_printf(&b, ",\"TEXCOORD_0\":%d", m->uv);
        sb_printf(&b, "},\"indices\":%d,\"material\":%d,\"mode\":4}]}", m->idx, m->material);
    }
    sb_printf(&b, "]");
    write_nodes_and_scene(d, &b);
    write_lights_cameras_anims(d, &b);
    write_buffers(d, &b);
    const char *used[5];
    int n_used = 0;
    if (d->n_lights)
        used[n_used++] = "KHR_lights_punctual";
    if (ext_strength)
        used[n_used++] = "KHR_materials_emissive_strength";
    if (ext_ior)
        used[n_used++] = "KHR_materials_ior";
    if (ext_specular)
        used[n_used++] = "KHR_materials_specular";
    if (ext_trans)
        used[n_used++] = "KHR_materials_transmission";
    if (n_used) {
        sb_printf(&b, ",\n\"extensionsUsed\":[");
        for (int i = 0; i < n_used; i++)
            sb_printf(&b, "%s\"%s\"", i ? "," : "", used[i]);
        sb_printf(&b, "]");
    }
    sb_printf(&b, "\n}\n");
    if (!b.s)
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory while writing", d->name);
    char path[1024];
    int rc = 0;
    const char *exts[2] = {"gltf", "bin"};
    const void *data[2] = {b.s, d->bin};
    size_t len[2] = {b.len, d->bin_len};
    for (int k = 0; k < 2 && rc == 0; k++) {
        snprintf(path, sizeof path, "%s/%s.%s", dir, d->name, exts[k]);
        gk_outfile o; /* a temporary file renamed into place: never a half-written scene */
        rc = gk_outfile_open(&o, path, e);
        if (rc == 0) {
            if (len[k])
                fwrite(data[k], 1, len[k], o.f); /* checked by the commit */
            rc = gk_outfile_commit(&o, e);
        }
    }
    free(b.s);
    return rc;
}
