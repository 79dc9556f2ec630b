/* `gikiosk run` argument parsing (see cli.h). */
#include "cli/cli.h"
#include "gi/gi_catalogue.h"
#include "scene/scene.h"

#include <stdio.h>
#include <string.h>

void gk_run_usage(FILE *f)
{
    fputs("usage: gikiosk run [options]\n"
          "Shows the GI showcase: a playlist of scenes, buttons, HUD, frame-time scheduler.\n"
          "\n"
          "  --config FILE          kiosk config (INI); default config/kiosk.ini when present\n"
          "  --platform P           auto | kms | mock (auto: KMS when a display is connected)\n"
          "  --size WxH             render size on mock; mode choice on KMS\n"
          "  --scene NAME[,NAME]    show these scenes instead of the config's playlist\n",
          f);
    char methods[256];
    gk_gi_method_names(methods, sizeof methods, " ");
    fprintf(f, "  --method NAME          force a GI method: %s\n", methods);
    fputs("  --frames N             stop after N frames\n"
          "  --seconds S            stop after S seconds (virtual seconds on mock)\n"
          "  --target-ms MS         frame-time target of the scheduler (config [frame] target_ms)\n"
          "  --script FILE          mock platform: button script (TIME_S BUTTON click|press|release|hold MS)\n"
          "  --capture DIR          write DIR/FFFFFF-SCENE-METHOD.png (the last frame of each scene visit)\n"
          "  --capture-every N      capture every Nth frame instead\n"
          "  --hdr                  captures also as linear .exr\n"
          "  --capture-hud          captures also with the HUD drawn, as shown: FFFFFF-SCENE-METHOD-hud.png\n"
          "  --stats FILE.csv       one row per frame: times per pass and budget levels\n"
          "  --gles 3.1|3.2         restrict the renderer to GLES 3.1 (portable path) or allow 3.2\n"
          "  --budget K=V[,K=V]     pin budget knobs (the scheduler leaves them alone)\n"
          "  --shader-dir DIR       read shaders from DIR instead of the embedded copies\n"
          "  --scenes-dir DIR       scene files (default config/scenes, else the installed share/gikiosk/scenes)\n"
          "  --help                 this text\n"
          "Exit codes: 0 success, 1 runtime failure, 2 bad usage or bad input.\n",
          f);
}

static int bad(gk_err *e, const char *opt, const char *val, const char *what)
{
    return gk_fail(e, GK_EINPUT, "%s: '%s' %s", opt, val, what);
}

