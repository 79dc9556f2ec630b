/* Caustic photons emitted towards the specular geometry (see caustic_emit.h). */
#include "caustic_emit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lights.h"

/* The targets: non-empty cells of a grid over the delta triangles' bounding box, each a sphere
   around the vertices of the triangles whose centroid falls in it. */
static int build_targets(gk_caustic_emitter *em, const gk_ref_scene *rs, int grid)
{
    vec3 lo = v3(INFINITY, INFINITY, INFINITY), hi = v3(-INFINITY, -INFINITY, -INFINITY);
    uint32_t n_delta = 0;
    for (uint32_t i = 0; i < rs->n_tris; i++) {
        if (!gk_ref_material_may_be_delta(&rs->materials[rs->tris[i].material]))
            continue;
        n_delta++;
        for (int k = 0; k < 3; k++) {
            lo = v3_min(lo, rs->tris[i].p[k]);
            hi = v3_max(hi, rs->tris[i].p[k]);
        }
    }
    if (n_delta == 0)
        return 0;
    int cells = grid * grid * grid;
    vec3 *clo = malloc(sizeof(vec3) * (size_t)cells), *chi = malloc(sizeof(vec3) * (size_t)cells);
    int *slot = malloc(sizeof(int) * (size_t)cells);
    em->target_centre = malloc(sizeof(vec3) * (size_t)cells);
    em->target_radius = calloc((size_t)cells, sizeof(float));
    if (!clo || !chi || !slot || !em->target_centre || !em->target_radius) {
        free(clo), free(chi), free(slot);
        return -1;
    }
    for (int c = 0; c < cells; c++) {
        clo[c] = v3(INFINITY, INFINITY, INFINITY);
        chi[c] = v3(-INFINITY, -INFINITY, -INFINITY);
        slot[c] = -1;
    }
    vec3 ext = v3_sub(hi, lo);
    float lo_a[3] = {lo.x, lo.y, lo.z}, ext_a[3] = {ext.x, ext.y, ext.z};
    /* Pass 1: each cell's vertex bounding box; pass 2: the sphere's radius around the box centre. */
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t i = 0; i < rs->n_tris; i++) {
            const gk_ref_tri *t = &rs->tris[i];
            if (!gk_ref_material_may_be_delta(&rs->materials[t->material]))
                continue;
            vec3 cen = v3_scale(v3_add(v3_add(t->p[0], t->p[1]), t->p[2]), 1.0f / 3.0f);
            float cen_a[3] = {cen.x, cen.y, cen.z};
            int idx[3];
            for (int a = 0; a < 3; a++) {
                int k = ext_a[a] > 0.0f ? (int)((cen_a[a] - lo_a[a]) / ext_a[a] * (float)grid) : 0;
                idx[a] = k < 0 ? 0 : (k >= grid ? grid - 1 : k);
            }
            int c = (idx[2] * grid + idx[1]) * grid + idx[0];
            for (int k = 0; k < 3; k++) {
                if (pass == 0) {
                    clo[c] = v3_min(clo[c], t->p[k]);
                    chi[c] = v3_max(chi[c], t->p[k]);
                } else {
                    if (slot[c] < 0) {
                        slot[c] = em->n_targets++;
                        em->target_centre[slot[c]] = v3_scale(v3_add(clo[c], chi[c]), 0.5f);
                    }
                    float r = v3_len(v3_sub(t->p[k], em->target_centre[slot[c]]));
                    if (r > em->target_radius[slot[c]])
                        em->target_radius[slot[c]] = r;
                }
            }
        }
    /* Float rounding must not leave a vertex outside its sphere. */
    for (int k = 0; k < em->n_targets; k++)
        em->target_radius[k] = em->target_radius[k] * 1.0001f + 1e-6f * rs->radius;
    free(clo), free(chi), free(slot);
    return 0;
}

/* The cone of target k seen from p. */
static gk_caustic_cone cone_towards(vec3 p, vec3 c, float r)
{
    gk_caustic_cone k;
    vec3 to = v3_sub(c, p);
    float d = v3_len(to);
    if (d <= r) {
        k.axis = v3(0, 0, 1);
        k.cos_max = -1.0f;
    } else {
        k.axis = v3_scale(to, 1.0f / d);
        float s = r / d;
        k.cos_max = sqrtf(fmaxf(0.0f, 1.0f - s * s));
    }
    k.solid_angle = 2.0f * GK_PI * (1.0f - k.cos_max);
    return k;
}

/* Can a direction inside cone k leave spot light L with a non-zero falloff? (The angle between the
   axes must not exceed the two half angles together.) */
