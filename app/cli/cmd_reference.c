/* gikiosk reference: renders a path-traced reference image of a scene into an EXR (DESIGN §3).
 * Linear radiance, 32-bit float, with the command line, scene, spp, seed, path classes, render
 * time and measured noise floor in the EXR header (keys gikiosk:*). */
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/commands.h"
#include "io/image_io.h"
#include "metrics/metrics.h"
#include "ref/render.h"
#include "scene/scene.h"

static void usage(FILE *f)
{
    fputs("usage: gikiosk reference --scene NAME --out FILE.exr [options]\n"
          "\n"
          "Renders a path-traced reference (linear radiance, EXR) with the same camera, lights and\n"
          "materials as the real-time renderer.\n"
          "\n"
          "  --scene NAME        scene file stem in the scenes directory (e.g. cornell)\n"
          "  --out FILE.exr      output image\n"
          "  --size WxH          image size (default 160x120)\n"
          "  --spp N             samples per pixel (default 64)\n"
          "  --paths CLASS       all | direct | indirect | caustics (default all):\n"
          "                      direct = L D S* E + L S* E, caustics = L S+ D S* E,\n"
          "                      indirect = paths with two or more diffuse/glossy vertices\n"
          "  --terms LIST        with a scene medium, the image terms of seed 001 ch. 8, joined by\n"
          "                      '+': airlight (L V E: single scattering lit directly, volumetric\n"
          "                      shadows), vcaustics (L S+ V E: volume caustics), surfaces (paths\n"
          "                      without scattering, attenuated; --paths restricts these),\n"
          "                      multiple (the rest: multiple scattering); default all\n"
          "  --bounces N         keep paths with at most N diffuse/glossy vertices, the first\n"
          "                      surface seen included: 1 = direct light, 2 = direct + one\n"
          "                      bounce; combines with --paths (default unlimited)\n"
          "  --caustic-emit E    guided | light: caustic photons (L S+ D E) from point and spot\n"
          "                      lights aimed at the mirror/glass surfaces (default guided),\n"
          "                      or emitted as the light emits; both unbiased, guided wastes none\n"
          "  --caustic-grid N    guided: cells per axis of the target grid (default 1)\n"
          "  --caustic-specular N  keep caustic paths with at most N mirror/glass vertices,\n"
          "                      L S{1..N} D E, of the light tracer (point and spot lights;\n"
          "                      default unlimited): the ruler of a method with N specular\n"
          "                      bounces (ispm_bounces)\n"
          "  --caustic-mask FILE.png  also write the caustic mask of this image (pixels above 1/4\n"
          "                      of its peak luminance) and store the noise floor inside and\n"
          "                      outside it in the EXR (gikiosk:noise_floor_in_mask/_outside_mask)\n"
          "  --threads N         worker threads (default: online CPUs); the image is the same\n"
          "  --seed N            random seed (default 1)\n"
          "  --scenes-dir DIR    where scenes live (default config/scenes)\n"
          "  --time T            animation time in seconds (default 0)\n"
          "  --bench             print samples/s and rays/s on stdout\n"
          "  --compare-to REF    print the rel RMSE against REF.exr and both noise floors (JSON)\n",
          f);
}

static int parse_int(const char *opt, const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || *end || end == s || v < lo || v > hi) {
        fprintf(stderr, "gikiosk reference: %s: '%s' is not an integer in [%ld, %ld]\n", opt, s, lo, hi);
        return -1;
    }
    *out = v;
    return 0;
}

static void list_scenes(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "  (cannot open the scenes directory %s: %s)\n", dir, strerror(errno));
        return;
    }
    fprintf(stderr, "scenes in %s:", dir);
    struct dirent *de;
    int n = 0;
    while ((de = readdir(d))) {
        size_t l = strlen(de->d_name);
        if ((l > 5 && !strcmp(de->d_name + l - 5, ".gltf")) || (l > 4 && !strcmp(de->d_name + l - 4, ".glb"))) {
            fprintf(stderr, " %.*s", (int)(l - (de->d_name[l - 1] == 'f' ? 5 : 4)), de->d_name);
            n++;
        }
    }
    closedir(d);
    fprintf(stderr, n ? "\n" : " (none)\n");
}

typedef struct args {
    const char *scene, *out, *dir, *compare_to, *mask_out;
    int width, height;
    gk_ref_options o;
    float time;
    int bench;
} args;

