/* How each light sees the scene for its shadow map. */
#include "shadow.h"

#include <math.h>
#include <string.h>

/* Widest single perspective map (spot lights with narrower cones). */
#define MAX_HALF_FOV 1.0472f /* 60 degrees */

static float far_plane(const gk_scene *s, vec3 pos)
{
    float far = 0.0f;
    for (int i = 0; i < 8; i++) {
        vec3 c = v3(i & 1 ? s->bmax.x : s->bmin.x, i & 2 ? s->bmax.y : s->bmin.y, i & 4 ? s->bmax.z : s->bmin.z);
        far = fmaxf(far, v3_len(v3_sub(c, pos)));
    }
    return fmaxf(far * 1.05f + 0.1f, 1.0f);
}

/* A view matrix whose x, y, -z axes are u, v, dir, at pos. */
static mat4 frame_view(vec3 pos, vec3 u, vec3 v, vec3 dir)
{
    mat4 r = m4_identity();
    vec3 z = v3_scale(dir, -1.0f);
    r.m[0] = u.x; r.m[4] = u.y; r.m[8] = u.z;
    r.m[1] = v.x; r.m[5] = v.y; r.m[9] = v.z;
    r.m[2] = z.x; r.m[6] = z.y; r.m[10] = z.z;
    r.m[12] = -v3_dot(u, pos);
    r.m[13] = -v3_dot(v, pos);
    r.m[14] = -v3_dot(z, pos);
    return r;
}

bool gk_shadow_view_for_light(const gk_scene *s, int node, int map_size, gk_shadow_view *v)
{
    memset(v, 0, sizeof *v);
    const gk_light *l = &s->lights[s->nodes[node].light];
    vec3 pos, dir, u, w;
    gk_scene_light_frame(s, node, &pos, &dir, &u, &w);
    v->map_size = map_size;
    v->pos = pos;
    v->axis = dir;
    if (l->type == GK_LIGHT_DIRECTIONAL) {
        vec3 c = v3_scale(v3_add(s->bmin, s->bmax), 0.5f);
        float r = fmaxf(0.5f * v3_len(v3_sub(s->bmax, s->bmin)), 0.01f);
        v->ortho = true;
        v->n_faces = 1;
        v->pos = v3_sub(c, v3_scale(dir, r + 1.0f));
        v->znear = 0.5f;
        v->zfar = 2.0f * r + 1.5f;
        v->tan_half_fov = r;
        v->size_u = v->size_v = 2.0f * tanf(l->radius);
        v->skip_face = -1;
        v->basis[0] = u;
        v->basis[1] = w;
        v->basis[2] = dir;
        mat4 view = frame_view(v->pos, u, w, dir);
        v->viewproj[0] = m4_mul(m4_ortho(-r, r, -r, r, v->znear, v->zfar), view);
        return true;
    }
    /* One perspective map suffices for a spot cone up to 60 degrees; everything else (point,
       sphere, and the one-sided rect/disc emitters, which light a whole hemisphere) gets six
       cube faces in the light's frame (u, v, dir), so the main face (+dir, layer 4) has the
       light's X and Y along map u and v -- PCSS's rectangular kernel follows the rectangle. */
    bool cube = !(l->type == GK_LIGHT_SPOT && l->outer_cone + 0.05f <= MAX_HALF_FOV);
    float size = l->shape == GK_SHAPE_RECT ? fmaxf(l->size[0], l->size[1]) : 2.0f * l->radius;
    /* Near plane: blockers closer to the light than half its size are rare and would make the
       PCSS search region (proportional to 1 / Z_n) huge; 5 cm for small lights. */
    v->znear = fmaxf(0.05f, 0.5f * size);
    v->zfar = fmaxf(far_plane(s, pos), v->znear * 2.0f);
    if (l->shape == GK_SHAPE_RECT) {
        v->size_u = l->size[0];
        v->size_v = l->size[1];
    } else {
        v->size_u = v->size_v = 2.0f * l->radius;
    }
    v->basis[0] = u;
    v->basis[1] = w;
    v->basis[2] = dir;
    if (cube) {
        v->n_faces = 6;
        v->tan_half_fov = 1.0f;
        /* One-sided emitters light nothing behind them: their back face (layer 5) is not drawn. */
        v->skip_face = (l->shape == GK_SHAPE_RECT || l->shape == GK_SHAPE_DISC) ? 5 : -1;
        mat4 proj = m4_perspective(1.5707964f, 1.0f, v->znear, v->zfar);
        for (int f = 0; f < 6; f++) {
            int k = f / 2;
            vec3 a = v3_scale(v->basis[k], f % 2 ? -1.0f : 1.0f);
            vec3 y = k == 2 ? w : v->basis[(k + 1) % 3];
            vec3 x = v3_cross(y, v3_scale(a, -1.0f));
            v->viewproj[f] = m4_mul(proj, frame_view(pos, x, y, a));
        }
        return true;
    }
    float half = fminf(MAX_HALF_FOV, l->outer_cone + 0.05f);
    v->n_faces = 1;
    v->skip_face = -1;
    v->tan_half_fov = tanf(half);
    mat4 proj = m4_perspective(2.0f * half, 1.0f, v->znear, v->zfar);
    v->viewproj[0] = m4_mul(proj, frame_view(pos, u, w, dir));
    return true;
}
