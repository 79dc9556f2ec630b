/* The fitted LTC tables (app/render/ltc_table.c, tools/ltc_fit.c) against numeric integration:
 * the GGX lobe of brdf_spec.md (F = 1: D V cos) integrated over a rectangular light by a 160^2
 * midpoint quadrature of the rectangle, against the LTC estimate A * E(Minv P) / pi, evaluated
 * exactly as shaders_gles/common/ltc.glsl does (bilinear table lookup, the view's tangent frame,
 * clip to the horizon, Lambert edge integral). Rectangles of 0.5 x 0.5 m at 1 m, centred on the
 * mirror direction and 25 / 50 degrees off it, over roughness x view angle. (The renderer's
 * representative point, which LTC replaces for rectangles, is compared in
 * tests/gpu/test_render_direct.c: 0.171 mean relative error there, LTC 0.130.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>

#include "core/vecmath.h"
#include "render/ltc_table.h"

#define PI 3.14159265358979

static double lobe(vec3 v, vec3 l, double roughness)
{
    if (l.z <= 0 || v.z <= 0)
        return 0;
    double a = fmax(roughness * roughness, 0.0025), a2 = a * a;
    vec3 h = v3_norm(v3_add(v, l));
    double d = h.z * h.z * (a2 - 1) + 1, D = a2 / (PI * d * d);
    double V = 0.5 / (l.z * sqrt(v.z * v.z * (1 - a2) + a2) + v.z * sqrt(l.z * l.z * (1 - a2) + a2));
    return D * V * l.z;
}

/* Bilinear lookup of cell values (as the shader: texel centres at (i + 0.5) / N). */
static void lookup(double roughness, double cos_v, double minv[4], double amp[2])
{
    double u = roughness * (GK_LTC_N - 1), w = sqrt(fmax(0.0, 1.0 - cos_v)) * (GK_LTC_N - 1);
    int a0 = (int)floor(u), t0 = (int)floor(w);
    a0 = a0 < 0 ? 0 : (a0 > GK_LTC_N - 2 ? GK_LTC_N - 2 : a0);
    t0 = t0 < 0 ? 0 : (t0 > GK_LTC_N - 2 ? GK_LTC_N - 2 : t0);
    double fa = fmin(fmax(u - a0, 0), 1), ft = fmin(fmax(w - t0, 0), 1);
    for (int k = 0; k < 4; k++)
        minv[k] = 0;
    amp[0] = amp[1] = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            double wgt = (i ? fa : 1 - fa) * (j ? ft : 1 - ft);
            int cell = (t0 + j) * GK_LTC_N + a0 + i;
            for (int k = 0; k < 4; k++)
                minv[k] += wgt * gk_ltc_minv[4 * cell + k];
            amp[0] += wgt * gk_ltc_amp[2 * cell];
            amp[1] += wgt * gk_ltc_amp[2 * cell + 1];
        }
}

/* Clamped-cosine integral (pi x form factor) of polygon q[0..n) (directions from the origin,
 * already transformed), clipped to z > 0. */
static double polygon_cosine(const vec3 *q, int n)
{
    vec3 c[12];
    int m = 0;
    for (int i = 0; i < n; i++) {
        vec3 a = q[i], b = q[(i + 1) % n];
        if (a.z > 0)
            c[m++] = a;
        if ((a.z > 0) != (b.z > 0))
            c[m++] = v3_add(a, v3_scale(v3_sub(b, a), a.z / (a.z - b.z)));
    }
    if (m < 3)
        return 0;
    double sum = 0;
    for (int i = 0; i < m; i++) {
        vec3 a = v3_norm(c[i]), b = v3_norm(c[(i + 1) % m]);
        vec3 x = v3_cross(a, b);
        double len = v3_len(x);
        if (len < 1e-12)
            continue;
        sum += atan2(len, v3_dot(a, b)) * x.z / len;
    }
    return 0.5 * fabs(sum);
}