static int parse_args(int argc, char **argv, args *a)
{
    memset(a, 0, sizeof *a);
    gk_ref_options_default(&a->o);
    a->width = 160;
    a->height = 120;
    a->dir = gk_scene_default_dir();
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    a->o.threads = ncpu > 0 ? (int)ncpu : 1;
    for (int i = 1; i < argc; i++) {
        const char *k = argv[i];
        if (!strcmp(k, "--help") || !strcmp(k, "-h")) {
            usage(stdout);
            return 1;
        }
        if (!strcmp(k, "--bench")) {
            a->bench = 1;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "gikiosk reference: %s needs a value\n", k);
            return -1;
        }
        const char *v = argv[++i];
        long n;
        if (!strcmp(k, "--scene"))
            a->scene = v;
        else if (!strcmp(k, "--out"))
            a->out = v;
        else if (!strcmp(k, "--scenes-dir"))
            a->dir = v;
        else if (!strcmp(k, "--compare-to"))
            a->compare_to = v;
        else if (!strcmp(k, "--caustic-mask"))
            a->mask_out = v;
        else if (!strcmp(k, "--caustic-emit")) {
            if (!strcmp(v, "guided"))
                a->o.caustic_emit = GK_CAUSTIC_EMIT_GUIDED;
            else if (!strcmp(v, "light"))
                a->o.caustic_emit = GK_CAUSTIC_EMIT_LIGHT;
            else {
                fprintf(stderr, "gikiosk reference: --caustic-emit: '%s' is not guided or light\n", v);
                return -1;
            }
        } else if (!strcmp(k, "--caustic-grid")) {
            if (parse_int(k, v, 1, 64, &n))
                return -1;
            a->o.caustic_grid = (int)n;
        } else if (!strcmp(k, "--caustic-specular")) {
            int b = gk_ref_bounces_parse(v);
            if (b == -2 || b == 0) {
                fprintf(stderr, "gikiosk reference: --caustic-specular: '%s' is not an integer in [1, 1000] or 'unlimited'\n", v);
                return -1;
            }
            a->o.caustic_specular = b;
        }
        else if (!strcmp(k, "--size")) {
            int w, h;
            char tail;
            if (sscanf(v, "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384) {
                fprintf(stderr, "gikiosk reference: --size: '%s' is not WxH (e.g. 160x120)\n", v);
                return -1;
            }
            a->width = w;
            a->height = h;
        } else if (!strcmp(k, "--spp")) {
            if (parse_int(k, v, 1, 1 << 24, &n))
                return -1;
            a->o.spp = (int)n;
        } else if (!strcmp(k, "--threads")) {
            if (parse_int(k, v, 1, 1024, &n))
                return -1;
            a->o.threads = (int)n;
        } else if (!strcmp(k, "--seed")) {
            if (parse_int(k, v, 0, LONG_MAX, &n))
                return -1;
            a->o.seed = (uint64_t)n;
        } else if (!strcmp(k, "--paths")) {
            int m = gk_ref_paths_parse(v);
            if (m < 0) {
                fprintf(stderr, "gikiosk reference: --paths: '%s' is not all, direct, indirect or caustics\n", v);
                return -1;
            }
            a->o.paths = (unsigned)m;
        } else if (!strcmp(k, "--terms")) {
            int m = gk_ref_terms_parse(v);
            if (m < 0) {
                fprintf(stderr, "gikiosk reference: --terms: '%s' is not all or a '+'-joined list of airlight, "
                                "vcaustics, surfaces, multiple\n", v);
                return -1;
            }
            a->o.terms = (unsigned)m;
        } else if (!strcmp(k, "--bounces")) {
            int b = gk_ref_bounces_parse(v);
            if (b == -2) {
                fprintf(stderr, "gikiosk reference: --bounces: '%s' is not an integer in [0, 1000] or 'unlimited'\n", v);
                return -1;
            }
            a->o.max_diffuse = b;
        } else if (!strcmp(k, "--time")) {
            char *end;
            a->time = strtof(v, &end);
            if (*end || end == v || !isfinite(a->time)) {
                fprintf(stderr, "gikiosk reference: --time: '%s' is not a number\n", v);
                return -1;
            }
        } else {
            fprintf(stderr, "gikiosk reference: unknown option '%s'\n", k);
            return -1;
        }
    }
    if (!a->scene || !a->out) {
        fprintf(stderr, "gikiosk reference: %s is required\n", !a->scene ? "--scene NAME" : "--out FILE.exr");
        return -1;
    }
    return 0;
}

static void join_command(int argc, char **argv, char *out, size_t len)
{
    size_t pos = (size_t)snprintf(out, len, "gikiosk");
    for (int i = 0; i < argc && pos < len; i++)
        pos += (size_t)snprintf(out + pos, len - pos, " %s", argv[i]);
}

