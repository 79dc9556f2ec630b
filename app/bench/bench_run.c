/* The bench's measuring half: renders each configuration on the mock platform, times it and
 * compares its linear HDR image with the scene's path-traced reference. */
#include "../sched/calibration.h"
#include "bench.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/log.h"
#include "../io/image_io.h"
#include "../metrics/metrics.h"
#include "gl/gl.h"
#include "../scene/scene.h"
#include "platform/platform.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Percentile by nearest rank on a copy (n is small). */
static double percentile(const double *v, int n, double p)
{
    if (n <= 0)
        return NAN;
    double *s = malloc(sizeof *s * (size_t)n);
    if (!s)
        return NAN;
    memcpy(s, v, sizeof *s * (size_t)n);
    qsort(s, (size_t)n, sizeof *s, cmp_double);
    int k = (int)ceil(p * n) - 1;
    double r = s[k < 0 ? 0 : (k >= n ? n - 1 : k)];
    free(s);
    return r;
}

static int pass_column(gk_bench_result *r, const char *name)
{
    for (int i = 0; i < r->n_passes; i++)
        if (strcmp(r->pass_names[i], name) == 0)
            return i;
    if (r->n_passes >= GK_BENCH_MAX_PASSES) {
        /* said once a name (it comes back every frame): a dropped column must not pass unnoticed */
        static char said[GK_PASS_PATH_LEN];
        if (strcmp(said, name) != 0)
            gk_log("bench: more than %d pass columns, %s's times left out", GK_BENCH_MAX_PASSES, name);
        snprintf(said, sizeof said, "%s", name);
        return -1;
    }
    snprintf(r->pass_names[r->n_passes], sizeof r->pass_names[0], "%s", name);
    return r->n_passes++;
}

static bool tty_progress(void) { return isatty(2); }

typedef struct bench_run {
    const gk_bench_opts *o;
    gk_bench_result *r;
    gk_platform *platform;
    gk_renderer *renderer;
    gk_scene *scene;
    gk_image reference;        /* SCENE.exr (all light paths); empty when the scene has none */
    gk_image reference_direct; /* SCENE-direct.exr: what method none computes */
    gk_image reference_1bounce; /* SCENE-1bounce.exr: direct + one diffuse bounce, what vct and vpl compute */
    unsigned char *caustic_mask; /* SCENE-caustics-mask.png at the bench's size, NULL where there is none */
    int width, height;
} bench_run;

