/* Selective photon emission: emission numbers, groups, tracing, per-surface storage (lm_photons.h). */
#include "lm_photons.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/tonemap.h"
#include "ref/lights.h"
#include "ref/materials.h"
#include "ref/sample.h"
#include "ref/trace.h"

/* The photons' random streams: any fixed number (a run is reproducible, the references' seeds
   are unrelated). */
#define LM_PHOTON_SEED 0x6c69676874ULL

float lm_halton(uint32_t i, uint32_t base)
{
    float f = 1.0f, r = 0.0f;
    while (i > 0) {
        f /= (float)base;
        r += f * (float)(i % base);
        i /= base;
    }
    return r < 1.0f ? r : 0.99999994f;
}

/* Hilbert index of (x, y) on a 2^order grid (the classic xy2d). */
static uint32_t hilbert(uint32_t order, uint32_t x, uint32_t y)
{
    uint32_t d = 0;
    for (uint32_t s = 1u << (order - 1); s > 0; s >>= 1) {
        uint32_t rx = (x & s) > 0, ry = (y & s) > 0;
        d += s * s * ((3 * rx) ^ ry);
        if (ry == 0) {
            if (rx == 1) {
                x = s - 1 - x;
                y = s - 1 - y;
            }
            uint32_t t = x;
            x = y, y = t;
        }
    }
    return d;
}

typedef struct sort_key {
    uint64_t key;
    int photon;
} sort_key;

static int cmp_sort_key(const void *pa, const void *pb)
{
    const sort_key *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return a->photon - b->photon;
}

/* Which of gk_light_photon_of's uniforms pick the direction (lights.c): u1, u2 for point and spot
   lights, u3, u4 for area emitters; a directional light's one direction: its position's. */
static int direction_dim(const gk_ref_light *L)
{
    switch (L->kind) {
    case GK_REF_POINT:
    case GK_REF_SPOT:
    case GK_REF_DIRECTIONAL: return 0;
    default: return 2;
    }
}

int lm_photons_init(lm_photons *ph, const gk_ref_scene *rs, int n_groups, int n_surfaces, float tau, gk_err *e)
{
    memset(ph, 0, sizeof *ph);
    ph->n_groups = n_groups < 1 ? 1 : n_groups;
    ph->per_group = LM_PHOTONS_PER_GROUP;
    ph->n_photons = ph->n_groups * ph->per_group;
    ph->n_stores = n_surfaces;
    ph->tau = tau;
    ph->scale = 1.0f / (float)ph->n_photons;
    ph->emit = calloc((size_t)ph->n_photons, sizeof *ph->emit);
    ph->paths = calloc((size_t)ph->n_photons, sizeof *ph->paths);
    ph->groups = calloc((size_t)ph->n_groups, sizeof *ph->groups);
    ph->stores = calloc((size_t)(n_surfaces > 0 ? n_surfaces : 1), sizeof *ph->stores);
    sort_key *keys = malloc(sizeof *keys * (size_t)ph->n_photons);
    lm_emit *raw = malloc(sizeof *raw * (size_t)ph->n_photons);
    if (!ph->emit || !ph->paths || !ph->groups || !ph->stores || !keys || !raw) {
        free(keys), free(raw);
        lm_photons_free(ph);
        return gk_fail(e, GK_ERUNTIME, "lightmap: out of memory for %d photons", ph->n_photons);
    }
    static const uint32_t primes[6] = {2, 3, 5, 7, 11, 13};
    for (int k = 0; k < ph->n_photons; k++) {
        /* Halton index k + 1: index 0 is the all-zero point */
        uint32_t i = (uint32_t)k + 1;
        lm_emit *m = &raw[k];
        m->light = gk_light_pick(rs, lm_halton(i, primes[0]), &m->prob);
        for (int d = 0; d < 5; d++)
            m->u[d] = lm_halton(i, primes[d + 1]);
        uint64_t light = m->light < 0 ? 0xffff : (uint64_t)m->light;
        int dd = m->light < 0 ? 0 : direction_dim(&rs->lights[m->light]);
        uint32_t x = (uint32_t)(m->u[dd] * 1024.0f), y = (uint32_t)(m->u[dd + 1] * 1024.0f);
        keys[k] = (sort_key){(light << 32) | hilbert(10, x > 1023 ? 1023 : x, y > 1023 ? 1023 : y), k};
    }
    qsort(keys, (size_t)ph->n_photons, sizeof *keys, cmp_sort_key);
    for (int k = 0; k < ph->n_photons; k++)
        ph->emit[k] = raw[keys[k].photon];
    for (int g = 0; g < ph->n_groups; g++)
        ph->groups[g].invalid = true;
    free(keys), free(raw);
    return 0;
}

void lm_photons_free(lm_photons *ph)
{
    if (ph->stores)
        for (int i = 0; i < ph->n_stores; i++)
            free(ph->stores[i].hits);
    free(ph->emit), free(ph->paths), free(ph->groups), free(ph->stores);
    memset(ph, 0, sizeof *ph);
}

