/* gikiosk bench: the command line of the bench (DESIGN §3). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/commands.h"
#include "base/log.h"
#include "bench/bench.h"
#include "bench/efficiency.h"
#include "bench/roofline.h"
#include "gl/gl.h"
#include "platform/platform.h"
#include "scene/scene.h"

static void usage(FILE *f)
{
    fputs("usage: gikiosk bench [--scenes LIST] [--methods LIST] [--size WxH] [--frames N] [--warmup N]\n"
          "                     [--sweep KNOB=V1,V2[;KNOB=V1,V2...] | --sweep each] [--scenes-dir DIR]\n"
          "                     [--references DIR] [--budget KNOB=VALUE[,KNOB=VALUE...]]\n"
          "                     [--gles 3.1|3.2] [--shader-dir DIR] [--rebuild-gi]\n"
          "                     [--target-ms MS] [--target-size WxH] [--one-ruler]\n"
          "                     [--roofline-csv ROOFLINE.csv] --out DIR\n"
          "       gikiosk bench --roofline [--shader-dir DIR] [--gles 3.1|3.2] --out DIR\n"
          "\n"
          "Renders every configuration offscreen (mock platform), measures the frame time (median and p95\n"
          "over --frames frames after --warmup untimed ones) and the error against the path-traced\n"
          "reference REFERENCES/SCENE.exr, and writes DIR/bench.csv and DIR/speed-accuracy-SCENE.png/.svg\n"
          "(error against frame time, one series per method, a bar from the median to the p95 frame time,\n"
          "the Pareto front, and the kiosk's automatic choice -- from config/calibration/CLASS.csv beside\n"
          "the scenes folder, at --target-ms (default 400) and --target-size (default 640x360) -- marked).\n"
          "Defaults: scenes cornell,shadow-planes; every method that applies; for method none the sweep\n"
          "shadow x shadow_map, for a GI method each of its knobs one at a time; size from the reference;\n"
          "5 frames after 2 warm-up frames. On a machine without a GPU the times are llvmpipe CPU times:\n"
          "read them as ratios between configurations measured in the same run. The scene clock stands\n"
          "at 0 in every frame: nothing animates and lightmap's IIM blend shows the gathered IIM at once.\n"
          "--one-ruler: every method of a scene is measured against one reference (SCENE-1bounce.exr\n"
          "where it exists, else SCENE.exr), so the methods compare on one axis (default: each against\n"
          "what it computes; none against SCENE-direct.exr).\n"
          "--budget: knob values pinned in every configuration (the sweep's own pins come after).\n"
          "--sweep each: the calibration's sweep (make calibrate): per method the default configuration,\n"
          "then every knob the scheduler may move (the renderer's and the method's) one at a time through\n"
          "its automatic levels.\n"
          "--rebuild-gi: the GI methods redo every frame what they otherwise keep between frames of a\n"
          "static scene (vct: voxelize, inject, mips) and shadow maps are re-rendered: the cost of a\n"
          "moving light or object, pass by pass.\n"
          "--roofline: instead of the sweep, this machine's fetch limits: a compute shader does a known\n"
          "number of fetches per invocation -- trilinear 3D (rgba8, rgba16f: the voxel volumes), 2D\n"
          "(rgba8, rgba16f trilinear; rgba32f nearest: a summed-area table), 3D imageLoad -- timed as\n"
          "the bench times frames; DIR/roofline.csv gets fetches per second per kind (median of 5).\n"
          "--roofline-csv FILE: with the limits --roofline wrote, also each pass's efficiency -- its useful\n"
          "fetches (counted or modelled beside the pass) per second of its median time, over the limit of\n"
          "its kind of fetch -- in DIR/efficiency.csv and per scene DIR/efficiency-SCENE.png/.svg (bars).\n",
          f);
}

static int parse_size(const char *s, int *w, int *h)
{
    char tail;
    return sscanf(s, "%dx%d%c", w, h, &tail) == 2 && *w > 0 && *h > 0 && *w <= 8192 && *h <= 8192 ? 0 : -1;
}

/* A value longer than its field is refused, not cut: a cut --budget once pinned
   "lightmap_workers=c" and failed on a knob value nobody wrote. */