/* Renders one configuration and appends its row. */
static int measure(bench_run *b, const char *method, const char *pins, gk_err *e)
{
    gk_bench_result *r = b->r;
    if (r->n_rows >= GK_BENCH_MAX_ROWS)
        return gk_fail(e, GK_EINPUT, "bench: more than %d configurations", GK_BENCH_MAX_ROWS);
    gk_budget budget;
    gk_budget_init(&budget);
    gk_renderer_declare_knobs(b->renderer, &budget);
    if (b->o->budget[0] && gk_budget_pin_list(&budget, b->o->budget, e) < 0)
        return -1;
    if (pins[0] && gk_budget_pin_list(&budget, pins, e) < 0)
        return -1;

    /* The kiosk keeps shadow maps of static scenes between frames; a sweep over shadow knobs must
       pay for them every frame to measure them, any other sweep (and the calibration's, which
       predicts the kiosk's frames) measures the kiosk's steady state. */
    bool each = strcmp(b->o->sweep, "each") == 0; /* the calibration measures the kiosk's steady state */
    gk_renderer_set_rerender_static_shadows(b->renderer, (!each && strstr(pins, "shadow") != NULL) || b->o->rebuild_gi);
    gk_renderer_set_rebuild_gi(b->renderer, b->o->rebuild_gi);
    gk_renderer_cut(b->renderer); /* no cross-fade from the previous configuration's GI */
    int frames = b->o->frames, total = b->o->warmup + frames;
    double *frame_ms = calloc((size_t)frames, sizeof *frame_ms);
    double *pass_ms = calloc((size_t)frames * GK_BENCH_MAX_PASSES, sizeof *pass_ms);
    if (!frame_ms || !pass_ms) {
        free(frame_ms);
        free(pass_ms);
        return gk_fail(e, GK_ERUNTIME, "bench: out of memory");
    }
    gk_bench_row *row = &r->rows[r->n_rows];
    memset(row, 0, sizeof *row);
    int rc = 0;
    for (int f = 0; f < total && rc == 0; f++) {
        gk_frame_params fp = {.time_s = 0.0, .method = method, .budget = &budget};
        gk_frame_report report;
        rc = gk_renderer_draw(b->renderer, &fp, gk_platform_framebuffer(b->platform), &report, e);
        if (rc == 0)
            rc = gk_platform_present(b->platform, e);
        /* Columns come from every frame, warm-up included, so a pass that ran only while warming
           up (vct's voxelize on a static scene) is a column of zeros, not a missing column. */
        for (int p = 0; rc == 0 && p < report.n; p++) {
            char path[GK_PASS_PATH_LEN];
            gk_frame_report_path(&report, p, path, sizeof path);
            pass_column(r, path);
        }
        if (rc == 0 && f >= b->o->warmup) {
            /* The renderer's frame report, as the kiosk and its scheduler read it: the frame is the
               sum of its top-level passes, a GI method's passes are columns "gi.NAME" nested in
               "gi" (a pass that did not run in a frame counts 0 there). */
            int k = f - b->o->warmup;
            frame_ms[k] = report.total_ms;
            for (int p = 0; p < report.n; p++) {
                char path[GK_PASS_PATH_LEN];
                gk_frame_report_path(&report, p, path, sizeof path);
                int col = pass_column(r, path);
                if (col >= 0)
                    pass_ms[(size_t)k * GK_BENCH_MAX_PASSES + (size_t)col] = report.pass[p].ms;
            }
        }
    }
    if (rc == 0) {
        snprintf(row->scene, sizeof row->scene, "%s", b->scene->name);
        snprintf(row->method, sizeof row->method, "%s", method);
        /* the levels as they ran: a knob a pass clamped (vct_res=256 past the storage-buffer
           limit runs at 128) is charted and written as what ran */
        const gk_budget *ran = gk_renderer_budget_ran(b->renderer);
        if (!ran || ran->n != budget.n)
            ran = &budget;
        for (int k = 0; k < budget.n; k++) {
            int col = gk_budget_find(&r->budget, budget.def[k]->name);
            if (col < 0)
                col = gk_budget_add(&r->budget, budget.def[k]);
            if (col >= 0)
                row->level[col] = ran->level[k];
        }
        row->frame_ms_median = percentile(frame_ms, frames, 0.5);
        row->frame_ms_p95 = percentile(frame_ms, frames, 0.95);
        double col_vals[64];
        for (int p = 0; p < r->n_passes; p++) {
            for (int k = 0; k < frames && k < 64; k++)
                col_vals[k] = pass_ms[(size_t)k * GK_BENCH_MAX_PASSES + (size_t)p];
            row->pass_ms[p] = percentile(col_vals, frames < 64 ? frames : 64, 0.5);
        }
        /* the useful fetches (the efficiency's numerator), of the last frame: a static scene's
           frames repeat the same work, so they go with the median times. What depends on the data (shadow
           lookups, vpl's gather) is counted in one more, untimed frame (an atomic add per pixel would weigh on the timed ones). */
        if (b->o->roofline_csv[0]) {
            gk_renderer_count_work(b->renderer, true);
            gk_frame_params fp = {.time_s = 0.0, .method = method, .budget = &budget};
            gk_frame_report report;
            rc = gk_renderer_draw(b->renderer, &fp, gk_platform_framebuffer(b->platform), &report, e);
            gk_renderer_count_work(b->renderer, false);
            row->n_work = gk_renderer_pass_work(b->renderer, method, row->work, GK_MAX_PASS_WORK);
        }
        row->rel_rmse = row->ssim = row->psnr = row->mean_ratio = row->test_mean = NAN;
        row->caustic_rel_rmse = row->caustic_mean_ratio = NAN;
        /* The image that is compared: the linear HDR capture, written where the user can look. */
        char exr[1024];
        snprintf(exr, sizeof exr, "%s/captures/%s-%s-%03d.exr", b->o->out_dir, b->scene->name, method, r->n_rows);
        rc = gk_renderer_capture(b->renderer, NULL, exr, e);
        /* Each method is judged on what it computes: none (direct light only) against the
           reference's direct component; the one-bounce GI methods (vct, vpl, ispm) against the
           one-bounce reference where the scene has one (summary C.1), else the full image;
           lightmap, whose photons bounce until Russian roulette ends them, and radiosity (4
           bounces by default; its bounce sweep converges on the full image) against the full
           image. The reference column says which. */
        bool none = strcmp(method, "none") == 0 && !b->o->one_ruler;
        bool direct = none && b->reference_direct.pixels;
        bool every_bounce = (strcmp(method, "lightmap") == 0 || strcmp(method, "radiosity") == 0) && !b->o->one_ruler;
        bool one_bounce = !none && !every_bounce && b->reference_1bounce.pixels;
        const gk_image *ref = direct ? &b->reference_direct : one_bounce ? &b->reference_1bounce : &b->reference;
        snprintf(row->reference, sizeof row->reference, "%s%s", ref->pixels ? b->scene->name : "",
                 direct ? "-direct" : one_bounce ? "-1bounce" : "");
        if (rc == 0 && ref->pixels) {
            gk_image test = {0};
            gk_metrics m;
            rc = gk_image_read(exr, &test, e);
            if (rc == 0)
                rc = gk_metrics_compute(ref, &test, 0.0, &m, e);
            if (rc == 0) {
                row->rel_rmse = m.rel_rmse;
                row->ssim = m.ssim;
                row->psnr = m.psnr;
                row->mean_ratio = m.mean_ratio;
                row->test_mean = m.test_mean;
            }
            /* Only where the caustic is: its shape and energy, against the row's ruler; `none`'s
               (the direct reference) has no caustic, so none is measured there against the scene's
               one ruler (SCENE-1bounce.exr where it exists, else SCENE.exr), what a caustic method
               adds to it. */
            const gk_image *caustic_ruler =
                !direct ? ref : b->reference_1bounce.pixels ? &b->reference_1bounce : &b->reference;
            if (rc == 0 && b->caustic_mask && caustic_ruler->pixels) {
                gk_metrics mm;
                rc = gk_metrics_compute_masked(caustic_ruler, &test, 0.0, b->caustic_mask, &mm, e);
                if (rc == 0) {
                    row->caustic_rel_rmse = mm.rel_rmse;
                    row->caustic_mean_ratio = mm.mean_ratio;
                }
            }
            gk_image_free(&test);
        }
        if (rc == 0)
            r->n_rows++;
    }
    free(frame_ms);
    free(pass_ms);
    return rc;
}

