/* lgv's tracer replayed on the CPU (lgv_replay.h): shaders_gles/lgv/tracer.glsl and common.glsl line
 * by line in float, with u_itp_mode 0 (angle partition) and without LGV_SEEING_MAPS (the nearest map), as the
 * kiosk runs it. */
#include "lgv_replay.h"

#include <math.h>
#include <string.h>

#define LGV_FAR 1.0e30f

static vec3 face_w(int f)
{
    int a = f / 2;
    float s = f % 2 == 0 ? 1.0f : -1.0f;
    return a == 0 ? v3(s, 0, 0) : (a == 1 ? v3(0, s, 0) : v3(0, 0, s));
}
static vec3 face_u(int f) { return f / 2 == 0 ? v3(0, 0, 1) : v3(1, 0, 0); }
static vec3 face_v(int f) { return f / 2 == 1 ? v3(0, 0, 1) : v3(0, 1, 0); }

vec3 gkt_lgv_face_dir(int f, float u, float v)
{
    return v3_add(face_w(f), v3_add(v3_scale(face_u(f), u), v3_scale(face_v(f), v)));
}

static int face_of(vec3 d, float *u, float *v)
{
    float ax = fabsf(d.x), ay = fabsf(d.y), az = fabsf(d.z);
    int f;
    if (ax >= ay && ax >= az)
        f = d.x >= 0.0f ? 0 : 1;
    else if (ay >= az)
        f = d.y >= 0.0f ? 2 : 3;
    else
        f = d.z >= 0.0f ? 4 : 5;
    float w = v3_dot(d, face_w(f));
    *u = v3_dot(d, face_u(f)) / w;
    *v = v3_dot(d, face_v(f)) / w;
    return f;
}

static vec3 centre(const gkt_lgv_replay *R, int m) { return v3(R->centres[4 * m], R->centres[4 * m + 1], R->centres[4 * m + 2]); }

static int clampi(int x, int lo, int hi) { return x < lo ? lo : (x > hi ? hi : x); }
static float clampf(float x, float lo, float hi) { return fminf(fmaxf(x, lo), hi); }

/* lgv_dist: the texel of map `map` towards d at `level`, counted */
static float dist(gkt_lgv_replay *R, int map, vec3 d, int level)
{
    float u, v;
    int f = face_of(d, &u, &v), res0 = R->info.res, res = res0 >> level;
    res = res < 1 ? 1 : res;
    int tx = clampi((int)((u * 0.5f + 0.5f) * (float)res), 0, res - 1);
    int ty = clampi((int)((v * 0.5f + 0.5f) * (float)res), 0, res - 1);
    long at = 0;
    for (int l = 0; l < level; l++)
        at += (long)R->info.layers * (res0 >> l) * (res0 >> l);
    at += ((long)(map * 6 + f) * res + ty) * res + tx;
    R->fetches++;
    float out;
    memcpy(&out, &R->maps[at], sizeof out);
    return out;
}

static int nearest_map(const gkt_lgv_replay *R, vec3 x, int first, int count)
{
    int best = first;
    float bd = 1e30f;
    for (int m = first; m < first + count; m++) {
        vec3 c = v3_sub(centre(R, m), x);
        float d = v3_dot(c, c);
        if (d < bd)
            bd = d, best = m;
    }
    return best;
}

static float energy(vec3 p, vec3 t, vec3 r)
{
    vec3 pt = v3_sub(p, t);
    float len = v3_len(pt), along = v3_dot(pt, r);
    if (along <= 0.0f)
        return 1e30f;
    float d = fabsf(len - along), a = len + along;
    return d * d * a;
}

static vec3 fan(vec3 th, vec3 b, float phi) { return v3_add(v3_scale(th, cosf(phi)), v3_scale(b, sinf(phi))); }

static bool itp_angle(gkt_lgv_replay *R, int m, vec3 x, vec3 r, vec3 *itp)
{
    vec3 v = centre(R, m), t = v3_sub(x, v);
    float tl = v3_len(t);
    if (tl < 1e-6f) {
        *itp = v3_add(v, v3_scale(r, dist(R, m, r, 0)));
        return true;
    }
    vec3 th = v3_scale(t, 1.0f / tl);
    float c = clampf(v3_dot(th, r), -1.0f, 1.0f), theta = acosf(c);
    vec3 b = v3_sub(r, v3_scale(th, c));
    if (v3_len(b) < 1e-5f)
        b = fabsf(th.x) < 0.9f ? v3_cross(th, v3(1, 0, 0)) : v3_cross(th, v3(0, 1, 0));
    b = v3_norm(b);
    float lo = 0.0f, hi = theta;
    vec3 prev = v3(1e30f, 1e30f, 1e30f);
    bool found = false;
    for (int loop = 0; loop < R->info.loops; loop++) {
        int level = clampi(R->info.loops - 1 - loop, 0, R->info.levels - 1);
        float step = (hi - lo) / (float)R->info.q;
        vec3 w0 = fan(th, b, lo);
        float f0 = energy(v3_scale(w0, dist(R, m, w0, level)), t, r), best = 1e30f;
        int bi = -1;
        for (int i = 0; i < R->info.q; i++) {
            vec3 w1 = fan(th, b, lo + step * (float)(i + 1));
            float f1 = energy(v3_scale(w1, dist(R, m, w1, level)), t, r), g = f0 + f1;
            if (g < best)
                best = g, bi = i;
            f0 = f1;
        }
        if (bi < 0 || best >= 1e29f)
            break;
        lo = lo + step * (float)bi;
        hi = lo + step;
        vec3 q = fan(th, b, 0.5f * (lo + hi));
        *itp = v3_add(v, v3_scale(q, dist(R, m, q, 0)));
        found = true;
        if (v3_len(v3_sub(*itp, prev)) < R->info.itp_eps)
            break;
        prev = *itp;
    }
    return found;
}

