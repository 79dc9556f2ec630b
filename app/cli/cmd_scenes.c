/* `gikiosk scenes [--dir DIR]`: a table of the scenes with what they contain and the GI methods
 * that apply; `gikiosk scenes --check FILE` loads one file and prints its summary (exit 2 and the
 * loader's message if it is broken). */
#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/commands.h"
#include "gi/gi_catalogue.h"
#include "gi/radiosity/radiosity.h"
#include "render/render_gi.h"
#include "scene/scene.h"


static void usage(FILE *f)
{
    fputs("usage: gikiosk scenes [--dir DIR]\n"
          "       gikiosk scenes --check FILE\n"
          "Lists the scenes in DIR (default config/scenes, else the installed share/gikiosk/scenes): name,\n"
          "triangles, lights, features, the GI methods that apply, description. --check loads one scene\n"
          "file, validates it and prints its summary.\n",
          f);
}

/* The methods the kiosk can run on the scene (implemented, needed by the scene, and accepting it),
   then in brackets those the scene needs that are not implemented yet: "none,vct,vpl [+ispm,lgv]". */
static void methods_string(const gk_scene *s, char *out, size_t cap)
{
    const char *runs[16], *needs[16];
    int n_runs = gk_render_gi_methods(s, runs, 16), n_needs = gk_scene_methods(s, needs, 16), len = 0;
    out[0] = '\0';
    for (int i = 0; i < n_runs && (size_t)len < cap; i++)
        len += snprintf(out + len, cap - (size_t)len, "%s%s", i ? "," : "", runs[i]);
    int missing = 0;
    for (int i = 0; i < n_needs && (size_t)len < cap; i++) {
        bool runs_it = false;
        for (int k = 0; k < n_runs; k++)
            runs_it |= strcmp(runs[k], needs[i]) == 0;
        if (runs_it || gk_gi_catalogue_find(needs[i])->implemented)
            continue; /* running, or implemented but declining this scene (e.g. vpl without lights) */
        len += snprintf(out + len, cap - (size_t)len, "%s%s", missing++ ? "," : " [+", needs[i]);
    }
    if (missing && (size_t)len < cap)
        snprintf(out + len, cap - (size_t)len, "]");
}

/* Whether the kiosk runs method `name` on s. */
static bool runs_method(const gk_scene *s, const char *name)
{
    const char *runs[16];
    int n = gk_render_gi_methods(s, runs, 16);
    for (int i = 0; i < n; i++)
        if (strcmp(runs[i], name) == 0)
            return true;
    return false;
}

/* The radiosity method's refined vertex count at the default radiosity_tess ("-" where the method
   does not run on the scene, "refused" where the refinement is over its limit). */
static void radiosity_vertices(const gk_scene *s, char *out, size_t cap)
{
    if (!runs_method(s, "radiosity")) {
        snprintf(out, cap, "-");
        return;
    }
    gk_err e = {0};
    int n = gk_radiosity_refined_vertices(s, -1, &e);
    if (n < 0)
        snprintf(out, cap, "refused");
    else
        snprintf(out, cap, "%d", n);
}

static const char *light_kind(const gk_light *l)
{
    static const char *const type[] = {"point", "spot", "directional"};
    static const char *const shape[] = {"", " sphere", " disc", " rect"};
    static char buf[32];
    snprintf(buf, sizeof buf, "%s%s", type[l->type], shape[l->shape]);
    return buf;
}