static int copy_value(char *dst, size_t size, const char *v)
{
    return (size_t)snprintf(dst, size, "%s", v) < size ? 0 : 2;
}

static int parse_count(const char *s, int lo, int hi, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (*s == '\0' || *end || v < lo || v > hi)
        return -1;
    *out = (int)v;
    return 0;
}

/* --roofline: the fetch limits on a small offscreen context of the mock platform. */
static int bench_roofline(const gk_bench_opts *o)
{
    gk_err e = {0};
    char csv[1100];
    snprintf(csv, sizeof csv, "%s/roofline.csv", o->out_dir);
    gk_platform_desc desc;
    gk_platform_desc_defaults(&desc);
    desc.kind = GK_PLATFORM_MOCK;
    desc.width = 64;
    desc.height = 64;
    /* the folder first: a bad --out fails before seconds of measuring */
    gk_platform *p = gk_bench_make_dir(o->out_dir, &e) == 0 ? gk_platform_open(&desc, &e) : NULL;
    if (!p) {
        fprintf(stderr, "gikiosk bench: %s\n", e.msg);
        return e.code ? e.code : 1;
    }
    gk_program_cache *programs = gk_program_cache_create(o->shader_dir, o->gles_version);
    gk_roofline_opts ro;
    gk_roofline_opts_defaults(&ro);
    gk_roofline_result res[GK_ROOFLINE_MAX_CASES];
    int n = programs ? gk_roofline_measure(programs, &ro, res, GK_ROOFLINE_MAX_CASES, &e)
                     : gk_fail(&e, GK_ERUNTIME, "roofline: no program cache");
    int rc = n < 0 ? -1 : gk_roofline_write_csv(res, n, csv, &e);
    if (rc == 0)
        for (int i = 0; i < n; i++)
            gk_log("bench: roofline %-24s %8.1f M %s/s (%.0f in %.2f ms; counted %llu of %.0f)", res[i].name,
                   res[i].fetches_per_s * 1e-6, res[i].unit, res[i].fetches, res[i].median_ms,
                   (unsigned long long)res[i].counted, res[i].expected);
    if (programs)
        gk_program_cache_destroy(programs);
    gk_platform_close(p);
    if (rc < 0) {
        fprintf(stderr, "gikiosk bench: %s\n", e.msg);
        return e.code ? e.code : 1;
    }
    gk_log("bench: roofline, %s", csv);
    return 0;
}

