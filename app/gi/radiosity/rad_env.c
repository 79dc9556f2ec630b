/* The environment through empty leaf bins (rad_env.h). */
#include "rad_env.h"

#include <math.h>
#include <string.h>

#include "scene/environment.h"

void rad_env_bin_radiance(const gk_environment *env, int n_face, int sub, float *out)
{
    int bins = 6 * n_face * n_face;
    memset(out, 0, sizeof *out * 3 * (size_t)bins);
    if (!env->present || !env->rgb || sub < 1)
        return;
    for (int k = 0; k < bins; k++) {
        double sum[3] = {0, 0, 0}, wsum = 0.0;
        for (int j = 0; j < sub; j++)
            for (int i = 0; i < sub; i++) {
                float s = ((float)i + 0.5f) / (float)sub, t = ((float)j + 0.5f) / (float)sub;
                vec3 d = rad_bin_direction(k, n_face, s, t);
                /* a cube face's texel element subtends 1 / (1 + u² + v²)^(3/2) per unit area:
                   the direction's weight, so the mean is over solid angle, not over the face */
                float u = 2.0f * ((float)(k % n_face) + s) / (float)n_face - 1.0f;
                float v = 2.0f * ((float)((k / n_face) % n_face) + t) / (float)n_face - 1.0f;
                float q = 1.0f + u * u + v * v;
                double w = 1.0 / ((double)q * sqrt((double)q));
                vec3 L = gk_env_radiance(env, d);
                sum[0] += w * L.x, sum[1] += w * L.y, sum[2] += w * L.z;
                wsum += w;
            }
        for (int c = 0; c < 3; c++)
            out[3 * k + c] = (float)(sum[c] / wsum);
    }
}

void rad_env_irradiance(const rad_tree *t, const rad_links *L, const float *bin_radiance, bool rest, float *out)
{
    int n = L->n_face, bins = 6 * n * n;
    for (int i = 0; i < t->n_leaves; i++) {
        vec3 nrm = t->nrm[i];
        double E[3] = {0, 0, 0}, open = 0.0;
        for (int k = 0; k < bins; k++) {
            if (!rad_leaf_bin_empty(L, i, k))
                continue;
            float c = v3_dot(nrm, rad_bin_direction(k, n, 0.5f, 0.5f));
            if (c <= 0.0f)
                continue;
            double w = (double)c * (double)rad_bin_solid_angle(k, n);
            open += w;
            for (int j = 0; j < 3; j++)
                E[j] += w * (double)bin_radiance[3 * k + j];
        }
        double scale = 1.0;
        if (rest && open > 0.0) {
            double linked = 0.0;
            for (uint32_t k = L->offset[i]; k < L->offset[i + 1]; k++)
                linked += L->weight[k];
            double left = M_PI - linked;
            scale = left <= 0.0 ? 0.0 : left < open ? left / open : 1.0;
        }
        for (int j = 0; j < 3; j++)
            out[3 * i + j] = (float)(E[j] * scale);
    }
}
