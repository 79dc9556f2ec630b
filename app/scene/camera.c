/* The view camera both renderers use (gk_scene_camera): the first camera node of the file, or a
 * default camera framing the scene's bounds when the file has none. */
#include <math.h>

#include "scene.h"

/* glTF's infinite projection (zfar = 0): the far plane at infinity. */
static mat4 infinite_perspective(float yfov, float aspect, float znear)
{
    mat4 r = m4_perspective(yfov, aspect, znear, 2.0f * znear);
    r.m[10] = -1.0f;
    r.m[14] = -2.0f * znear;
    return r;
}

void gk_scene_camera(const gk_scene *s, float aspect, mat4 *view, mat4 *proj, vec3 *eye)
{
    if (s->camera_node >= 0) {
        const gk_node *n = &s->nodes[s->camera_node];
        const gk_camera *c = &s->cameras[n->camera];
        /* The viewport's aspect wins over the file's, so an image is never stretched. */
        float a = aspect > 0 ? aspect : (c->aspect > 0 ? c->aspect : 1.0f);
        /* Drop any scale of the node: a camera's view is a rigid transform. */
        mat4 w = n->world;
        for (int col = 0; col < 3; col++) {
            vec3 axis = v3_norm(v3(w.m[col * 4], w.m[col * 4 + 1], w.m[col * 4 + 2]));
            w.m[col * 4] = axis.x, w.m[col * 4 + 1] = axis.y, w.m[col * 4 + 2] = axis.z;
        }
        if (view)
            *view = m4_inverse(w);
        if (proj)
            *proj = c->zfar > 0 ? m4_perspective(c->yfov, a, c->znear, c->zfar) : infinite_perspective(c->yfov, a, c->znear);
        if (eye)
            *eye = v3(w.m[12], w.m[13], w.m[14]);
        return;
    }
    /* Default: 45° vertical field of view, looking at the bounds' centre from the front (+z), a
     * little above, far enough that the bounding sphere fits the view. */
    vec3 c = v3_scale(v3_add(s->bmin, s->bmax), 0.5f);
    float r = 0.5f * v3_len(v3_sub(s->bmax, s->bmin));
    if (!(r > 0))
        r = 1.0f;
    float yfov = 45.0f * (float)M_PI / 180.0f, a = aspect > 0 ? aspect : 1.0f;
    float fov = a < 1.0f ? 2.0f * atanf(tanf(yfov * 0.5f) * a) : yfov; /* the narrower of the two */
    float dist = r / sinf(fov * 0.5f);
    vec3 e = v3_add(c, v3_scale(v3_norm(v3(0.0f, 0.35f, 1.0f)), dist));
    if (view)
        *view = m4_look_at(e, c, v3(0, 1, 0));
    if (proj)
        *proj = m4_perspective(yfov, a, fmaxf(dist - r, dist * 0.01f) * 0.5f, dist + 2.0f * r);
    if (eye)
        *eye = e;
}