static vec3 offset_point(const gk_ref_scene *rs, vec3 p, vec3 ng, vec3 dir)
{
    float eps = 1e-5f * (rs->radius + fmaxf(fabsf(p.x), fmaxf(fabsf(p.y), fabsf(p.z))));
    return v3_add(p, v3_scale(ng, v3_dot(dir, ng) > 0.0f ? eps : -eps));
}

void lm_trace_photon(const lm_photons *ph, const gk_ref_scene *rs, const int *ref_chart, int k, lm_path *out)
{
    out->n = 0;
    const lm_emit *m = &ph->emit[k];
    vec3 o, d, flux;
    if (m->light < 0 || !gk_light_photon_of(rs, m->light, m->prob, m->u, &o, &d, &flux))
        return;
    flux = v3_scale(flux, ph->scale);
    gk_rng rng;
    gk_rng_seed(&rng, LM_PHOTON_SEED, (uint64_t)k, 0, 0);
    /* The renderer's direct pass lights surfaces from the scene's lights, not from emissive meshes
       (it only shows their emission), so a GI method adds the light of emissive surfaces too (as
       vct's voxel emission does): their photons count as indirect from the first hit. */
    int n_diffuse = rs->lights[m->light].kind == GK_REF_MESH ? 1 : 0, n_specular = 0;
    for (int depth = 0; depth < LM_MAX_HITS; depth++) {
        gk_scene_hit h;
        if (!gk_scene_intersect(rs, o, d, INFINITY, &h) || h.light >= 0)
            return;
        const gk_ref_light *L = &rs->lights[m->light];
        if (depth == 0 && (L->kind == GK_REF_POINT || L->kind == GK_REF_SPOT))
            flux = v3_scale(flux, gk_light_window(L, h.t));
        vec3 x = v3_add(o, v3_scale(d, h.t));
        gk_surface sf;
        gk_surface_init(&sf, rs, &rs->tris[h.tri], h.b1, h.b2);
        vec3 w_in = v3_scale(d, -1.0f);
        lm_path_hit *ph_hit = &out->h[out->n++];
        ph_hit->surface = ref_chart[h.tri];
        ph_hit->stored = ph_hit->surface >= 0 && gk_surface_has_smooth_part(&sf);
        ph_hit->slot = -1;
        ph_hit->pos = x;
        ph_hit->power = flux;
        ph_hit->kind = n_diffuse > 0 ? LM_HIT_INDIRECT : (n_specular > 0 ? LM_HIT_CAUSTIC : LM_HIT_DIRECT);
        gk_bsdf_sample bs;
        if (!gk_bsdf_sample_dir(&sf, w_in, false, &rng, &bs))
            return;
        /* Russian roulette by the bounce's reflectance: the surviving photon keeps its power
           (equal energies, as the seed's photon map). */
        float q = fminf(0.95f, v3_maxc(bs.weight));
        if (!(q > 0.0f) || gk_rng_float(&rng) >= q)
            return;
        flux = v3_scale(v3_mul(flux, bs.weight), 1.0f / q);
        if (bs.delta)
            n_specular++;
        else
            n_diffuse++;
        o = offset_point(rs, x, sf.ng, bs.wi);
        d = bs.wi;
    }
}

bool lm_path_diverges(const lm_path *a, const lm_path *b, float tau)
{
    if (a->n != b->n)
        return true;
    for (int i = 0; i < a->n; i++) {
        if (a->h[i].surface != b->h[i].surface)
            return true;
        if (v3_len(v3_sub(a->h[i].pos, b->h[i].pos)) > tau)
            return true;
    }
    return false;
}

static double lum(vec3 p) { return gk_luminance(p.x, p.y, p.z); }

static void store_delta(lm_store *s, const lm_path_hit *h, double sign)
{
    double l = lum(h->power);
    s->delta_f += l;
    if (h->kind == LM_HIT_INDIRECT)
        s->delta_i += l, s->delta_g += l;
    s->energy += sign * l;
}

void lm_photons_replace(lm_photons *ph, int k, const lm_path *fresh)
{
    lm_path *p = &ph->paths[k];
    for (int i = 0; i < p->n; i++) {
        lm_path_hit *h = &p->h[i];
        if (h->slot < 0)
            continue;
        lm_store *s = &ph->stores[h->surface];
        lm_hit last = s->hits[--s->n];
        if (h->slot != s->n) {
            s->hits[h->slot] = last;
            ph->paths[last.photon].h[last.index].slot = h->slot;
        }
        store_delta(s, h, -1.0);
    }
    *p = *fresh;
    for (int i = 0; i < p->n; i++) {
        lm_path_hit *h = &p->h[i];
        h->slot = -1;
        if (!h->stored)
            continue;
        lm_store *s = &ph->stores[h->surface];
        if (s->n == s->cap) {
            int nc = s->cap ? 2 * s->cap : 16;
            lm_hit *nh = realloc(s->hits, sizeof *nh * (size_t)nc);
            if (!nh) /* out of memory: the hit is not stored (the surface is a little dark) */
                continue;
            s->hits = nh, s->cap = nc;
        }
        h->slot = s->n;
        s->hits[s->n++] = (lm_hit){h->pos, h->power, k, (uint8_t)i, h->kind};
        store_delta(s, h, 1.0);
    }
}
