/* Flattening a gk_scene into the path tracer's scene (see ref_scene.h). */
#include "ref_scene.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "core/tonemap.h"
#include "materials.h"
#include "sample.h"

static float lum3(vec3 c) { return gk_luminance(c.x, c.y, c.z); }

static int add_mesh_triangles(gk_ref_scene *rs, const gk_scene *s, const gk_node *node, const gk_mesh *m,
                              uint32_t *cap, gk_err *e)
{
    const gk_material *mat = &s->materials[m->material >= 0 && m->material < s->n_materials ? m->material : 0];
    if (mat->light_proxy)
        return 0; /* its area light stands in for it (scene.h) */
    mat4 w = node->world;
    bool mirrored = gk_node_mirrored(node);
    mat4 nm = m4_transpose(m4_inverse(w));
    if (rs->n_tris + m->n_triangles > *cap) {
        uint32_t nc = (*cap ? *cap * 2 : 1024);
        while (nc < rs->n_tris + m->n_triangles)
            nc *= 2;
        gk_ref_tri *t = realloc(rs->tris, sizeof *t * nc);
        if (!t)
            return gk_fail(e, GK_ERUNTIME, "reference: out of memory flattening the scene");
        rs->tris = t;
        *cap = nc;
    }
    for (uint32_t i = 0; i < m->n_triangles; i++) {
        gk_ref_tri *t = &rs->tris[rs->n_tris];
        memset(t, 0, sizeof *t);
        for (int k = 0; k < 3; k++) {
            uint32_t vi = m->indices[3 * i + k];
            const float *p = &m->positions[3 * vi];
            t->p[k] = m4_point(w, v3(p[0], p[1], p[2]));
            if (m->normals) {
                const float *n = &m->normals[3 * vi];
                t->n[k] = v3_norm(m4_dir(nm, v3(n[0], n[1], n[2])));
            }
            if (m->uvs) {
                t->uv[k][0] = m->uvs[2 * vi];
                t->uv[k][1] = m->uvs[2 * vi + 1];
            }
            const float *uv1 = m->uvs1 ? m->uvs1 : m->uvs;
            if (uv1) {
                t->uv1[k][0] = uv1[2 * vi];
                t->uv1[k][1] = uv1[2 * vi + 1];
            }
            for (int c = 0; c < 4; c++)
                t->color[k][c] = m->colors ? m->colors[4 * vi + (uint32_t)c] : 1.0f;
            if (m->tangents) {
                const float *tg = &m->tangents[4 * vi];
                vec3 tw = m4_dir(w, v3(tg[0], tg[1], tg[2]));
                t->tangent[k][0] = tw.x, t->tangent[k][1] = tw.y, t->tangent[k][2] = tw.z, t->tangent[k][3] = tg[3];
            } else {
                memset(t->tangent[k], 0, sizeof t->tangent[k]);
            }
        }
        vec3 c = v3_cross(v3_sub(t->p[1], t->p[0]), v3_sub(t->p[2], t->p[0]));
        float len = v3_len(c);
        if (!(len > 1e-20f) || !isfinite(len))
            continue; /* degenerate after transform: never hit, never sampled */
        /* the glTF front face: counter-clockwise, clockwise under a mirroring transform */
        t->ng = v3_scale(c, (mirrored ? -1.0f : 1.0f) / len);
        t->area = 0.5f * len;
        if (!m->normals)
            t->n[0] = t->n[1] = t->n[2] = t->ng;
        t->material = (int)(mat - s->materials);
        t->emissive = -1;
        rs->n_tris++;
    }
    return 0;
}

/* The brightest emission the tracer accepts, per channel (cd, lux or nits). A pixel is a float sum
 * of spp samples of emission x BRDF x geometry / pdf; the bound leaves 18 orders of magnitude
 * below FLT_MAX (3.4e38) for those factors (1/d^2 alone is 1e6 at a millimetre) and the sum, and
 * is 11 orders above the sun's disc (1.6e9 nits). An order-of-magnitude margin, not a measurement. Brighter lights (a 1e38 cd
 * point rendered black with exit 0 before) are refused by name. */