/* What of glTF the file uses, what gikiosk converts, and what it ignores. */
static void print_gltf_use(const gk_scene_gltf_use *u)
{
    printf("gltf reads:  %s", u->extensions_read[0] ? u->extensions_read : "core glTF 2.0");
    const struct { int n; const char *what; } counts[] = {
        {u->embedded_images, "embedded images"},
        {u->sparse_accessors, "sparse accessors"},
        {u->quantized_accessors, "quantized accessors"},
        {u->strips_fans, "strips/fans converted to triangles"},
        {u->draco_primitives, "Draco-compressed primitives decoded"},
        {u->meshopt_views, "meshopt-compressed bufferViews decoded"},
        {u->samplers, "textures with a non-default sampler"},
        {u->texture_transforms, "texture transforms"},
        {u->second_uv_slots, "textures on TEXCOORD_1"},
        {u->alpha_masked, "alpha-masked materials"},
        {u->double_sided, "double-sided materials"},
        {u->alpha_blended, "alpha-blended materials (drawn over the opaque ones)"},
        {u->occlusion_textures, "occlusion textures (ambient and indirect light only; not the tracer's)"},
    };
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++)
        if (counts[i].n)
            printf("; %d %s", counts[i].n, counts[i].what);
    printf("\n");
    printf("gltf skips:  %s", u->extensions_ignored);
    bool any = u->extensions_ignored[0] != '\0';
    const struct { int n; const char *what; } skips[] = {
        {u->not_drawn, "points/lines primitives not drawn"},
        {u->orthographic_cameras, "orthographic cameras never used as the view"},
        {u->skins, "skins drawn unskinned"},
    };
    for (size_t i = 0; i < sizeof skips / sizeof skips[0]; i++)
        if (skips[i].n) {
            printf("%s%d %s", any ? "; " : "", skips[i].n, skips[i].what);
            any = true;
        }
    printf("%s\n", any ? "" : "-");
}