/* REFS/NAME+SUFFIX.exr into img; a missing or differently sized reference leaves img empty (the
   bench then measures time only) and says so, unless the reference is optional. */
static int load_reference(bench_run *b, const char *name, const char *suffix, bool optional, gk_image *img,
                          gk_err *e)
{
    char ref[1024];
    snprintf(ref, sizeof ref, "%s/%s%s.exr", b->o->refs_dir, name, suffix);
    memset(img, 0, sizeof *img);
    if (access(ref, R_OK) != 0) {
        if (!optional)
            gk_log("bench: no reference %s (make references): no error from it", ref);
        return 0;
    }
    if (gk_image_read(ref, img, e) < 0)
        return -1;
    if (img->width != b->width || img->height != b->height) {
        gk_log("bench: %s is %dx%d, the bench renders %dx%d: no error from it", ref, img->width, img->height,
               b->width, b->height);
        gk_image_free(img);
    }
    return 0;
}

/* REFS/NAME-caustics-mask.png (written by `gikiosk reference --caustic-mask`) as a mask at the
   bench's size; none, another size or an empty mask leave b->caustic_mask NULL (said in the log). */
static int load_caustic_mask(bench_run *b, const char *name, gk_err *e)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s-caustics-mask.png", b->o->refs_dir, name);
    b->caustic_mask = NULL;
    if (access(path, R_OK) != 0)
        return 0;
    gk_image img = {0};
    if (gk_image_read(path, &img, e) < 0)
        return -1;
    if (img.width != b->width || img.height != b->height)
        gk_log("bench: %s is %dx%d, the bench renders %dx%d: no caustic error", path, img.width, img.height,
               b->width, b->height);
    else
        b->caustic_mask = gk_mask_from_image(&img);
    if (b->caustic_mask && gk_mask_count(b->caustic_mask, img.width, img.height) == 0) {
        gk_log("bench: %s selects no pixel: no caustic error", path);
        free(b->caustic_mask);
        b->caustic_mask = NULL;
    }
    gk_image_free(&img);
    return 0;
}

