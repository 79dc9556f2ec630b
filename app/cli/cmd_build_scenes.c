/* `gikiosk build-scenes DIR` (and `make scenes`): writes every procedural scene into DIR, then
 * loads each one back with the loader, so a scene that does not validate is never committed. */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/commands.h"
#include "scene/build_geom.h"
#include "scene/scene.h"

static void usage(FILE *f)
{
    fputs("usage: gikiosk build-scenes DIR [NAME...]\n"
          "Writes the procedural scenes (all, or the NAMEs given) as DIR/NAME.gltf + .bin and checks that\n"
          "each loads. `make scenes` runs it on config/scenes.\n",
          f);
}

int gk_cmd_build_scenes(int argc, char **argv)
{
    if (argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        usage(stdout);
        return 0;
    }
    if (argc < 2 || argv[1][0] == '-') {
        usage(stderr);
        return 2;
    }
    const char *dir = argv[1];
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "gikiosk build-scenes: %s: not a directory\n", dir);
        return 2;
    }
    for (int a = 2; a < argc; a++) {
        int found = 0;
        for (int i = 0; i < gk_n_scene_builders; i++)
            found |= !strcmp(argv[a], gk_scene_builders[i].name);
        if (!found) {
            fprintf(stderr, "gikiosk build-scenes: unknown scene '%s'\n", argv[a]);
            return 2;
        }
    }
    for (int i = 0; i < gk_n_scene_builders; i++) {
        const char *name = gk_scene_builders[i].name;
        int wanted = argc == 2;
        for (int a = 2; a < argc; a++)
            wanted |= !strcmp(argv[a], name);
        if (!wanted)
            continue;
        gk_err e = {0};
        if (gk_scene_builders[i].build(dir, &e) != 0) {
            fprintf(stderr, "gikiosk build-scenes: %s\n", e.msg);
            return e.code ? e.code : 1;
        }
        char path[1024];
        snprintf(path, sizeof path, "%s/%s.gltf", dir, name);
        gk_scene *s = gk_scene_load(path, &e);
        if (!s) {
            fprintf(stderr, "gikiosk build-scenes: the scene just written does not load: %s\n", e.msg);
            return 1;
        }
        printf("wrote %s (%u triangles, %d lights)\n", path, s->n_triangles, s->n_lights);
        gk_scene_free(s);
    }
    return 0;
}