int gk_cmd_bench(int argc, char **argv)
{
    gk_bench_opts o;
    bool roofline = false;
    memset(&o, 0, sizeof o);
    o.frames = 5;
    o.warmup = 2;
    o.gles_version = 32;
    o.target_ms = 400.0;   /* the kiosk's default target and `make run`'s size */
    o.target_width = 640;
    o.target_height = 360;
    snprintf(o.scenes_dir, sizeof o.scenes_dir, "%s", gk_scene_default_dir());
    snprintf(o.refs_dir, sizeof o.refs_dir, "tests/references");
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        if (!strcmp(a, "--rebuild-gi")) {
            o.rebuild_gi = true;
            continue;
        }
        if (!strcmp(a, "--roofline")) {
            roofline = true;
            continue;
        }
        if (!strcmp(a, "--one-ruler")) {
            o.one_ruler = true;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "gikiosk bench: %s needs a value\n", a);
            usage(stderr);
            return 2;
        }
        const char *v = argv[++i];
        int bad = 0;
        if (!strcmp(a, "--scenes"))
            bad = copy_value(o.scenes, sizeof o.scenes, v);
        else if (!strcmp(a, "--methods"))
            bad = copy_value(o.methods, sizeof o.methods, v);
        else if (!strcmp(a, "--budget"))
            bad = copy_value(o.budget, sizeof o.budget, v);
        else if (!strcmp(a, "--sweep"))
            bad = copy_value(o.sweep, sizeof o.sweep, v);
        else if (!strcmp(a, "--out"))
            bad = copy_value(o.out_dir, sizeof o.out_dir, v);
        else if (!strcmp(a, "--scenes-dir"))
            bad = copy_value(o.scenes_dir, sizeof o.scenes_dir, v);
        else if (!strcmp(a, "--references"))
            bad = copy_value(o.refs_dir, sizeof o.refs_dir, v);
        else if (!strcmp(a, "--roofline-csv"))
            bad = copy_value(o.roofline_csv, sizeof o.roofline_csv, v);
        else if (!strcmp(a, "--shader-dir"))
            o.shader_dir = v;
        else if (!strcmp(a, "--size"))
            bad = parse_size(v, &o.width, &o.height);
        else if (!strcmp(a, "--target-size"))
            bad = parse_size(v, &o.target_width, &o.target_height);
        else if (!strcmp(a, "--target-ms")) {
            char *end;
            o.target_ms = strtod(v, &end);
            bad = *v == '\0' || *end || !(o.target_ms >= 1.0 && o.target_ms <= 60000.0);
        } else if (!strcmp(a, "--frames"))
            bad = parse_count(v, 1, 10000, &o.frames);
        else if (!strcmp(a, "--warmup"))
            bad = parse_count(v, 0, 1000, &o.warmup);
        else if (!strcmp(a, "--gles")) {
            if (!strcmp(v, "3.1"))
                o.gles_version = 31;
            else if (!strcmp(v, "3.2"))
                o.gles_version = 32;
            else
                bad = 1;
        } else {
            fprintf(stderr, "gikiosk bench: unknown option '%s'\n", a);
            usage(stderr);
            return 2;
        }
        if (bad) {
            if (bad == 2)
                fprintf(stderr, "gikiosk bench: %s: value too long (%zu characters)\n", a, strlen(v));
            else
                fprintf(stderr, "gikiosk bench: %s: bad value '%s'\n", a, v);
            return 2;
        }
    }
    if (!o.out_dir[0]) {
        fprintf(stderr, "gikiosk bench: --out DIR is required\n");
        usage(stderr);
        return 2;
    }
    if (roofline)
        return bench_roofline(&o);
    gk_err e = {0};
    /* read before the sweep: a bad file is refused at once, not after minutes of rendering */
    gk_fetch_limit limits[GK_ROOFLINE_MAX_CASES];
    int n_limits = o.roofline_csv[0] ? gk_fetch_limits_read(o.roofline_csv, limits, GK_ROOFLINE_MAX_CASES, &e) : 0;
    if (n_limits < 0) {
        fprintf(stderr, "gikiosk bench: %s\n", e.msg);
        return e.code ? e.code : 1;
    }
    gk_bench_result *r = NULL;
    if (gk_bench_run(&o, &r, &e) < 0) {
        fprintf(stderr, "gikiosk bench: %s\n", e.msg);
        return e.code ? e.code : 1;
    }
    char csv[1100];
    snprintf(csv, sizeof csv, "%s/bench.csv", o.out_dir);
    int rc = gk_bench_write_csv(r, csv, &e);
    if (rc == 0)
        rc = gk_bench_write_charts(r, o.out_dir, &e);
    if (rc == 0 && o.roofline_csv[0])
        rc = gk_bench_write_efficiency(r, limits, n_limits, o.out_dir, &e);
    if (rc < 0)
        fprintf(stderr, "gikiosk bench: %s\n", e.msg);
    else
        gk_log("bench: %d configurations, %s", r->n_rows, csv);
    free(r);
    return rc < 0 ? (e.code ? e.code : 1) : 0;
}
