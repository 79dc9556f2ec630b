/* The shipped scenes as the tests read them (scene_file.h). */
#include "scene_file.h"

#include <stdio.h>

gk_scene *gkt_load_scene(const char *name, gk_err *e)
{
    char path[256];
    snprintf(path, sizeof path, "config/scenes/%s.gltf", name);
    gk_scene *s = gk_scene_load(path, e);
    if (s)
        gk_scene_evaluate(s, 0.0f);
    return s;
}
