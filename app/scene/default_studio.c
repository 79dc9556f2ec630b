/* The default studio: lights for a scene whose file brings none. glTF assets usually ship without
 * lights (lighting is the viewer's business), and a kiosk that shows such a model black has shown
 * nothing. A file with no light node, no emissive surface and no environment gets the studio of
 * DESIGN §4: the built-in procedural environment (environment.h: a sun-less gradient sky over a
 * grey ground with three soft panels) plus a key light, a small disc sun placed around its view
 * camera. Both are added to the scene itself, so both renderers (the GLES one, which splits the
 * environment into area lights, env_split.h, and the reference tracer, which samples the map) light
 * it identically and `compare` means what it always means. The key's direction follows the view
 * camera so it always lights the side the visitor sees; the environment fills what faces away. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "environment.h"
#include "scene_internal.h"

/* Illuminance of the key light (lux). The absolute value only sets the exposure the renderer's
 * auto-exposure (measured key) then normalises; what matters is its ratio to the environment, whose
 * irradiance on an upward surface is about 4 lux at intensity 1 (sky 0.3..0.9 nits plus the
 * panels), so the key is the brighter of the two without flattening the environment's shading.
 * The key is a small disc sun (angular radius 0.03 rad, 1.7°) so its shadows are soft. */
#define STUDIO_KEY_LUX 3.0f
#define STUDIO_KEY_ANGULAR_RADIUS 0.03f
#define STUDIO_ENV_INTENSITY 1.0f

typedef struct studio_light {
    const char *name;
    float right, up, toward_camera; /* where the light comes from, in the camera's frame */
    float lux;
    float angular_radius;
} studio_light;

/* The rotation that turns -Z (a glTF light's direction) into dir (unit). */
static quat rotation_from_minus_z(vec3 dir)
{
    vec3 from = v3(0, 0, -1);
    float d = v3_dot(from, dir);
    if (d < -0.9999f) /* opposite: half a turn about any axis perpendicular to -Z */
        return (quat){0, 1, 0, 0};
    vec3 axis = v3_cross(from, dir);
    quat q = {axis.x, axis.y, axis.z, 1.0f + d};
    return q_normalize(q);
}

static bool has_light_or_emitter(const gk_scene *s)
{
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].light >= 0 && s->lights[s->nodes[i].light].intensity > 0)
            return true;
    return s->features.has_emissive || s->environment.present;
}

int gk_scene_add_default_studio(gk_scene *s, gk_err *e)
{
    if (has_light_or_emitter(s))
        return 0;
    static const studio_light kStudio[1] = {
        {"studio key", 0.6f, 1.0f, 0.6f, STUDIO_KEY_LUX, STUDIO_KEY_ANGULAR_RADIUS},
    };
    int n = 1;
    if (gk_env_make_studio(&s->environment, GK_ENV_STUDIO_HEIGHT, STUDIO_ENV_INTENSITY, e) != 0)
        return -1;
    gk_light *lights = realloc(s->lights, (size_t)(s->n_lights + n + 1) * sizeof *lights);
    if (!lights)
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory adding the default studio", s->path);
    s->lights = lights;
    gk_node *nodes = realloc(s->nodes, (size_t)(s->n_nodes + n + 1) * sizeof *nodes);
    if (!nodes)
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory adding the default studio", s->path);
    s->nodes = nodes;

    /* The camera's frame at t = 0 (the scene is evaluated already): rows of the view matrix. */
    mat4 view;
    gk_scene_camera(s, 16.0f / 9.0f, &view, NULL, NULL);
    vec3 right = v3(view.m[0], view.m[4], view.m[8]);
    vec3 up = v3(view.m[1], view.m[5], view.m[9]);
    vec3 back = v3(view.m[2], view.m[6], view.m[10]); /* from the target toward the camera */
    for (int k = 0; k < n; k++) {
        const studio_light *L = &kStudio[k];
        vec3 from = v3_norm(v3_add(v3_add(v3_scale(right, L->right), v3_scale(up, L->up)),
                                   v3_scale(back, L->toward_camera)));
        gk_light *l = &s->lights[s->n_lights];
        memset(l, 0, sizeof *l);
        snprintf(l->name, sizeof l->name, "%s", L->name);
        l->type = GK_LIGHT_DIRECTIONAL;
        l->shape = L->angular_radius > 0 ? GK_SHAPE_DISC : GK_SHAPE_POINT;
        l->radius = L->angular_radius;
        l->color[0] = l->color[1] = l->color[2] = 1.0f;
        l->intensity = L->lux;
        gk_node *node = &s->nodes[s->n_nodes];
        memset(node, 0, sizeof *node);
        snprintf(node->name, sizeof node->name, "%s", L->name);
        node->parent = -1;
        node->translation = v3(0, 0, 0);
        node->rotation = rotation_from_minus_z(v3_scale(from, -1.0f));
        node->scale = v3(1, 1, 1);
        node->light = s->n_lights;
        node->camera = -1;
        s->n_lights++;
        s->n_nodes++;
    }
    s->default_lighting = true;
    gk_log("scene %s has no lights: using the default studio (the built-in studio environment and a key light)", s->name);
    return 0;
}