static int bench_scene(bench_run *b, const char *name, gk_err *e)
{
    char path[1024];
    if (gk_scene_find(b->o->scenes_dir, name, path, sizeof path) < 0)
        return gk_fail(e, GK_EINPUT, "bench: no scene '%s' in %s", name, b->o->scenes_dir);
    b->scene = gk_scene_load(path, e);
    if (!b->scene)
        return -1;
    /* -1bounce is optional: only scenes made to measure one-bounce methods have it (tools/references.sh) */
    if (load_reference(b, name, "", false, &b->reference, e) < 0 ||
        load_reference(b, name, "-direct", false, &b->reference_direct, e) < 0 ||
        load_reference(b, name, "-1bounce", true, &b->reference_1bounce, e) < 0)
        return -1;
    if (load_caustic_mask(b, name, e) < 0)
        return -1;
    int rc = gk_renderer_set_scene(b->renderer, b->scene, e);
    const char *applies[16];
    int n_applies = rc == 0 ? gk_renderer_methods(b->renderer, applies, 16) : 0;

    /* The methods to run: the requested ones that apply, or every one that applies. */
    const char *run[16];
    int n_run = 0;
    for (int i = 0; i < n_applies; i++) {
        if (b->o->methods[0]) {
            char list[sizeof b->o->methods + 2];
            snprintf(list, sizeof list, ",%s,", b->o->methods);
            char needle[48];
            snprintf(needle, sizeof needle, ",%s,", applies[i]);
            if (!strstr(list, needle))
                continue;
        }
        run[n_run++] = applies[i];
    }
    if (rc == 0 && n_run == 0)
        gk_log("bench: none of the methods '%s' applies to %s", b->o->methods, name);

    gk_budget knobs;
    gk_budget_init(&knobs);
    if (rc == 0)
        gk_renderer_declare_knobs(b->renderer, &knobs);
    for (int mi = 0; rc == 0 && mi < n_run; mi++) {
        gk_bench_sweep sweeps[GK_MAX_KNOBS];
        int n_sweeps;
        bool each = strcmp(b->o->sweep, "each") == 0;
        if (each) {
            /* the default configuration first: the calibration's reference row for this method */
            rc = measure(b, run[mi], "", e);
            n_sweeps = gk_bench_each_knob_sweeps(&knobs, run[mi], sweeps, GK_MAX_KNOBS);
        } else if (b->o->sweep[0]) {
            rc = gk_bench_sweep_parse(b->o->sweep, &knobs, &sweeps[0], e);
            n_sweeps = 1;
        } else {
            n_sweeps = gk_bench_default_sweeps(&knobs, run[mi], sweeps, GK_MAX_KNOBS);
        }
        if (rc == 0 && n_sweeps == 0 && !each)
            rc = measure(b, run[mi], "", e);
        for (int s = 0; rc == 0 && s < n_sweeps; s++) {
            int count = gk_bench_sweep_count(&sweeps[s]);
            for (int c = 0; rc == 0 && c < count; c++) {
                char pins[512];
                gk_bench_sweep_pins(&sweeps[s], c, pins, sizeof pins);
                if (tty_progress())
                    fprintf(stderr, "\rbench: %s %s %-60s", name, run[mi], pins);
                rc = measure(b, run[mi], pins, e);
            }
        }
    }
    if (tty_progress())
        fputc('\n', stderr);
    gk_image_free(&b->reference);
    gk_image_free(&b->reference_direct);
    gk_image_free(&b->reference_1bounce);
    free(b->caustic_mask);
    b->caustic_mask = NULL;
    gk_scene_free(b->scene);
    b->scene = NULL;
    return rc;
}