static int check(const char *path)
{
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path, &e);
    if (!s) {
        fprintf(stderr, "gikiosk scenes: %s\n", e.msg);
        return e.code ? e.code : 1;
    }
    char feat[128], meth[128];
    gk_scene_features_string(&s->features, feat, sizeof feat);
    methods_string(s, meth, sizeof meth);
    printf("scene:       %s (%s)\n", s->name, s->path);
    printf("triangles:   %u drawn, %u degenerate dropped, %d meshes\n", s->n_triangles, s->n_degenerate_dropped,
           s->n_meshes);
    printf("materials:   %d (with the default), textures: %d\n", s->n_materials, s->n_textures);
    const gk_environment *env = &s->environment;
    printf("lights:      %d%s\n", s->n_lights - env->n_env_lights,
           s->default_lighting ? " (the file has none: the default studio, its environment and a key light)" : "");
    for (int i = 0; i < s->n_lights; i++)
        if (!s->lights[i].env_part)
            printf("  %-16s %-18s intensity %g %s\n", s->lights[i].name, light_kind(&s->lights[i]), s->lights[i].intensity,
               s->lights[i].type == GK_LIGHT_DIRECTIONAL ? "lux" : "cd");
    if (env->present)
        printf("environment: %s, %dx%d lat-long, intensity %g; split into %d area lights (CSSM-shadowed in the "
               "rasterizer, knob env_lights)\n", env->uri[0] ? env->uri : "built-in studio", env->width, env->height,
               env->intensity, env->n_env_lights);
    else
        printf("environment: none\n");
    printf("camera:      %s\n", s->camera_node >= 0 ? s->nodes[s->camera_node].name : "default (framing the bounds)");
    printf("bounds:      (%.3f, %.3f, %.3f) .. (%.3f, %.3f, %.3f) m\n", s->bmin.x, s->bmin.y, s->bmin.z, s->bmax.x,
           s->bmax.y, s->bmax.z);
    printf("animation:   %s", s->anim_duration > 0 ? "" : "none\n");
    if (s->anim_duration > 0)
        printf("%d channels, %.3f s loop\n", s->n_channels, s->anim_duration);
    if (s->has_exposure)
        printf("exposure:    %+.2f EV\n", s->exposure_ev);
    printf("features:    %s\n", feat);
    print_gltf_use(&s->gltf);
    printf("methods:     %s\n", meth);
    if (runs_method(s, "radiosity")) {
        printf("radiosity:   refined at load to");
        for (int l = 0; l < gk_radiosity_tess_levels(); l++) {
            gk_err re = {0};
            int n = gk_radiosity_refined_vertices(s, l, &re);
            printf("%s", l ? " / " : " ");
            if (n < 0)
                printf("refused");
            else
                printf("%d", n);
        }
        printf(" vertices at radiosity_tess");
        for (int l = 0; l < gk_radiosity_tess_levels(); l++)
            printf("%s%g", l ? " / " : " ", (double)gk_radiosity_tess(l));
        printf(" (edge = the scene's diagonal / value)\n");
    }
    printf("description: %s\n", s->description[0] ? s->description : "-");
    gk_scene_free(s);
    return 0;
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static int list(const char *dir)
{
    DIR *dp = opendir(dir);
    if (!dp) {
        fprintf(stderr, "gikiosk scenes: %s: cannot open the scene folder\n", dir);
        return 2;
    }
    char *files[256];
    int n = 0;
    for (struct dirent *de; (de = readdir(dp)) && n < 256;) {
        size_t len = strlen(de->d_name);
        if ((len > 5 && !strcmp(de->d_name + len - 5, ".gltf")) || (len > 4 && !strcmp(de->d_name + len - 4, ".glb")))
            files[n++] = strdup(de->d_name);
    }
    closedir(dp);
    qsort(files, (size_t)n, sizeof files[0], cmp_str);
    int rc = 0;
    printf("%-22s %7s %6s  %-30s %-36s %9s %s\n", "NAME", "TRIS", "LIGHTS", "FEATURES", "METHODS", "RAD_VERTS",
           "DESCRIPTION");
    for (int i = 0; i < n; i++) {
        char path[PATH_MAX];
        if (snprintf(path, sizeof path, "%s/%s", dir, files[i]) >= (int)sizeof path) {
            fprintf(stderr, "gikiosk scenes: %s/%s: path too long\n", dir, files[i]);
            rc = 2;
            free(files[i]);
            continue;
        }
        gk_err e = {0};
        gk_scene *s = gk_scene_load(path, &e);
        if (!s) {
            fprintf(stderr, "gikiosk scenes: %s\n", e.msg);
            rc = e.code ? e.code : 1;
        } else {
            char feat[128], meth[128], desc[96];
            gk_scene_features_string(&s->features, feat, sizeof feat);
            methods_string(s, meth, sizeof meth);
            /* the description's first sentence keeps the table to one line a scene */
            const char *src = s->description[0] ? s->description : "-";
            size_t dl = strnlen(src, sizeof desc - 1);
            memcpy(desc, src, dl);
            desc[dl] = '\0';
            static const char *const cuts[] = {": ", ". ", " ("};
            for (int c = 0; c < 3; c++) {
                char *at = strstr(desc, cuts[c]);
                if (at)
                    *at = '\0';
            }
            if (strlen(desc) > 60)
                memcpy(desc + 57, "...", 4);
            char lights[24]; /* "+env": lit by an environment too (its split's lights not counted) */
            snprintf(lights, sizeof lights, "%d%s", s->n_lights - s->environment.n_env_lights,
                     s->environment.present ? "+env" : "");
            char rad[16];
            radiosity_vertices(s, rad, sizeof rad);
            printf("%-22s %7u %6s  %-30s %-36s %9s %s\n", s->name, s->n_triangles, lights, feat, meth, rad, desc);
            gk_scene_free(s);
        }
        free(files[i]);
    }
    /* one footer line: the tests read every line with five fields but this one as a scene */
    printf("\nMETHODS: what the kiosk runs on the scene; [+...]: methods the scene needs that are not implemented yet."
           " LIGHTS: +env: also lit by an environment map (the default studio's or the file's)."
           " RAD_VERTS: the vertices radiosity refines the scene into at the default radiosity_tess (-: not run there).\n");
    if (n == 0)
        fprintf(stderr, "gikiosk scenes: %s: no .gltf or .glb files\n", dir);
    return rc;
}

int gk_cmd_scenes(int argc, char **argv)
{
    const char *dir = NULL, *file = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(argv[i], "--dir") && i + 1 < argc) {
            dir = argv[++i];
        } else if (!strcmp(argv[i], "--check") && i + 1 < argc) {
            file = argv[++i];
        } else {
            fprintf(stderr, "gikiosk scenes: unknown or incomplete option '%s'\n", argv[i]);
            usage(stderr);
            return 2;
        }
    }
    if (file)
        return check(file);
    return list(dir ? dir : gk_scene_default_dir());
}