static int compare_to(const char *path, const gk_ref_result *r, int w, int h, double seconds)
{
    gk_err e = {0};
    gk_image ref = {0};
    if (gk_image_read(path, &ref, &e)) {
        fprintf(stderr, "gikiosk reference: %s\n", e.msg);
        return e.code ? e.code : 1;
    }
    if (ref.width != w || ref.height != h || ref.channels < 3) {
        fprintf(stderr, "gikiosk reference: %s is %dx%d with %d channels; the render is %dx%d RGB\n", path,
                ref.width, ref.height, ref.channels, w, h);
        gk_image_free(&ref);
        return 2;
    }
    size_t n = (size_t)w * h * 3;
    float *rgb = malloc(n * sizeof(float));
    if (!rgb) {
        gk_image_free(&ref);
        return 1;
    }
    for (size_t p = 0; p < (size_t)w * h; p++)
        for (int c = 0; c < 3; c++)
            rgb[3 * p + c] = ref.pixels[p * ref.channels + c];
    double rel = gk_ref_rel_rmse(r->rgb, rgb, n);
    char floor_s[64] = "";
    gk_image_read_attr(path, "gikiosk:noise_floor", floor_s, sizeof floor_s, &e);
    char spp_s[64] = "";
    gk_image_read_attr(path, "gikiosk:spp", spp_s, sizeof spp_s, &e);
    printf("{\"rel_rmse\": %.6g, \"noise_floor\": %.6g, \"ref_noise_floor\": %s, \"ref_spp\": %s, \"seconds\": %.3f}\n",
           rel, r->noise_floor, floor_s[0] ? floor_s : "null", spp_s[0] ? spp_s : "null", seconds);
    free(rgb);
    gk_image_free(&ref);
    return 0;
}

