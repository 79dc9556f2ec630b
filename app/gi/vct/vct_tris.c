/* The triangle list the compute voxelizer reads: world space, one albedo and emission per triangle
 * (base colour x the base-colour texture at the triangle's centroid), and what the voxelizer needs
 * to cut an alphaMode MASK material's holes: the vertices' alpha and base-colour UVs, the
 * material's layer of the alpha-mask array (vct_alpha.c) and cutoff. Static triangles first, then
 * those of animated nodes, which are re-transformed when their node moves. Light-proxy meshes are
 * left out: the area light they stand for is already the direct light, and the path tracer does not
 * intersect them either. */
#include <stdlib.h>
#include <string.h>

#include "vct_internal.h"

static vec3 tex_sample(const gk_texture *t, float u, float v)
{
    if (!t->rgba || t->width <= 0 || t->height <= 0)
        return v3(1, 1, 1);
    u -= floorf(u);
    v -= floorf(v);
    int x = (int)(u * (float)t->width), y = (int)(v * (float)t->height);
    x = x < 0 ? 0 : (x >= t->width ? t->width - 1 : x);
    y = y < 0 ? 0 : (y >= t->height ? t->height - 1 : y);
    const float *p = t->rgba + ((size_t)y * (size_t)t->width + (size_t)x) * 4;
    return v3(p[0], p[1], p[2]);
}

/* The share of the light a surface's diffuse lobe reradiates (brdf_spec.md's fresnel_mix):
 * 1 - w max(Fd), with Fd's Schlick weight (1 - v.h)^5 averaged over cosine-weighted incident and
 * outgoing directions, because a voxel's directions are not known: 0.028 (1 - mu)^2.6 (brdf.glsl's
 * gk_brdf_diffuse_gathered) averaged over mu with weight 2 mu is 0.028 * 2 / (3.6 * 4.6) = 0.00338.
 * 1 for a Lambertian material (w = 0); metallic is left out, as the voxels always were. */
static float diffuse_share(const gk_material *mat)
{
    float r = (mat->ior - 1.0f) / (mat->ior + 1.0f);
    float c0_max = 0.0f;
    for (int c = 0; c < 3; c++)
        c0_max = fmaxf(c0_max, fminf(r * r * mat->specular_color[c], 1.0f));
    return 1.0f - mat->specular * (c0_max + (1.0f - c0_max) * 0.00338f);
}

static bool mesh_skipped(const gk_scene *s, const gk_mesh *m)
{
    return m->material >= 0 && m->material < s->n_materials && s->materials[m->material].light_proxy;
}

static void emit_tri(const vct_tris *tris, const gk_scene *s, const gk_node *node, const gk_mesh *m, uint32_t t,
                     float *out)
{
    const gk_material *mat = (m->material >= 0 && m->material < s->n_materials) ? &s->materials[m->material] : NULL;
    int layer = mat ? tris->mask_layer[m->material] : -1;
    float *uv = out + 20;
    vec3 alb = mat ? v3(mat->base_color[0], mat->base_color[1], mat->base_color[2]) : v3(0.8f, 0.8f, 0.8f);
    vec3 emi = mat ? v3(mat->emissive[0], mat->emissive[1], mat->emissive[2]) : v3(0, 0, 0);
    float uc = 0, vc = 0;
    for (int k = 0; k < 3; k++) {
        uint32_t idx = m->indices[t * 3 + k];
        vec3 p = v3(m->positions[idx * 3], m->positions[idx * 3 + 1], m->positions[idx * 3 + 2]);
        vec3 w = m4_point(node->world, p);
        out[k * 4 + 0] = w.x;
        out[k * 4 + 1] = w.y;
        out[k * 4 + 2] = w.z;
        /* glTF: alpha = base colour factor x texture x COLOR_0 (the texture: the voxelizer's) */
        out[k * 4 + 3] = (mat ? mat->base_color[3] : 1.0f) * (m->colors ? m->colors[idx * 4 + 3] : 1.0f);
        const float *set = mat && mat->tex_uv[GK_SLOT_BASE].texcoord == 1 && m->uvs1 ? m->uvs1 : m->uvs;
        uv[2 * k] = uv[2 * k + 1] = 0.0f;
        if (set) {
            uc += set[idx * 2] / 3.0f;
            vc += set[idx * 2 + 1] / 3.0f;
            /* the transform is affine: transformed at the vertices, interpolated on the GPU */
            if (mat)
                gk_tex_uv_apply(&mat->tex_uv[GK_SLOT_BASE], set[idx * 2], set[idx * 2 + 1], &uv[2 * k], &uv[2 * k + 1]);
        }
    }
    uv[6] = (float)layer;
    uv[7] = mat && mat->alpha_mask ? mat->alpha_cutoff : -1.0f;
    if (mat && mat->base_color_tex >= 0 && mat->base_color_tex < s->n_textures && m->uvs) {
        gk_tex_uv_apply(&mat->tex_uv[GK_SLOT_BASE], uc, vc, &uc, &vc);
        alb = v3_mul(alb, tex_sample(&s->textures[mat->base_color_tex], uc, vc));
    }
    if (mat)
        alb = v3_scale(alb, diffuse_share(mat));
    float *a = out + 12, *em = out + 16;
    a[0] = alb.x, a[1] = alb.y, a[2] = alb.z, a[3] = 1.0f;
    em[0] = emi.x, em[1] = emi.y, em[2] = emi.z, em[3] = 0.0f;
}

