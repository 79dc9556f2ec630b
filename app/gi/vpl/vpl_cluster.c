/* k-means of VPLs into VALs (thesis §6.4.1) and the helpers around it; see vpl_cluster.h. */
#include "vpl_cluster.h"

#include <math.h>
#include <string.h>

float gk_halton(uint32_t i, uint32_t base)
{
    float f = 1.0f, r = 0.0f;
    while (i > 0) {
        f /= (float)base;
        r += f * (float)(i % base);
        i /= base;
    }
    return r;
}

float gk_vpl_distance(const gk_kmeans_opts *o, vec3 p, vec3 n, vec3 cp, vec3 cn)
{
    float dx = v3_len(v3_sub(p, cp)) / o->scene_diam;
    float c = v3_dot(n, cn);
    c = c > 1.0f ? 1.0f : (c < -1.0f ? -1.0f : c);
    return o->w_pos * dx + o->w_nrm * acosf(c);
}

static bool vpl_valid(const gk_vpl *v) { return v->flux.x + v->flux.y + v->flux.z > 0.0f; }

static uint32_t bit_reverse(uint32_t k, int bits)
{
    uint32_t r = 0;
    for (int b = 0; b < bits; b++)
        r |= ((k >> b) & 1u) << (bits - 1 - b);
    return r;
}

int gk_vpl_nested_seeds(const gk_vpl *vpl, int n, int m, int *seeds)
{
    int bits = 0;
    while ((1 << bits) < n)
        bits++;
    /* Walk the bit-reversed order once; a VPL is taken when valid. Non-power-of-two n: indices
       >= n are skipped (the order stays fixed, so nesting holds). */
    int got = 0;
    for (uint32_t k = 0; k < (1u << bits) && got < m; k++) {
        uint32_t i = bit_reverse(k, bits);
        if ((int)i < n && vpl_valid(&vpl[i]))
            seeds[got++] = (int)i;
    }
    return got;
}

static void frame_from_normal(vec3 n, vec3 *t, vec3 *b)
{
    vec3 a = fabsf(n.x) < 0.9f ? v3(1, 0, 0) : v3(0, 1, 0);
    *t = v3_norm(v3_cross(a, n));
    *b = v3_cross(n, *t);
}

void gk_val_frame_area(const gk_vpl *vpl, int n, const int *labels, int k, gk_val *val)
{
    frame_from_normal(val->normal, &val->t, &val->b);
    float r[4] = {INFINITY, -INFINITY, INFINITY, -INFINITY};
    vec3 flux = v3(0, 0, 0);
    int count = 0;
    float best = INFINITY;
    val->origin = val->centre;
    for (int i = 0; i < n; i++) {
        if (labels[i] != k)
            continue;
        vec3 d = v3_sub(vpl[i].pos, val->centre);
        if (v3_dot(d, d) < best)
            best = v3_dot(d, d), val->origin = vpl[i].pos;
        float s = v3_dot(d, val->t), t = v3_dot(d, val->b);
        r[0] = fminf(r[0], s), r[1] = fmaxf(r[1], s);
        r[2] = fminf(r[2], t), r[3] = fmaxf(r[3], t);
        flux = v3_add(flux, vpl[i].flux);
        count++;
    }
    if (count == 0)
        r[0] = r[1] = r[2] = r[3] = 0.0f;
    memcpy(val->rect, r, sizeof r);
    val->flux = flux;
    val->count = count;
    float w = r[1] - r[0], h = r[3] - r[2];
    val->area = w * h;
    val->size = fmaxf(w, h);
}

static int nearest(const gk_kmeans_opts *o, const gk_vpl *v, const gk_val *vals, int m, float *dist)
{
    float best = INFINITY;
    int bk = 0;
    for (int k = 0; k < m; k++) {
        float d = gk_vpl_distance(o, v->pos, v->nrm, vals[k].centre, vals[k].normal);
        if (d < best) /* strict '<': deterministic tie-break towards the lower index */
            best = d, bk = k;
    }
    if (dist)
        *dist = best;
    return bk;
}