#define GK_REF_MAX_EMISSION 1e20f

static bool emission_in_range(vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z) && fabsf(v.x) <= GK_REF_MAX_EMISSION &&
           fabsf(v.y) <= GK_REF_MAX_EMISSION && fabsf(v.z) <= GK_REF_MAX_EMISSION;
}

static void light_from_node(gk_ref_light *L, const gk_light *gl, mat4 w)
{
    memset(L, 0, sizeof *L);
    L->pos = v3(w.m[12], w.m[13], w.m[14]);
    L->axis = v3_norm(v3(-w.m[8], -w.m[9], -w.m[10]));
    L->u = v3_norm(v3(w.m[0], w.m[1], w.m[2]));
    L->v = v3_norm(v3(w.m[4], w.m[5], w.m[6]));
    L->intensity = v3_scale(v3(gl->color[0], gl->color[1], gl->color[2]), gl->intensity);
    L->range = gl->range;
    L->cos_inner = cosf(gl->inner_cone);
    L->cos_outer = cosf(gl->outer_cone);
    if (L->cos_inner <= L->cos_outer)
        L->cos_inner = L->cos_outer + 1e-4f;
    float I = lum3(L->intensity);
    if (gl->type == GK_LIGHT_DIRECTIONAL) {
        if (gl->radius > 0.0f) {
            L->kind = GK_REF_SUN;
            L->sun_cos_max = cosf(gl->radius);
            float omega = 2.0f * GK_PI * (1.0f - L->sun_cos_max);
            L->radiance = v3_scale(L->intensity, 1.0f / omega); /* E = L * solid angle (small disc) */
        } else {
            L->kind = GK_REF_DIRECTIONAL;
        }
        return; /* power is set once the scene's size is known */
    }
    L->spot_mask = gl->type == GK_LIGHT_SPOT;
    if (gl->shape == GK_SHAPE_RECT && gl->size[0] > 0.0f && gl->size[1] > 0.0f) {
        L->kind = GK_REF_RECT;
        L->half_w = 0.5f * gl->size[0];
        L->half_h = 0.5f * gl->size[1];
        L->area = gl->size[0] * gl->size[1];
        L->spot_mask = false;
        L->radiance = v3_scale(L->intensity, 1.0f / L->area);
        L->power = GK_PI * I;
    } else if (gl->radius > 0.0f && gl->type == GK_LIGHT_POINT) {
        L->kind = GK_REF_SPHERE;
        L->radius = gl->radius;
        L->radiance = v3_scale(L->intensity, 1.0f / (GK_PI * gl->radius * gl->radius));
        L->power = 4.0f * GK_PI * I;
    } else if (gl->radius > 0.0f) {
        L->kind = GK_REF_DISC;
        L->radius = gl->radius;
        L->area = GK_PI * gl->radius * gl->radius;
        L->radiance = v3_scale(L->intensity, 1.0f / L->area);
        L->power = GK_PI * I;
    } else if (gl->type == GK_LIGHT_SPOT) {
        L->kind = GK_REF_SPOT;
        L->power = 2.0f * GK_PI * (1.0f - 0.5f * (L->cos_inner + L->cos_outer)) * I;
    } else {
        L->kind = GK_REF_POINT;
        L->power = 4.0f * GK_PI * I;
    }
}

static int build_cdf(const gk_ref_scene *rs, float **out, bool delta_only)
{
    float *cdf = malloc(sizeof(float) * (rs->n_lights + 1));
    if (!cdf)
        return -1;
    cdf[0] = 0.0f;
    for (int i = 0; i < rs->n_lights; i++) {
        enum gk_ref_light_kind k = rs->lights[i].kind;
        bool is_delta = k == GK_REF_POINT || k == GK_REF_SPOT || k == GK_REF_DIRECTIONAL;
        float p = (!delta_only || is_delta) ? fmaxf(rs->lights[i].power, 0.0f) : 0.0f;
        cdf[i + 1] = cdf[i] + p;
    }
    *out = cdf;
    return 0;
}