void vct_tris_free(vct_tris *t)
{
    free(t->data);
    free(t->dyn_node);
    free(t->dyn_mesh);
    free(t->dyn_tri);
    free(t->dyn_world);
    free(t->mask_layer);
    memset(t, 0, sizeof *t);
}

int vct_tris_build(vct_tris *t, const gk_scene *s, gk_err *e)
{
    vct_tris_free(t);
    long total = 0;
    for (int ni = 0; ni < s->n_nodes; ni++)
        for (int mi = s->nodes[ni].mesh_first; mi < s->nodes[ni].mesh_first + s->nodes[ni].mesh_count; mi++)
            if (!mesh_skipped(s, &s->meshes[mi]))
                total += s->meshes[mi].n_triangles;
    t->data = calloc((size_t)(total ? total : 1), VCT_TRI_FLOATS * sizeof(float));
    t->dyn_node = calloc((size_t)(total ? total : 1), sizeof(int));
    t->dyn_mesh = calloc((size_t)(total ? total : 1), sizeof(int));
    t->dyn_tri = calloc((size_t)(total ? total : 1), sizeof(int));
    t->dyn_world = calloc((size_t)(s->n_nodes ? s->n_nodes : 1), 16 * sizeof(float));
    t->mask_layer = calloc((size_t)(s->n_materials ? s->n_materials : 1), sizeof(int));
    if (!t->data || !t->dyn_node || !t->dyn_mesh || !t->dyn_tri || !t->dyn_world || !t->mask_layer) {
        vct_tris_free(t);
        return gk_fail(e, GK_ERUNTIME, "vct: out of memory for %ld triangles", total);
    }
    vct_alpha_layers(s, t->mask_layer);
    int n = 0;
    for (int pass = 0; pass < 2; pass++) {          /* 0: static nodes, 1: animated nodes */
        if (pass == 1)
            t->n_static = n;
        for (int ni = 0; ni < s->n_nodes; ni++) {
            const gk_node *node = &s->nodes[ni];
            if (node->animated != (pass == 1))
                continue;
            memcpy(t->dyn_world + ni * 16, node->world.m, 16 * sizeof(float));
            for (int mi = node->mesh_first; mi < node->mesh_first + node->mesh_count; mi++) {
                const gk_mesh *m = &s->meshes[mi];
                if (mesh_skipped(s, m))
                    continue;
                for (uint32_t tri = 0; tri < m->n_triangles; tri++) {
                    emit_tri(t, s, node, m, tri, t->data + (size_t)n * VCT_TRI_FLOATS);
                    if (pass == 1) {
                        t->dyn_node[n - t->n_static] = ni;
                        t->dyn_mesh[n - t->n_static] = mi;
                        t->dyn_tri[n - t->n_static] = (int)tri;
                    }
                    const float *em = t->data + (size_t)n * VCT_TRI_FLOATS + 16;
                    for (int k = 0; k < 3; k++)
                        if (em[k] > t->max_emission)
                            t->max_emission = em[k];
                    n++;
                }
            }
        }
    }
    t->n = n;
    return 0;
}

static void grow(vec3 *lo, vec3 *hi, const float *tri)
{
    for (int k = 0; k < 3; k++) {
        vec3 p = v3(tri[k * 4], tri[k * 4 + 1], tri[k * 4 + 2]);
        *lo = v3_min(*lo, p);
        *hi = v3_max(*hi, p);
    }
}

bool vct_tris_update(vct_tris *t, const gk_scene *s, vec3 *bmin, vec3 *bmax)
{
    bool moved = false;
    vec3 lo = v3(1e30f, 1e30f, 1e30f), hi = v3(-1e30f, -1e30f, -1e30f);
    for (int i = t->n_static; i < t->n; i++) {
        int ni = t->dyn_node[i - t->n_static];
        const gk_node *node = &s->nodes[ni];
        if (memcmp(t->dyn_world + ni * 16, node->world.m, 16 * sizeof(float)) == 0)
            continue;
        float *tri = t->data + (size_t)i * VCT_TRI_FLOATS;
        grow(&lo, &hi, tri);                                  /* where it was */
        emit_tri(t, s, node, &s->meshes[t->dyn_mesh[i - t->n_static]], (uint32_t)t->dyn_tri[i - t->n_static], tri);
        grow(&lo, &hi, tri);                                  /* where it is */
        moved = true;
    }
    if (moved)
        for (int ni = 0; ni < s->n_nodes; ni++)
            if (s->nodes[ni].animated)
                memcpy(t->dyn_world + ni * 16, s->nodes[ni].world.m, 16 * sizeof(float));
    *bmin = lo;
    *bmax = hi;
    return moved;
}
