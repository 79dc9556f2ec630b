/* Explicit link visibility by shadow rays (rad_vis.h). */
#include "rad_vis.h"

#include <math.h>
#include <stdbool.h>

#include "ref/trace.h"

/* the reference tracer's shadow-ray origin offset (1e-4 of the scene's scale, as rad_direct.c) */
static float ray_offset(const gk_ref_scene *rs, vec3 x)
{
    return 1e-4f * (rs->radius + fmaxf(fabsf(x.x), fmaxf(fabsf(x.y), fabsf(x.z))));
}

long rad_links_cull_occluded(rad_links *L, const rad_tree *t, const gk_ref_scene *rs)
{
    long culled = 0;
    for (int i = 0; i < L->n_leaves; i++) {
        vec3 x = t->pos[i], n = t->nrm[i];
        vec3 o = v3_add(x, v3_scale(n, ray_offset(rs, x)));
        for (uint32_t k = L->offset[i]; k < L->offset[i + 1]; k++) {
            if (!(L->weight[k] > 0.0f))
                continue;
            int j = (int)L->target[k];
            vec3 y = t->pos[j];
            /* the target's end is pulled back by the same offset, so its own surface does not count */
            vec3 d = v3_sub(y, o);
            float r = v3_len(d);
            float end = r - ray_offset(rs, y);
            /* Each end must stand in front of the other's surface by more than that offset: what lies
               within it is coplanar to the ray's precision (light-leak's wall top, in the ceiling's
               plane, had links of weight ~1e-8 to the lit ceiling through float rounding of the
               cosines, and its segments ran just outside the room, where nothing blocks them). */
            bool facing = v3_dot(n, v3_sub(y, x)) > ray_offset(rs, x) &&
                          v3_dot(t->nrm[j], v3_sub(x, y)) > ray_offset(rs, y);
            if (!facing || !(end > 0.0f) || gk_scene_occluded(rs, o, v3_scale(d, 1.0f / r), end)) {
                L->weight[k] = 0.0f;
                culled++;
            }
        }
    }
    return culled;
}