/* mkdir -p */
int gk_bench_make_dir(const char *path, gk_err *e)
{
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *p = buf + 1; *p; p++) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(buf, 0755) < 0 && errno != EEXIST)
            return gk_fail(e, GK_ERUNTIME, "bench: cannot create %s: %s", buf, strerror(errno));
        *p = '/';
    }
    if (mkdir(buf, 0755) < 0 && errno != EEXIST)
        return gk_fail(e, GK_ERUNTIME, "bench: cannot create %s: %s", buf, strerror(errno));
    return 0;
}

int gk_bench_run(const gk_bench_opts *o, gk_bench_result **out, gk_err *e)
{
    *out = NULL;
    bench_run b = {.o = o, .width = o->width, .height = o->height};
    b.r = calloc(1, sizeof *b.r);
    if (!b.r)
        return gk_fail(e, GK_ERUNTIME, "bench: out of memory");
    gk_budget_init(&b.r->budget);

    const char *scenes = o->scenes[0] ? o->scenes : "cornell,shadow-planes";
    if (b.width <= 0 || b.height <= 0) {
        /* The size of the first scene's reference, so errors can be measured; else a small default. */
        char first[64], ref[1024];
        snprintf(first, sizeof first, "%.*s", (int)strcspn(scenes, ","), scenes);
        snprintf(ref, sizeof ref, "%s/%s.exr", o->refs_dir, first);
        gk_image img = {0};
        gk_err ignore = {0};
        if (gk_image_read(ref, &img, &ignore) == 0) {
            b.width = img.width;
            b.height = img.height;
        } else {
            b.width = 128;
            b.height = 128;
        }
        gk_image_free(&img);
    }
    char captures[1024];
    snprintf(captures, sizeof captures, "%s/captures", o->out_dir);
    if (gk_bench_make_dir(o->out_dir, e) < 0 || gk_bench_make_dir(captures, e) < 0) {
        free(b.r);
        return -1;
    }
    gk_platform_desc desc;
    gk_platform_desc_defaults(&desc);
    desc.kind = GK_PLATFORM_MOCK;
    desc.width = b.width;
    desc.height = b.height;
    b.platform = gk_platform_open(&desc, e);
    if (!b.platform) {
        free(b.r);
        return -1;
    }
    gk_render_opts ro = {.width = b.width, .height = b.height, .gles_version = o->gles_version,
                         .shader_dir = o->shader_dir, .gpu_timer_queries = false};
    b.renderer = gk_renderer_create(&ro, e);
    int rc = b.renderer ? 0 : -1;
    char gl_renderer[256] = "";
    if (rc == 0)
        snprintf(gl_renderer, sizeof gl_renderer, "%s", (const char *)glGetString(GL_RENDERER));
    char list[512];
    snprintf(list, sizeof list, "%s", scenes);
    char *save = NULL;
    for (char *name = strtok_r(list, ",", &save); rc == 0 && name; name = strtok_r(NULL, ",", &save))
        rc = bench_scene(&b, name, e);
    if (b.renderer)
        gk_renderer_destroy(b.renderer);
    gk_platform_close(b.platform);
    if (rc < 0) {
        free(b.r);
        return -1;
    }
    gk_bench_mark_pareto(b.r->rows, b.r->n_rows);
    b.r->frames = o->frames;
    /* the kiosk's choice, from the calibration it would load (missing: nothing marked) */
    gk_calibration cal;
    char cal_path[1024];
    gk_err ce = {0};
    gk_calibration_path(o->scenes_dir, gl_renderer, cal_path, sizeof cal_path);
    if (gk_calibration_load(cal_path, &cal, &ce) == 0) {
        gk_bench_mark_choice(b.r, &cal, o->target_ms, (double)o->target_width * o->target_height);
        b.r->choice_target_ms = o->target_ms;
        b.r->choice_width = o->target_width;
        b.r->choice_height = o->target_height;
        gk_calibration_free(&cal);
        gk_log("bench: the kiosk's choice at %.0f ms, %dx%d, marked from %s", o->target_ms, o->target_width,
               o->target_height, cal_path);
    } else {
        gk_log("bench: no kiosk choice marked: %s", ce.msg);
    }
    *out = b.r;
    return 0;
}