bool gk_ref_material_may_be_delta(const gk_material *mt)
{
    /* Textures multiply the factors by at most 1, so these bounds hold at every point. */
    return (mt->metallic > 0.5f && mt->roughness < 0.05f) || (mt->transmission > 0.0f && mt->roughness < 0.05f);
}

int gk_ref_scene_build(gk_ref_scene *rs, const gk_scene *s, mat4 view, mat4 proj, vec3 eye, int width,
                       int height, gk_err *e)
{
    memset(rs, 0, sizeof *rs);
    rs->mesh_light = -1;
    rs->env_light = -1;
    rs->materials = s->materials;
    rs->n_materials = s->n_materials;
    rs->textures = s->textures;
    rs->n_textures = s->n_textures;
    uint32_t cap = 0;
    int n_punctual = 0;
    for (int i = 0; i < s->n_nodes; i++) {
        const gk_node *nd = &s->nodes[i];
        for (int m = nd->mesh_first; m < nd->mesh_first + nd->mesh_count; m++)
            if (m >= 0 && m < s->n_meshes && add_mesh_triangles(rs, s, nd, &s->meshes[m], &cap, e))
                goto fail;
        if (nd->light >= 0 && nd->light < s->n_lights && !s->lights[nd->light].env_part)
            n_punctual++;
    }
    /* Emissive triangles become one mesh light, sampled in proportion to emitted power. */
    for (uint32_t i = 0; i < rs->n_tris; i++) {
        const gk_material *mt = &s->materials[rs->tris[i].material];
        if (mt->emissive[0] > 0 || mt->emissive[1] > 0 || mt->emissive[2] > 0)
            rs->n_emissive++;
    }
    rs->lights = calloc((size_t)n_punctual + 2, sizeof *rs->lights); /* + mesh light + environment */
    rs->emissive_tris = malloc(sizeof(uint32_t) * (rs->n_emissive + 1));
    rs->emissive_cdf = malloc(sizeof(float) * (rs->n_emissive + 1));
    if (!rs->lights || !rs->emissive_tris || !rs->emissive_cdf) {
        gk_fail(e, GK_ERUNTIME, "reference: out of memory flattening the scene");
        goto fail;
    }
    rs->emissive_cdf[0] = 0.0f;
    int ne = 0;
    for (uint32_t i = 0; i < rs->n_tris; i++) {
        const gk_material *mt = &s->materials[rs->tris[i].material];
        vec3 le = v3(mt->emissive[0], mt->emissive[1], mt->emissive[2]);
        if (le.x > 0 || le.y > 0 || le.z > 0) {
            rs->tris[i].emissive = ne;
            rs->emissive_tris[ne] = i;
            float w = lum3(le) * rs->tris[i].area * (mt->double_sided ? 2.0f : 1.0f);
            rs->emissive_cdf[ne + 1] = rs->emissive_cdf[ne] + fmaxf(w, 1e-12f);
            ne++;
        }
    }
    /* Bounds of geometry and lights (for directional lights and light tracing). */
    vec3 lo = v3(FLT_MAX, FLT_MAX, FLT_MAX), hi = v3(-FLT_MAX, -FLT_MAX, -FLT_MAX);
    for (uint32_t i = 0; i < rs->n_tris; i++)
        for (int k = 0; k < 3; k++) {
            lo = v3_min(lo, rs->tris[i].p[k]);
            hi = v3_max(hi, rs->tris[i].p[k]);
        }
    for (int i = 0; i < s->n_nodes; i++) {
        const gk_node *nd = &s->nodes[i];
        if (nd->light < 0 || nd->light >= s->n_lights || s->lights[nd->light].env_part)
            continue;
        gk_ref_light *L = &rs->lights[rs->n_lights++];
        light_from_node(L, &s->lights[nd->light], nd->world);
        if (!emission_in_range(L->intensity) || !emission_in_range(L->radiance) ||
            !(isfinite(L->power) && L->power <= GK_REF_MAX_EMISSION * 4.0f * GK_PI)) {
            gk_fail(e, GK_EINPUT, "%s: light %d ('%s'): emission %g beyond what the reference tracer can sum "
                    "(at most %g cd, lux or nits a channel)", s->path, nd->light, s->lights[nd->light].name,
                    (double)s->lights[nd->light].intensity, (double)GK_REF_MAX_EMISSION);
            goto fail;
        }
        if (L->kind != GK_REF_DIRECTIONAL && L->kind != GK_REF_SUN) {
            lo = v3_min(lo, L->pos);
            hi = v3_max(hi, L->pos);
        }
        if (L->kind == GK_REF_POINT || L->kind == GK_REF_SPOT || L->kind == GK_REF_DIRECTIONAL)
            rs->has_delta_lights = true;
    }
    if (lo.x > hi.x)
        lo = hi = v3(0, 0, 0);
    rs->centre = v3_scale(v3_add(lo, hi), 0.5f);
    rs->radius = fmaxf(0.5f * v3_len(v3_sub(hi, lo)), 1e-3f);
    if (s->medium.present) {
        gk_ref_medium *m = &rs->medium;
        m->present = true;
        m->sigma_s = v3(s->medium.sigma_s[0], s->medium.sigma_s[1], s->medium.sigma_s[2]);
        m->sigma_a = v3(s->medium.sigma_a[0], s->medium.sigma_a[1], s->medium.sigma_a[2]);
        m->sigma_t = v3_add(m->sigma_s, m->sigma_a);
        m->sigma_mean = (m->sigma_t.x + m->sigma_t.y + m->sigma_t.z) / 3.0f;
        m->g = s->medium.g;
        m->bounded = s->medium.bounded;
        m->box_min = s->medium.box_min;
        m->box_max = s->medium.box_max;
    }
    for (int i = 0; i < rs->n_lights; i++) {
        gk_ref_light *L = &rs->lights[i];
        if (L->kind == GK_REF_DIRECTIONAL || L->kind == GK_REF_SUN)
            L->power = lum3(L->intensity) * GK_PI * rs->radius * rs->radius;
    }
    for (uint32_t i = 0; i < rs->n_tris; i++) {
        const gk_material *mt = &s->materials[rs->tris[i].material];
        if (!emission_in_range(v3(mt->emissive[0], mt->emissive[1], mt->emissive[2]))) {
            gk_fail(e, GK_EINPUT, "%s: material '%s': emission beyond what the reference tracer can sum (at most "
                    "%g nits a channel)", s->path, mt->name, (double)GK_REF_MAX_EMISSION);
            goto fail;
        }
    }
    if (ne > 0) {
        rs->mesh_light = rs->n_lights;
        gk_ref_light *L = &rs->lights[rs->n_lights++];
        memset(L, 0, sizeof *L);
        L->kind = GK_REF_MESH;
        L->power = GK_PI * rs->emissive_cdf[ne];
    }
    if (gk_ref_env_build(&rs->env, &s->environment) != 0) {
        gk_fail(e, GK_ERUNTIME, "reference: out of memory for the environment's sampling tables");
        goto fail;
    }
    if (rs->env.env) {
        rs->env_light = rs->n_lights;
        gk_ref_light *L = &rs->lights[rs->n_lights++];
        memset(L, 0, sizeof *L);
        L->kind = GK_REF_ENV;
        L->power = rs->env.flux_density * GK_PI * rs->radius * rs->radius; /* as directional lights */
    }
    for (uint32_t i = 0; i < rs->n_tris; i++) {
        if (gk_ref_material_may_be_delta(&s->materials[rs->tris[i].material]))
            rs->has_delta_surfaces = true;
    }
    if (build_cdf(rs, &rs->light_cdf, false) || build_cdf(rs, &rs->delta_cdf, true)) {
        gk_fail(e, GK_ERUNTIME, "reference: out of memory flattening the scene");
        goto fail;
    }
    vec3 *verts = malloc(sizeof(vec3) * 3 * (rs->n_tris + 1));
    if (!verts) {
        gk_fail(e, GK_ERUNTIME, "reference: out of memory flattening the scene");
        goto fail;
    }
    for (uint32_t i = 0; i < rs->n_tris; i++)
        for (int k = 0; k < 3; k++)
            verts[3 * i + k] = rs->tris[i].p[k];
    int rc = gk_bvh_build(&rs->bvh, verts, rs->n_tris, e);
    free(verts);
    if (rc)
        goto fail;
    /* glTF alphaMode MASK and BLEND: the BVH asks the material's alpha at every hit on such a triangle */
    bool any_mask = false;
    for (uint32_t i = 0; i < rs->n_tris && !any_mask; i++)
        any_mask = rs->materials[rs->tris[i].material].alpha_mask || rs->materials[rs->tris[i].material].alpha_blend;
    if (any_mask) {
        rs->alpha_tested = calloc(rs->n_tris, 1);
        if (!rs->alpha_tested) {
            gk_fail(e, GK_ERUNTIME, "reference: out of memory flattening the scene");
            goto fail;
        }
        for (uint32_t i = 0; i < rs->n_tris; i++)
            rs->alpha_tested[i] = rs->materials[rs->tris[i].material].alpha_mask ||
                                  rs->materials[rs->tris[i].material].alpha_blend;
        rs->bvh.tested = rs->alpha_tested;
        rs->bvh.accept = gk_tri_alpha_accept;
        rs->bvh.accept_ctx = rs;
    }

    /* Camera: the inverse view's columns are the camera's axes; the projection's diagonal gives
       the image plane's half extents (symmetric perspective, as gk_scene_camera makes). */
    mat4 iv = m4_inverse(view);
    rs->width = width;
    rs->height = height;
    rs->eye = eye;
    rs->right = v3_norm(v3(iv.m[0], iv.m[1], iv.m[2]));
    rs->up = v3_norm(v3(iv.m[4], iv.m[5], iv.m[6]));
    rs->fwd = v3_norm(v3(-iv.m[8], -iv.m[9], -iv.m[10]));
    rs->tan_x = proj.m[0] != 0.0f ? 1.0f / proj.m[0] : 1.0f;
    rs->tan_y = proj.m[5] != 0.0f ? 1.0f / proj.m[5] : 1.0f;
    return 0;
fail:
    gk_ref_scene_free(rs);
    return -1;
}

void gk_ref_scene_free(gk_ref_scene *rs)
{
    gk_bvh_free(&rs->bvh);
    free(rs->alpha_tested);
    rs->alpha_tested = NULL;
    free(rs->tris);
    free(rs->lights);
    free(rs->light_cdf);
    free(rs->delta_cdf);
    free(rs->emissive_tris);
    free(rs->emissive_cdf);
    gk_ref_env_free(&rs->env);
    memset(rs, 0, sizeof *rs);
    rs->mesh_light = -1;
    rs->env_light = -1;
}

vec3 gk_ref_camera_dir(const gk_ref_scene *rs, float px, float py)
{
    float sx = (2.0f * px / (float)rs->width - 1.0f) * rs->tan_x;
    float sy = (1.0f - 2.0f * py / (float)rs->height) * rs->tan_y;
    return v3_norm(v3_add(rs->fwd, v3_add(v3_scale(rs->right, sx), v3_scale(rs->up, sy))));
}