gk_kmeans_result gk_vpl_kmeans(const gk_vpl *vpl, int n, int m, const gk_kmeans_opts *o, int *labels,
                               gk_val *vals)
{
    gk_kmeans_result res = {0};
    if (m > GK_VPL_MAX_M)
        m = GK_VPL_MAX_M;
    if (!o->warm_start) {
        int seeds[GK_VPL_MAX_M];
        int got = gk_vpl_nested_seeds(vpl, n, m, seeds);
        if (got == 0) { /* nothing lit: no cluster */
            for (int i = 0; i < n; i++)
                labels[i] = -1;
            return res;
        }
        m = got;
        for (int k = 0; k < m; k++) {
            memset(&vals[k], 0, sizeof vals[k]);
            vals[k].centre = vpl[seeds[k]].pos;
            vals[k].normal = vpl[seeds[k]].nrm;
        }
    }
    res.m = m;
    for (int i = 0; i < n; i++)
        labels[i] = -2; /* "not yet assigned", so the first pass always counts as a change */
    for (int it = 0; it < o->max_iters; it++) {
        int changed = 0;
        for (int i = 0; i < n; i++) {
            int l = vpl_valid(&vpl[i]) ? nearest(o, &vpl[i], vals, m, NULL) : -1;
            changed += l != labels[i];
            labels[i] = l;
        }
        res.iters = it + 1;
        if (!changed)
            break;
        for (int k = 0; k < m; k++) {
            vec3 p = v3(0, 0, 0), nn = v3(0, 0, 0);
            int c = 0;
            for (int i = 0; i < n; i++)
                if (labels[i] == k)
                    p = v3_add(p, vpl[i].pos), nn = v3_add(nn, vpl[i].nrm), c++;
            if (c > 0 && v3_len(nn) > 1e-6f) { /* empty: keeps its seed (dong-001.md §4.3) */
                vals[k].centre = v3_scale(p, 1.0f / (float)c);
                vals[k].normal = v3_norm(nn);
            }
        }
    }
    double err = 0.0;
    int valid = 0;
    for (int i = 0; i < n; i++) {
        if (labels[i] < 0)
            continue;
        err += gk_vpl_distance(o, vpl[i].pos, vpl[i].nrm, vals[labels[i]].centre, vals[labels[i]].normal);
        valid++;
    }
    res.error = valid ? err / valid : 0.0;
    for (int k = 0; k < m; k++) {
        gk_val_frame_area(vpl, n, labels, k, &vals[k]);
        res.empty += vals[k].count == 0;
    }
    return res;
}

gk_kmeans_result gk_vpl_kmeans_adaptive(const gk_vpl *vpl, int n, int m_min, int m_max, float rel_drop,
                                        int prev_m, const gk_kmeans_opts *o, int *labels, gk_val *vals)
{
    gk_kmeans_opts oo = *o;
    oo.warm_start = false;
    if (m_max > GK_VPL_MAX_M)
        m_max = GK_VPL_MAX_M;
    /* Error of each power-of-two M; the chosen M is the first whose doubling gains less than
       rel_drop. Hysteresis: keep prev_m while its own doubling gain stays within [0.5, 1.5]·rel_drop
       and the gain into it stays above 0.5·rel_drop, so noise in the error does not flip M. */
    double errs[8];
    int ms[8], count = 0;
    int labels_tmp[GK_VPL_MAX_N];
    gk_val vals_tmp[GK_VPL_MAX_M];
    for (int m = m_min; m <= m_max && count < 8; m *= 2) {
        gk_kmeans_result r = gk_vpl_kmeans(vpl, n, m, &oo, labels_tmp, vals_tmp);
        ms[count] = m;
        errs[count++] = r.error;
        if (r.m < m) /* fewer valid VPLs than clusters: no point going further */
            break;
    }
    int chosen = count - 1;
    for (int j = 1; j < count; j++) {
        double drop = errs[j - 1] > 0 ? (errs[j - 1] - errs[j]) / errs[j - 1] : 0.0;
        if (drop < rel_drop) {
            chosen = j - 1;
            break;
        }
    }
    for (int j = 0; j < count; j++) {
        if (ms[j] != prev_m || j == chosen)
            continue;
        double gain_in = j > 0 && errs[j - 1] > 0 ? (errs[j - 1] - errs[j]) / errs[j - 1] : 1.0;
        double gain_out = j + 1 < count && errs[j] > 0 ? (errs[j] - errs[j + 1]) / errs[j] : 0.0;
        if (gain_in > 0.5 * rel_drop && gain_out < 1.5 * rel_drop)
            chosen = j;
    }
    return gk_vpl_kmeans(vpl, n, ms[chosen], &oo, labels, vals);
}

float gk_vpl_mean_spacing(const gk_vpl *vpl, int n)
{
    double a = 0.0;
    int valid = 0;
    for (int i = 0; i < n; i++)
        if (vpl_valid(&vpl[i]))
            a += vpl[i].area, valid++;
    return valid ? (float)sqrt(a / valid) : 0.0f;
}
