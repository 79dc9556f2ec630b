/* Fits linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt 2016, "Real-Time
 * Polygonal-Light Shading with Linearly Transformed Cosines") to the specular lobe of
 * app/core/brdf_spec.md: GGX D times Smith height-correlated V times cos(theta_l), with F = 1.
 * Written so the tables need no download: `make ltc` runs it and rewrites app/render/ltc_table.c.
 *
 * Table: N x N cells over u = roughness (alpha = max(roughness^2, 0.0025), as the shaders clamp)
 * and v = sqrt(1 - cos(theta_v)) (finer near grazing, where the lobe changes fastest). Per cell:
 *   minv[4]: the inverse LTC matrix, normalised so its middle element is 1, in the frame
 *            x = view projected on the tangent plane, z = normal:
 *            Minv = [[m0, 0, m1], [0, 1, 0], [m2, 0, m3]] (rows);
 *   amp[2]:  A = integral of D V cos over the hemisphere (the lobe's albedo with F = 1) and
 *            B = integral of (1 - v.h)^5 D V cos, so a light's specular is
 *            L (F0 A + (F90 - F0) B) * (clamped-cosine integral over the polygon transformed by Minv).
 * Fit (as the paper's reference code): per cell, Nelder-Mead over (m11, m22, m13) of
 * M = [X Y Z] [[m11, 0, m13], [0, m22, 0], [0, 0, 1]], Z = the lobe's mean direction, minimising
 * sum |f - A D_ltc|^3 / (pdf_ltc + pdf_brdf) over stratified samples of both distributions;
 * rough to smooth, each cell starting from its neighbour's fit.
 *
 * usage: ltc_fit OUT.c        (about two and a half minutes on one core) */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N 64
#define NS 64 /* stratified samples per axis for the error and the moments */
#define PI 3.14159265358979323846

typedef struct { double x, y, z; } d3;
static d3 mk(double x, double y, double z) { return (d3){x, y, z}; }
static double dot(d3 a, d3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static d3 add(d3 a, d3 b) { return mk(a.x + b.x, a.y + b.y, a.z + b.z); }
static d3 scale(d3 a, double s) { return mk(a.x * s, a.y * s, a.z * s); }
static d3 norm(d3 a) { return scale(a, 1.0 / sqrt(dot(a, a))); }

typedef struct { double m[3][3]; } m3; /* rows */
static d3 mul(const m3 *a, d3 v)
{
    return mk(a->m[0][0] * v.x + a->m[0][1] * v.y + a->m[0][2] * v.z, a->m[1][0] * v.x + a->m[1][1] * v.y + a->m[1][2] * v.z,
              a->m[2][0] * v.x + a->m[2][1] * v.y + a->m[2][2] * v.z);
}
static m3 mmul(const m3 *a, const m3 *b)
{
    m3 r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] + a->m[i][2] * b->m[2][j];
    return r;
}
static double det(const m3 *a)
{
    const double (*m)[3] = a->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}
static m3 inverse(const m3 *a)
{
    const double (*m)[3] = a->m;
    double d = det(a);
    m3 r;
    r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / d;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / d;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / d;
    r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / d;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / d;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / d;
    r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / d;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / d;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / d;
    return r;
}

/* ---- the specular lobe of brdf_spec.md, F = 1, view v (v.y = 0), normal +z ---------------- */
static double ggx_d(double nh, double a2)
{
    double d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}
static double smith_v(double nl, double nv, double a2)
{
    return 0.5 / (nl * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nl * nl * (1.0 - a2) + a2));
}
static double g1(double nv, double a2) { return 2.0 * nv / (nv + sqrt(a2 + (1.0 - a2) * nv * nv)); }

/* f cos and the VNDF sampling pdf of l */
static double lobe(d3 v, d3 l, double alpha, double *pdf)
{
    *pdf = 0.0;
    if (l.z <= 0.0 || v.z <= 0.0)
        return 0.0;
    double a2 = alpha * alpha;
    d3 h = norm(add(v, l));
    double d = ggx_d(h.z, a2);
    *pdf = g1(v.z, a2) * d / (4.0 * v.z);
    return d * smith_v(l.z, v.z, a2) * l.z;
}

/* Heitz 2018 visible-normal sampling, reflected about the sampled normal */
static d3 lobe_sample(d3 v, double alpha, double u1, double u2)
{
    d3 vh = norm(mk(alpha * v.x, alpha * v.y, v.z));
    double lensq = vh.x * vh.x + vh.y * vh.y;
    d3 t1 = lensq > 0 ? scale(mk(-vh.y, vh.x, 0), 1.0 / sqrt(lensq)) : mk(1, 0, 0);
    d3 t2 = mk(vh.y * t1.z - vh.z * t1.y, vh.z * t1.x - vh.x * t1.z, vh.x * t1.y - vh.y * t1.x);
    double r = sqrt(u1), phi = 2.0 * PI * u2;
    double p1 = r * cos(phi), p2 = r * sin(phi), s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(fmax(0.0, 1.0 - p1 * p1)) + s * p2;
    d3 nh = add(add(scale(t1, p1), scale(t2, p2)), scale(vh, sqrt(fmax(0.0, 1.0 - p1 * p1 - p2 * p2))));
    d3 n = norm(mk(alpha * nh.x, alpha * nh.y, fmax(1e-7, nh.z)));
    return add(scale(n, 2.0 * dot(v, n)), scale(v, -1.0));
}