static void ltc_vs_quadrature(void **state)
{
    (void)state;
    const double rs[] = {0.2, 0.4, 0.6, 0.8, 1.0}, thetas[] = {0, 30, 60, 80}, offs[] = {0, 25, 50};
    double worst = 0, sum = 0, sum_t[4] = {0}, n_t[4] = {0};
    int n = 0;
    for (int ri = 0; ri < 5; ri++)
        for (int ti = 0; ti < 4; ti++)
            for (int oi = 0; oi < 3; oi++) {
                double th = thetas[ti] * PI / 180, rough = rs[ri];
                vec3 v = v3((float)sin(th), 0, (float)cos(th));
                /* the light's centre direction: the mirror direction turned towards the normal by
                   offs degrees (kept above 10 degrees of elevation) */
                double el = fmin(PI / 2 - th + offs[oi] * PI / 180, 80 * PI / 180);
                vec3 dir = v3((float)(-cos(el)), 0, (float)sin(el));
                vec3 c = dir; /* 1 m away, facing the receiver */
                vec3 eu = v3_norm(v3_cross(dir, v3(0, 1, 0))), ev = v3(0, 1, 0);
                const double hw = 0.25;
                /* quadrature */
                const int q = 160;
                double want = 0;
                for (int j = 0; j < q; j++)
                    for (int i = 0; i < q; i++) {
                        double s = ((i + 0.5) / q - 0.5) * 2 * hw, t = ((j + 0.5) / q - 0.5) * 2 * hw;
                        vec3 pnt = v3_add(c, v3_add(v3_scale(eu, (float)s), v3_scale(ev, (float)t)));
                        double r2 = v3_dot(pnt, pnt);
                        vec3 l = v3_scale(pnt, (float)(1 / sqrt(r2)));
                        double cos_e = v3_dot(l, dir); /* the light emits towards the receiver, along -dir */
                        if (cos_e > 0)
                            want += lobe(v, l, rough) * cos_e / r2;
                    }
                want *= (2 * hw) * (2 * hw) / (q * q);
                if (want < 1e-4)
                    continue; /* nothing to shade */
                /* LTC: frame x = v projected (here world x), y, z = n */
                double minv[4], amp[2];
                lookup(rough, v.z, minv, amp);
                vec3 corners[4] = {v3_sub(v3_sub(c, v3_scale(eu, (float)hw)), v3_scale(ev, (float)hw)),
                                   v3_sub(v3_add(c, v3_scale(eu, (float)hw)), v3_scale(ev, (float)hw)),
                                   v3_add(v3_add(c, v3_scale(eu, (float)hw)), v3_scale(ev, (float)hw)),
                                   v3_add(v3_sub(c, v3_scale(eu, (float)hw)), v3_scale(ev, (float)hw))};
                vec3 tq[4];
                for (int k = 0; k < 4; k++) {
                    vec3 p = corners[k];
                    tq[k] = v3((float)(minv[0] * p.x + minv[1] * p.z), p.y, (float)(minv[2] * p.x + minv[3] * p.z));
                }
                double got = amp[0] * polygon_cosine(tq, 4) / PI;
                double rel = fabs(got - want) / want;
                worst = fmax(worst, rel);
                sum += rel;
                sum_t[ti] += rel;
                n_t[ti]++;
                n++;
                if (rel > 0.1)
                    printf("# roughness %.1f theta %2.0f offset %2.0f: quadrature %.5f, LTC %.5f (%.1f%%)\n", rough,
                           thetas[ti], offs[oi], want, got, 100 * rel);
            }
    printf("# LTC vs quadrature over %d configurations: mean relative error %.4f, worst %.4f; by view angle "
           "0/30/60/80 degrees: %.4f %.4f %.4f %.4f\n", n, sum / n, worst, sum_t[0] / n_t[0], sum_t[1] / n_t[1],
           sum_t[2] / n_t[2], sum_t[3] / n_t[3]);
    /* Measured (the committed table, 64^2 samples per cell fit): mean 0.069, worst 0.53 (roughness
       0.2, 80 degrees, 50 degrees off the mirror direction, where the lobe's integral is 1% of its
       peak); by view angle 0.009 / 0.012 / 0.070 / 0.186 at 0 / 30 / 60 / 80 degrees: the fit is
       weakest at grazing views, as in the paper. Bounds 1.3x the mean and just
       above the worst: a wrong frame, a transposed Minv or a missing amplitude is off by 50-100%
       everywhere. */
    assert_true(n > 40);
    assert_true(sum / n < 0.09);
    assert_true(worst < 0.6);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(ltc_vs_quadrature)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
