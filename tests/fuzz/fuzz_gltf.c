/* libFuzzer target for the glTF loader (gk_scene_load_memory): any input must either load, or
 * fail with a message that starts with the file's name; no crash, leak, hang or undefined
 * behaviour (built with -fsanitize=fuzzer,address,undefined by the Makefile's fuzz rule). Loaded
 * from memory without a base directory, so the loader reads no file whatever the input says. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gk_log_set_quiet(1);
    gk_err e = {0};
    gk_scene *s = gk_scene_load_memory(data, size, "fuzz.gltf", NULL, &e);
    if (!s) {
        if (e.code == GK_OK || strncmp(e.msg, "fuzz.gltf: ", 11) != 0)
            abort(); /* a failure must say so, naming the file */
        return 0;
    }
    /* exercise what the renderers call on a loaded scene */
    gk_scene_evaluate(s, 1.25f);
    gk_scene_evaluate(s, 1e6f);
    mat4 view, proj;
    vec3 eye;
    gk_scene_camera(s, 1.5f, &view, &proj, &eye);
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].light >= 0) {
            vec3 p, d, u, v;
            gk_scene_light_frame(s, i, &p, &d, &u, &v);
        }
    const char *names[8];
    gk_scene_methods(s, names, 8);
    gk_scene_free(s);
    return 0;
}