static float err(gkt_lgv_replay *R, int m, vec3 x0, vec3 r, float d)
{
    vec3 p = v3_add(x0, v3_scale(r, d));
    float l = v3_len(p);
    return l - dist(R, m, v3_scale(p, 1.0f / fmaxf(l, 1e-12f)), 0);
}

static bool bounds_hit(gkt_lgv_replay *R, int m, vec3 p) { return R->bounds_hits && dist(R, m, p, 0) < 0.5f * LGV_FAR; }

static float refine(gkt_lgv_replay *R, int m, vec3 x0, vec3 r, float dl, float el, float dp, float ep)
{
    float d = dp;
    for (int k = 0; k < R->info.secant_steps; k++) {
        float den = ep - el;
        d = clampf(fabsf(den) > 1e-12f ? dl - el * (dp - dl) / den : 0.5f * (dl + dp), dl, dp);
        float e = err(R, m, x0, r, d);
        if ((e < 0.0f) == (el < 0.0f))
            dl = d, el = e;
        else
            dp = d, ep = e;
    }
    return d;
}

static float secant(gkt_lgv_replay *R, int m, vec3 x, vec3 r, float d0, float d_start, float d_max)
{
    vec3 x0 = v3_sub(x, centre(R, m));
    float dl = d_start, el = err(R, m, x0, r, dl);
    float dp = clampf(d0, 2.0f * d_start, fmaxf(d_max, 2.0f * d_start)), ep = err(R, m, x0, r, dp);
    if (ep < 0.0f) {
        bool hit = false;
        for (int k = 0; k < 16 && !hit; k++) {
            dl = dp, el = ep;
            if (dp >= d_max)
                return bounds_hit(R, m, v3_add(x0, v3_scale(r, d_max))) ? d_max : -1.0f;
            dp = fminf(dp * 1.5f + d_start, d_max);
            ep = err(R, m, x0, r, dp);
            hit = ep >= 0.0f;
        }
        if (!hit)
            return -1.0f;
    } else if (el >= 0.0f) {
        bool ok = false;
        float pe = el, pd = dl;
        for (int k = 1; k <= 8 && !ok; k++) {
            float dk = d_start + (dp - d_start) * (float)k / 8.0f, ek = err(R, m, x0, r, dk);
            if (pe < 0.0f && ek >= 0.0f)
                dl = pd, el = pe, dp = dk, ep = ek, ok = true;
            pd = dk, pe = ek;
        }
        if (!ok)
            return dp;
    }
    return refine(R, m, x0, r, dl, el, dp, ep);
}

static float signf(float x) { return (float)((x > 0.0f) - (x < 0.0f)); }

static float exit_distance(const gkt_lgv_replay *R, vec3 x, vec3 r)
{
    vec3 inv = v3(signf(r.x + 1e-24f) / (fabsf(r.x) + 1e-12f), signf(r.y + 1e-24f) / (fabsf(r.y) + 1e-12f),
                  signf(r.z + 1e-24f) / (fabsf(r.z) + 1e-12f));
    vec3 lo = R->info.bmin, hi = R->info.bmax;
    float tx = fmaxf((lo.x - x.x) * inv.x, (hi.x - x.x) * inv.x), ty = fmaxf((lo.y - x.y) * inv.y, (hi.y - x.y) * inv.y),
          tz = fmaxf((lo.z - x.z) * inv.z, (hi.z - x.z) * inv.z);
    return fmaxf(fminf(tx, fminf(ty, tz)), 0.0f);
}

float gkt_lgv_replay_trace(gkt_lgv_replay *R, vec3 x, vec3 r)
{
    r = v3_norm(r); /* the probe normalises its ray */
    int n = R->info.n_maps, m1 = nearest_map(R, x, 0, n);
    vec3 itp;
    bool ok = itp_angle(R, m1, x, r, &itp);
    float exit_d = exit_distance(R, x, r);
    float d0 = ok ? v3_dot(v3_sub(itp, x), r) : exit_d;
    if (!(d0 < exit_d))
        d0 = exit_d;
    int map = nearest_map(R, v3_add(x, v3_scale(r, d0)), 0, n);
    float start = 2.0f * v3_len(v3_sub(x, centre(R, map))) * 2.0f / (float)R->info.res + 1e-4f;
    float d = secant(R, map, x, r, d0, start, exit_d);
    if (d < 0.0f && map != m1) {
        float start1 = 2.0f * v3_len(v3_sub(x, centre(R, m1))) * 2.0f / (float)R->info.res + 1e-4f;
        d = secant(R, m1, x, r, 2.0f * start1, start1, exit_d);
    }
    return d;
}