/* ---- the LTC -------------------------------------------------------------------------------- */
typedef struct ltc {
    double m11, m22, m13;
    d3 X, Y, Z;
    double amp; /* A: the lobe's albedo */
    m3 M, invM;
    double det_inv;
} ltc;

static void ltc_update(ltc *t)
{
    m3 basis = {{{t->X.x, t->Y.x, t->Z.x}, {t->X.y, t->Y.y, t->Z.y}, {t->X.z, t->Y.z, t->Z.z}}};
    m3 shape = {{{t->m11, 0, t->m13}, {0, t->m22, 0}, {0, 0, 1}}};
    t->M = mmul(&basis, &shape);
    t->invM = inverse(&t->M);
    t->det_inv = fabs(det(&t->invM));
}

static double ltc_eval(const ltc *t, d3 l)
{
    d3 lo = mul(&t->invM, l);
    double len = sqrt(dot(lo, lo));
    double c = lo.z / len;
    if (c <= 0.0)
        return 0.0;
    return t->amp * (c / PI) * t->det_inv / (len * len * len);
}

static d3 ltc_sample(const ltc *t, double u1, double u2)
{
    double r = sqrt(u1), phi = 2.0 * PI * u2;
    d3 lo = mk(r * cos(phi), r * sin(phi), sqrt(fmax(0.0, 1.0 - u1)));
    return norm(mul(&t->M, lo));
}

static double fit_error(const ltc *t, d3 v, double alpha)
{
    double err = 0.0;
    for (int j = 0; j < NS; j++)
        for (int i = 0; i < NS; i++) {
            double u1 = (i + 0.5) / NS, u2 = (j + 0.5) / NS;
            for (int k = 0; k < 2; k++) {
                d3 l = k == 0 ? ltc_sample(t, u1, u2) : lobe_sample(v, alpha, u1, u2);
                double pdf_b, f = lobe(v, l, alpha, &pdf_b);
                double e_ltc = ltc_eval(t, l), pdf_l = e_ltc / t->amp;
                double d = fabs(f - e_ltc);
                if (pdf_l + pdf_b > 0.0)
                    err += d * d * d / (pdf_l + pdf_b);
            }
        }
    return err / (NS * NS);
}

static double eval_params(ltc *t, const double x[3], bool isotropic, d3 v, double alpha)
{
    if (x[0] <= 1e-7 || x[1] <= 1e-7)
        return 1e30; /* keep the matrix non-degenerate */
    t->m11 = x[0];
    t->m22 = isotropic ? x[0] : x[1];
    t->m13 = isotropic ? 0.0 : x[2];
    ltc_update(t);
    return fit_error(t, v, alpha);
}

/* Nelder-Mead in 3 dimensions (reflection 1, expansion 2, contraction 0.5, shrink 0.5). */
static void nelder_mead(ltc *t, double start[3], double delta, bool isotropic, d3 v, double alpha)
{
    double s[4][3], f[4];
    for (int i = 0; i < 4; i++) {
        memcpy(s[i], start, sizeof s[i]);
        if (i > 0)
            s[i][i - 1] += delta;
        f[i] = eval_params(t, s[i], isotropic, v, alpha);
    }
    for (int iter = 0; iter < 100; iter++) {
        int lo = 0, hi = 0, nh = 0;
        for (int i = 1; i < 4; i++) {
            if (f[i] < f[lo]) lo = i;
            if (f[i] > f[hi]) hi = i;
        }
        nh = lo;
        for (int i = 0; i < 4; i++)
            if (i != hi && f[i] > f[nh]) nh = i;
        if (fabs(f[hi] - f[lo]) <= 1e-5 * fabs(f[lo]) + 1e-12)
            break;
        double c[3] = {0, 0, 0};
        for (int i = 0; i < 4; i++)
            if (i != hi)
                for (int k = 0; k < 3; k++) c[k] += s[i][k] / 3.0;
        double r[3], e[3], ct[3];
        for (int k = 0; k < 3; k++) r[k] = c[k] + (c[k] - s[hi][k]);
        double fr = eval_params(t, r, isotropic, v, alpha);
        if (fr < f[lo]) {
            for (int k = 0; k < 3; k++) e[k] = c[k] + 2.0 * (c[k] - s[hi][k]);
            double fe = eval_params(t, e, isotropic, v, alpha);
            if (fe < fr) { memcpy(s[hi], e, sizeof e); f[hi] = fe; }
            else { memcpy(s[hi], r, sizeof r); f[hi] = fr; }
        } else if (fr < f[nh]) {
            memcpy(s[hi], r, sizeof r);
            f[hi] = fr;
        } else {
            bool outside = fr < f[hi];
            for (int k = 0; k < 3; k++) ct[k] = c[k] + 0.5 * ((outside ? r[k] : s[hi][k]) - c[k]);
            double fc = eval_params(t, ct, isotropic, v, alpha);
            if (fc < (outside ? fr : f[hi])) {
                memcpy(s[hi], ct, sizeof ct);
                f[hi] = fc;
            } else {
                for (int i = 0; i < 4; i++)
                    if (i != lo) {
                        for (int k = 0; k < 3; k++) s[i][k] = s[lo][k] + 0.5 * (s[i][k] - s[lo][k]);
                        f[i] = eval_params(t, s[i], isotropic, v, alpha);
                    }
            }
        }
    }
    int best = 0;
    for (int i = 1; i < 4; i++)
        if (f[i] < f[best]) best = i;
    memcpy(start, s[best], sizeof s[best]);
    eval_params(t, start, isotropic, v, alpha);
}