int gk_run_parse_args(int argc, char **argv, gk_run_opts *o, gk_err *e)
{
    memset(o, 0, sizeof *o);
    o->scenes_dir = gk_scene_default_dir();
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
            o->help = true;
            continue;
        }
        if (!strcmp(arg, "--hdr")) {
            o->hdr = true;
            continue;
        }
        if (!strcmp(arg, "--capture-hud")) {
            o->capture_hud = true;
            continue;
        }
        if (strncmp(arg, "--", 2) != 0)
            return gk_fail(e, GK_EINPUT, "run: unexpected argument '%s' (see gikiosk run --help)", arg);
        char opt[64];
        const char *val;
        const char *eq = strchr(arg, '=');
        if (eq) {
            snprintf(opt, sizeof opt, "%.*s", (int)(eq - arg), arg);
            val = eq + 1;
        } else {
            snprintf(opt, sizeof opt, "%s", arg);
            val = NULL;
        }
        static const char *const with_value[] = {
            "--config", "--platform", "--size", "--scene", "--method", "--frames", "--seconds",
            "--target-ms", "--script", "--capture", "--capture-every", "--stats", "--gles",
            "--budget", "--shader-dir", "--scenes-dir", NULL,
        };
        bool known = false;
        for (int k = 0; with_value[k]; k++)
            known |= !strcmp(with_value[k], opt);
        if (!known)
            return gk_fail(e, GK_EINPUT, "run: unknown option '%s' (see gikiosk run --help)", opt);
        if (!val) {
            if (i + 1 >= argc)
                return gk_fail(e, GK_EINPUT, "%s: missing value", opt);
            val = argv[++i];
        }
        if (!*val)
            return gk_fail(e, GK_EINPUT, "%s: empty value", opt);
        long n;
        double d;
        if (!strcmp(opt, "--config"))
            o->config_path = val;
        else if (!strcmp(opt, "--platform")) {
            if (gk_parse_platform(val, &o->platform))
                return bad(e, opt, val, "is not auto, kms or mock");
            o->platform_set = true;
        } else if (!strcmp(opt, "--size")) {
            if (gk_parse_size(val, &o->width, &o->height))
                return bad(e, opt, val, "is not WxH");
            o->size_set = true;
        } else if (!strcmp(opt, "--scene"))
            o->scene = val;
        else if (!strcmp(opt, "--method")) {
            if (!gk_gi_is_method(val)) {
                char names[200], what[256];
                gk_gi_method_names(names, sizeof names, ", ");
                snprintf(what, sizeof what, "is not a method (%s)", names);
                return bad(e, opt, val, what);
            }
            o->method = val;
        } else if (!strcmp(opt, "--frames")) {
            if (gk_parse_int(val, &n) || n < 1)
                return bad(e, opt, val, "is not a positive integer");
            o->frames = n;
        } else if (!strcmp(opt, "--seconds")) {
            if (gk_parse_double(val, &d) || d <= 0)
                return bad(e, opt, val, "is not a positive number of seconds");
            o->seconds = d;
        } else if (!strcmp(opt, "--target-ms")) {
            if (gk_parse_double(val, &d) || d < 1 || d > 1000)
                return bad(e, opt, val, "is not a frame time in 1..1000 ms");
            o->target_ms = d;
            o->target_set = true;
        } else if (!strcmp(opt, "--script"))
            o->script = val;
        else if (!strcmp(opt, "--capture"))
            o->capture_dir = val;
        else if (!strcmp(opt, "--capture-every")) {
            if (gk_parse_int(val, &n) || n < 1)
                return bad(e, opt, val, "is not a positive integer");
            o->capture_every = n;
        } else if (!strcmp(opt, "--stats"))
            o->stats_path = val;
        else if (!strcmp(opt, "--gles")) {
            if (!strcmp(val, "3.1"))
                o->gles = 31;
            else if (!strcmp(val, "3.2"))
                o->gles = 32;
            else
                return bad(e, opt, val, "is not 3.1 or 3.2");
        } else if (!strcmp(opt, "--budget")) {
            /* Syntax only here; knob names and values are checked once the renderer declared them. */
            char buf[1024], *save = NULL;
            snprintf(buf, sizeof buf, "%s", val);
            for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
                char *q = strchr(tok, '=');
                if (!q || q == tok || !q[1])
                    return bad(e, opt, tok, "is not KNOB=VALUE");
            }
            o->budget_pins = val;
        } else if (!strcmp(opt, "--shader-dir"))
            o->shader_dir = val;
        else if (!strcmp(opt, "--scenes-dir"))
            o->scenes_dir = val;
    }
    if (o->frames && o->seconds > 0)
        return gk_fail(e, GK_EINPUT, "run: --frames and --seconds exclude each other (give one)");
    if (o->capture_every && !o->capture_dir)
        return gk_fail(e, GK_EINPUT, "--capture-every: needs --capture DIR");
    if (o->hdr && !o->capture_dir)
        return gk_fail(e, GK_EINPUT, "--hdr: needs --capture DIR");
    if (o->capture_hud && !o->capture_dir)
        return gk_fail(e, GK_EINPUT, "--capture-hud: needs --capture DIR");
    if (o->scene) {
        char buf[1024], *save = NULL;
        snprintf(buf, sizeof buf, "%s", o->scene);
        int count = 0;
        for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
            if (strlen(tok) >= GK_NAME_LEN || strchr(tok, '/'))
                return bad(e, "--scene", tok, "is not a scene name");
            count++;
        }
        if (count == 0 || count > GK_MAX_PLAYLIST)
            return bad(e, "--scene", o->scene, "is not a list of 1..32 scene names");
    }
    return 0;
}

void gk_run_opts_apply(const gk_run_opts *o, gk_kiosk_config *c)
{
    if (o->platform_set)
        c->platform = o->platform;
    if (o->size_set) {
        c->width = o->width;
        c->height = o->height;
        snprintf(c->mode, sizeof c->mode, "%dx%d", o->width, o->height);
    }
    if (o->target_set)
        c->target_ms = o->target_ms;
    if (o->scene) {
        char buf[1024], *save = NULL;
        snprintf(buf, sizeof buf, "%s", o->scene);
        c->n_scenes = 0;
        c->scenes_line = 0;
        for (char *tok = strtok_r(buf, ",", &save); tok && c->n_scenes < GK_MAX_PLAYLIST;
             tok = strtok_r(NULL, ",", &save))
            snprintf(c->scenes[c->n_scenes++], GK_NAME_LEN, "%s", tok);
    }
}
