/* Direct irradiance at the surfels (rad_direct.h). */
#include "rad_direct.h"

#include <math.h>

#include "ref/lights.h"
#include "ref/sample.h"
#include "ref/trace.h"

static bool is_delta(enum gk_ref_light_kind k) { return k == GK_REF_POINT || k == GK_REF_SPOT || k == GK_REF_DIRECTIONAL; }

void rad_direct_irradiance(const gk_ref_scene *rs, const rad_tree *t, int samples, int first, int count, float *out)
{
    rad_direct_irradiance_except(rs, t, samples, -1, first, count, out);
}

void rad_direct_irradiance_except(const gk_ref_scene *rs, const rad_tree *t, int samples, int skip, int first,
                                  int count, float *out)
{
    for (int i = first; i < first + count; i++) {
        vec3 n = t->nrm[i], x = t->pos[i];
        /* off the surface as the tracer offsets its shadow rays' origins (1e-4 of the scene) */
        float eps = 1e-4f * (rs->radius + fmaxf(fabsf(x.x), fmaxf(fabsf(x.y), fabsf(x.z))));
        vec3 o = v3_add(x, v3_scale(n, eps));
        vec3 E = v3(0, 0, 0);
        gk_rng rng;
        gk_rng_seed(&rng, 0x7261646975ull, (uint64_t)i, 0, 0);
        for (int li = 0; li < rs->n_lights; li++) {
            const gk_ref_light *L = &rs->lights[li];
            if (L->kind == GK_REF_MESH || li == skip)
                continue; /* emissive surfaces: geometry, through the links */
            int k = is_delta(L->kind) ? 1 : samples;
            vec3 sum = v3(0, 0, 0);
            for (int s = 0; s < k; s++) {
                float u1 = gk_rng_float(&rng), u2 = gk_rng_float(&rng), u3 = gk_rng_float(&rng);
                gk_light_sample ls;
                if (!gk_light_sample_one(rs, li, o, u1, u2, u3, &ls))
                    continue;
                float c = v3_dot(n, ls.wi);
                if (c <= 0.0f)
                    continue;
                float tmax = isinf(ls.dist) ? INFINITY : ls.dist * (1.0f - 1e-4f);
                if (gk_scene_occluded(rs, o, ls.wi, tmax))
                    continue;
                sum = v3_add(sum, v3_scale(ls.li, c / ls.pdf));
            }
            E = v3_add(E, v3_scale(sum, 1.0f / (float)k));
        }
        out[3 * i] = E.x, out[3 * i + 1] = E.y, out[3 * i + 2] = E.z;
    }
}