static bool spot_sees(const gk_ref_light *L, const gk_caustic_cone *k)
{
    if (k->cos_max <= -1.0f || !L->spot_mask)
        return true;
    float between = acosf(fminf(1.0f, fmaxf(-1.0f, v3_dot(k->axis, L->axis))));
    return between <= acosf(k->cos_max) + acosf(fmaxf(-1.0f, fminf(1.0f, L->cos_outer))) + 1e-4f;
}

int gk_caustic_emitter_build(gk_caustic_emitter *em, const gk_ref_scene *rs, int grid, gk_err *e)
{
    memset(em, 0, sizeof *em);
    if (grid < 1 || grid > 64)
        return gk_fail(e, GK_EINPUT, "reference: caustic target grid %d is not in [1, 64]", grid);
    em->n_lights = rs->n_lights;
    em->guided = calloc((size_t)rs->n_lights + 1, sizeof(bool));
    em->first_cone = calloc((size_t)rs->n_lights + 1, sizeof(int));
    if (!em->guided || !em->first_cone || build_targets(em, rs, grid) != 0)
        goto oom;
    size_t max_cones = (size_t)rs->n_lights * (size_t)em->n_targets;
    em->cones = malloc(sizeof(gk_caustic_cone) * (max_cones + 1));
    em->cone_cdf = malloc(sizeof(float) * (max_cones + 1));
    if (!em->cones || !em->cone_cdf)
        goto oom;
    int n = 0;
    for (int l = 0; l < rs->n_lights; l++) {
        const gk_ref_light *L = &rs->lights[l];
        em->first_cone[l] = n;
        em->guided[l] = (L->kind == GK_REF_POINT || L->kind == GK_REF_SPOT) && em->n_targets > 0;
        if (!em->guided[l])
            continue;
        float sum = 0.0f;
        for (int t = 0; t < em->n_targets; t++) {
            gk_caustic_cone k = cone_towards(L->pos, em->target_centre[t], em->target_radius[t]);
            if (L->kind == GK_REF_SPOT && !spot_sees(L, &k))
                continue;
            sum += k.solid_angle;
            em->cones[n] = k;
            em->cone_cdf[n++] = sum;
        }
    }
    em->first_cone[rs->n_lights] = n;
    return 0;
oom:
    gk_caustic_emitter_free(em);
    return gk_fail(e, GK_ERUNTIME, "reference: out of memory for the caustic photon targets");
}

void gk_caustic_emitter_free(gk_caustic_emitter *em)
{
    free(em->target_centre);
    free(em->target_radius);
    free(em->guided);
    free(em->first_cone);
    free(em->cones);
    free(em->cone_cdf);
    memset(em, 0, sizeof *em);
}

bool gk_caustic_photon(const gk_ref_scene *rs, const gk_caustic_emitter *em, gk_rng *rng, vec3 *o, vec3 *d,
                       vec3 *flux, int *light)
{
    /* The same six numbers as gk_light_photon, so unguided lights emit exactly as there. */
    float u0 = gk_rng_float(rng), u[5];
    for (int k = 0; k < 5; k++)
        u[k] = gk_rng_float(rng);
    float pl;
    int li = gk_light_pick(rs, u0, &pl);
    if (li < 0)
        return false;
    *light = li;
    if (!em->guided[li])
        return gk_light_photon_of(rs, li, pl, u, o, d, flux);
    int c0 = em->first_cone[li], c1 = em->first_cone[li + 1];
    if (c1 == c0)
        return false; /* a spot that sees no delta surface: no caustic can start from it */
    const gk_ref_light *L = &rs->lights[li];
    float total = em->cone_cdf[c1 - 1], x = u[0] * total;
    int pick = c0;
    while (pick < c1 - 1 && em->cone_cdf[pick] <= x)
        pick++;
    const gk_caustic_cone *k = &em->cones[pick];
    vec3 t, b;
    gk_onb(k->axis, &t, &b);
    *o = L->pos;
    *d = gk_to_world(gk_sample_uniform_cone(u[1], u[2], k->cos_max), t, b, k->axis);
    /* Mixture pdf (balance heuristic): with p_k = Omega_k / total, pdf = covering cones / total. */
    int cover = 1;
    for (int j = c0; j < c1; j++)
        if (j != pick && v3_dot(*d, em->cones[j].axis) >= em->cones[j].cos_max)
            cover++;
    float falloff = L->kind == GK_REF_SPOT ? gk_spot_falloff(L, *d) : 1.0f;
    *flux = v3_scale(L->intensity, falloff * total / ((float)cover * pl));
    return falloff > 0.0f;
}
