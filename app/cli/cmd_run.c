/* `gikiosk run` (DESIGN §3): command line + config -> playlist -> the kiosk loop. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/commands.h"
#include "scene/scene.h"
#include "cli/cli.h"
#include "kiosk/config.h"
#include "kiosk/kiosk.h"

static int cmp_names(const void *a, const void *b) { return strcmp((const char *)a, (const char *)b); }

/* Without [playlist] scenes: every NAME.gltf / NAME.glb in the scenes directory, sorted. */
static int list_scenes(const char *dir, gk_kiosk_config *c, gk_err *e)
{
    DIR *d = opendir(dir);
    if (!d)
        return gk_fail(e, GK_EINPUT, "%s: cannot open the scenes directory", dir);
    struct dirent *de;
    c->n_scenes = 0;
    while ((de = readdir(d)) && c->n_scenes < GK_MAX_PLAYLIST) {
        const char *dot = strrchr(de->d_name, '.');
        if (!dot || de->d_name[0] == '.' || (strcmp(dot, ".gltf") && strcmp(dot, ".glb")))
            continue;
        int len = (int)(dot - de->d_name);
        if (len >= GK_NAME_LEN)
            continue;
        char name[GK_NAME_LEN];
        snprintf(name, sizeof name, "%.*s", len, de->d_name);
        bool dup = false;
        for (int i = 0; i < c->n_scenes; i++)
            dup |= !strcmp(c->scenes[i], name);
        if (!dup)
            snprintf(c->scenes[c->n_scenes++], GK_NAME_LEN, "%s", name);
    }
    closedir(d);
    qsort(c->scenes, (size_t)c->n_scenes, GK_NAME_LEN, cmp_names);
    if (c->n_scenes == 0)
        return gk_fail(e, GK_ERUNTIME, "%s: no scenes (.gltf or .glb); `make scenes` builds them", dir);
    return 0;
}

static int run(int argc, char **argv, gk_err *e)
{
    gk_run_opts o;
    if (gk_run_parse_args(argc, argv, &o, e))
        return -1;
    if (o.help) {
        gk_run_usage(stdout);
        return 0;
    }
    gk_kiosk_config c;
    gk_kiosk_config_defaults(&c);
    const char *config = o.config_path;
    if (!config && access("config/kiosk.ini", R_OK) == 0)
        config = "config/kiosk.ini";
    if (config && gk_kiosk_config_load(&c, config, e))
        return -1;
    gk_run_opts_apply(&o, &c);
    if (o.scene) {
        /* Named on the command line: a missing scene is a usage error, not something to skip. */
        for (int i = 0; i < c.n_scenes; i++) {
            char path[1024];
            if (gk_scene_find(o.scenes_dir, c.scenes[i], path, sizeof path))
                return gk_fail(e, GK_EINPUT, "--scene: no scene '%s' in %s (.gltf or .glb)", c.scenes[i], o.scenes_dir);
        }
    } else if (c.n_scenes == 0 && list_scenes(o.scenes_dir, &c, e)) {
        return -1;
    }
    gk_kiosk_opts ko = {
        .size_set = o.size_set, .frames = o.frames, .seconds = o.seconds, .method = o.method,
        .script = o.script, .capture_dir = o.capture_dir, .capture_every = o.capture_every, .hdr = o.hdr, .capture_hud = o.capture_hud,
        .stats_path = o.stats_path, .gles = o.gles, .budget_pins = o.budget_pins,
        .shader_dir = o.shader_dir, .scenes_dir = o.scenes_dir,
    };
    return gk_kiosk_run(&ko, &c, e);
}

int gk_cmd_run(int argc, char **argv)
{
    gk_err e = {0};
    if (run(argc, argv, &e) == 0)
        return 0;
    fprintf(stderr, "gikiosk: %s\n", e.msg);
    return e.code == GK_EINPUT ? 2 : 1;
}