/* The lobe's albedo A, its Schlick moment B and mean direction, by VNDF sampling (f / pdf). */
static void moments(d3 v, double alpha, double *A, double *B, d3 *mean)
{
    double a = 0, b = 0;
    d3 m = mk(0, 0, 0);
    for (int j = 0; j < NS; j++)
        for (int i = 0; i < NS; i++) {
            d3 l = lobe_sample(v, alpha, (i + 0.5) / NS, (j + 0.5) / NS);
            double pdf, f = lobe(v, l, alpha, &pdf);
            if (pdf <= 0.0)
                continue;
            double w = f / pdf;
            double vh = dot(v, norm(add(v, l)));
            a += w;
            b += w * pow(1.0 - vh, 5.0);
            m = add(m, scale(l, w));
        }
    *A = a / (NS * NS);
    *B = b / (NS * NS);
    m.y = 0.0;
    *mean = norm(m);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: ltc_fit OUT.c\n");
        return 2;
    }
    static float minv[N][N][4], amp[N][N][2]; /* [theta][roughness] */
    static double fits[N][N][3];
    for (int a = N - 1; a >= 0; a--) {
        double roughness = (double)a / (N - 1);
        double alpha = fmax(roughness * roughness, 0.0025);
        for (int t = 0; t < N; t++) {
            double x = (double)t / (N - 1), ct = fmax(1.0 - x * x, 0.0087); /* theta_v <= 89.5 deg */
            d3 v = mk(sqrt(1.0 - ct * ct), 0.0, ct);
            ltc l;
            memset(&l, 0, sizeof l);
            double A, B;
            d3 mean;
            moments(v, alpha, &A, &B, &mean);
            l.amp = A;
            double start[3];
            bool iso = t == 0;
            if (iso) {
                l.X = mk(1, 0, 0), l.Y = mk(0, 1, 0), l.Z = mk(0, 0, 1);
                if (a == N - 1)
                    start[0] = start[1] = 1.0, start[2] = 0.0;
                else
                    memcpy(start, fits[0][a + 1], sizeof start);
            } else {
                l.Z = mean;
                l.X = mk(mean.z, 0.0, -mean.x);
                l.Y = mk(0, 1, 0);
                memcpy(start, fits[t - 1][a], sizeof start);
            }
            nelder_mead(&l, start, 0.05, iso, v, alpha);
            memcpy(fits[t][a], start, sizeof start);
            m3 inv = l.invM;
            double s = inv.m[1][1];
            minv[t][a][0] = (float)(inv.m[0][0] / s);
            minv[t][a][1] = (float)(inv.m[0][2] / s);
            minv[t][a][2] = (float)(inv.m[2][0] / s);
            minv[t][a][3] = (float)(inv.m[2][2] / s);
            amp[t][a][0] = (float)A;
            amp[t][a][1] = (float)B;
        }
        fprintf(stderr, "\rltc_fit: roughness %.3f", roughness);
    }
    fprintf(stderr, "\n");
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s.part", argv[1]);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        perror(tmp);
        return 1;
    }
    fprintf(f, "/* Generated by tools/ltc_fit.c (`make ltc`): linearly transformed cosines fitted to the GGX\n"
               " * lobe of app/core/brdf_spec.md. Layout in ltc_table.h. Do not edit. */\n"
               "#include \"ltc_table.h\"\n\n"
               "const float gk_ltc_minv[GK_LTC_N * GK_LTC_N * 4] = {\n");
    for (int t = 0; t < N; t++)
        for (int a = 0; a < N; a++)
            fprintf(f, "    %.8g, %.8g, %.8g, %.8g,\n", minv[t][a][0], minv[t][a][1], minv[t][a][2], minv[t][a][3]);
    fprintf(f, "};\n\nconst float gk_ltc_amp[GK_LTC_N * GK_LTC_N * 2] = {\n");
    for (int t = 0; t < N; t++)
        for (int a = 0; a < N; a++)
            fprintf(f, "    %.8g, %.8g,\n", amp[t][a][0], amp[t][a][1]);
    fprintf(f, "};\n");
    if (fclose(f) != 0 || rename(tmp, argv[1]) != 0) {
        perror(argv[1]);
        return 1;
    }
    return 0;
}