int gk_cmd_reference(int argc, char **argv)
{
    args a;
    int rc = parse_args(argc, argv, &a);
    if (rc > 0)
        return 0;
    if (rc < 0) {
        usage(stderr);
        return 2;
    }
    char path[1024];
    if (gk_scene_find(a.dir, a.scene, path, sizeof path)) {
        fprintf(stderr, "gikiosk reference: unknown scene '%s' (no %s/%s.gltf or .glb)\n", a.scene, a.dir, a.scene);
        list_scenes(a.dir);
        return 2;
    }
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path, &e);
    if (!s) {
        fprintf(stderr, "gikiosk reference: %s\n", e.msg);
        return e.code ? e.code : 2;
    }
    gk_scene_evaluate(s, a.time);
    mat4 view, proj;
    vec3 eye;
    gk_scene_camera(s, (float)a.width / (float)a.height, &view, &proj, &eye);
    gk_ref_scene rs;
    if (gk_ref_scene_build(&rs, s, view, proj, eye, a.width, a.height, &e)) {
        fprintf(stderr, "gikiosk reference: %s\n", e.msg);
        gk_scene_free(s);
        return e.code ? e.code : 1;
    }
    a.o.progress = isatty(2);
    gk_ref_result r;
    if (gk_ref_render(&rs, &a.o, &r, &e)) {
        fprintf(stderr, "gikiosk reference: %s\n", e.msg);
        gk_ref_scene_free(&rs);
        gk_scene_free(s);
        return e.code ? e.code : 1;
    }
    if (a.bench)
        printf("reference %s %dx%d spp %d threads %d: %.3f s, %.0f samples/s, %.0f rays/s (%llu rays)\n", a.scene,
               a.width, a.height, a.o.spp, a.o.threads, r.seconds, (double)r.samples / r.seconds,
               (double)r.rays / r.seconds, (unsigned long long)r.rays);

    /* The caustic mask of this image and the noise floor inside and outside it. */
    unsigned char *mask = NULL;
    char in_s[32] = "", out_s[32] = "", mask_px_s[32] = "";
    if (a.mask_out) {
        gk_image view = {a.width, a.height, 3, r.rgb};
        float peak = 0.0f;
        mask = gk_mask_above_peak(&view, 0.25, &peak);
        if (!mask) {
            fprintf(stderr, "gikiosk reference: out of memory for the caustic mask\n");
            gk_ref_result_free(&r);
            gk_ref_scene_free(&rs);
            gk_scene_free(s);
            return 1;
        }
        snprintf(in_s, sizeof in_s, "%.6g", gk_ref_noise_floor_masked(&r, a.width, a.height, mask, true));
        snprintf(out_s, sizeof out_s, "%.6g", gk_ref_noise_floor_masked(&r, a.width, a.height, mask, false));
        snprintf(mask_px_s, sizeof mask_px_s, "%ld", gk_mask_count(mask, a.width, a.height));
        fprintf(stderr, "gikiosk reference: caustic mask %s: %s pixels above 1/4 of the peak %.6g; noise floor %s "
                        "inside, %s outside\n", a.mask_out, mask_px_s, peak, in_s, out_s);
    }
    char cmd[2048], spp_s[32], seed_s[32], floor_s[32], secs_s[32], size_s[32], tris_s[32], bounces_s[32];
    char grid_s[32], spec_s[32], terms_s[64];
    snprintf(grid_s, sizeof grid_s, "%d", a.o.caustic_grid);
    gk_ref_bounces_name(a.o.caustic_specular, spec_s, sizeof spec_s);
    join_command(argc, argv, cmd, sizeof cmd);
    snprintf(spp_s, sizeof spp_s, "%d", a.o.spp);
    snprintf(seed_s, sizeof seed_s, "%llu", (unsigned long long)a.o.seed);
    snprintf(floor_s, sizeof floor_s, "%.6g", r.noise_floor);
    snprintf(secs_s, sizeof secs_s, "%.3f", r.seconds);
    snprintf(size_s, sizeof size_s, "%dx%d", a.width, a.height);
    snprintf(tris_s, sizeof tris_s, "%u", rs.n_tris);
    gk_image_meta meta = {0};
    const char *kv[][2] = {
        {"gikiosk:command", cmd}, {"gikiosk:scene", a.scene}, {"gikiosk:spp", spp_s},
        {"gikiosk:seed", seed_s}, {"gikiosk:paths", gk_ref_paths_name(a.o.paths)},
        {"gikiosk:bounces", gk_ref_bounces_name(a.o.max_diffuse, bounces_s, sizeof bounces_s)},
        {"gikiosk:render_seconds", secs_s}, {"gikiosk:size", size_s}, {"gikiosk:triangles", tris_s},
        {"gikiosk:caustic_emit", a.o.caustic_emit == GK_CAUSTIC_EMIT_GUIDED ? "guided" : "light"},
        {"gikiosk:caustic_grid", grid_s}, {"gikiosk:caustic_specular", spec_s},
        {"gikiosk:terms", gk_ref_terms_name(a.o.terms, terms_s, sizeof terms_s)},
        {"gikiosk:noise_floor", floor_s},
    };
    int nkv = (int)(sizeof kv / sizeof kv[0]) - (isfinite(r.noise_floor) ? 0 : 1);
    for (int i = 0; i < nkv; i++) {
        meta.keys[meta.count] = kv[i][0];
        meta.values[meta.count++] = kv[i][1];
    }
    const char *mkv[][2] = {{"gikiosk:caustic_mask_pixels", mask_px_s}, {"gikiosk:noise_floor_in_mask", in_s},
                            {"gikiosk:noise_floor_outside_mask", out_s}};
    for (int i = 0; mask && i < 3; i++) {
        meta.keys[meta.count] = mkv[i][0];
        meta.values[meta.count++] = mkv[i][1];
    }
    gk_image img = {a.width, a.height, 3, r.rgb};
    rc = 0;
    long nonfinite = 0;
    for (long i = 0; i < 3L * a.width * a.height; i++)
        nonfinite += !isfinite(r.rgb[i]);
    if (nonfinite > 0) { /* never a reference with NaN/inf in it: it would poison every comparison */
        fprintf(stderr, "gikiosk reference: %ld NaN/inf values in the rendered image; %s not written\n", nonfinite,
                a.out);
        rc = 1;
    } else if (gk_image_write_float(a.out, &img, &meta, &e)) {
        fprintf(stderr, "gikiosk reference: %s\n", e.msg);
        rc = e.code ? e.code : 1;
    } else if (mask) {
        gk_image mimg = {0};
        if (gk_image_alloc(&mimg, a.width, a.height, 1)) {
            fprintf(stderr, "gikiosk reference: out of memory for the caustic mask\n");
            rc = 1;
        } else {
            for (size_t p = 0; p < (size_t)a.width * a.height; p++)
                mimg.pixels[p] = mask[p] ? 1.0f : 0.0f;
            if (gk_image_write(a.mask_out, &mimg, NULL, &e)) {
                fprintf(stderr, "gikiosk reference: %s\n", e.msg);
                rc = e.code ? e.code : 1;
            }
            gk_image_free(&mimg);
        }
    }
    if (rc == 0 && a.compare_to)
        rc = compare_to(a.compare_to, &r, a.width, a.height, r.seconds);
    free(mask);
    gk_ref_result_free(&r);
    gk_ref_scene_free(&rs);
    gk_scene_free(s);
    return rc;
}
