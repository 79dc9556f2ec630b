/* The kiosk's live error (see live_error.h). */
#include "live_error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "io/image_io.h"
#include "ref/render.h"

/* The HUD's note while an animated scene moves: how a visitor gets its truth. */
#define NOTE_MOVES "no truth: the scene moves (hold prev to pause)"

int gk_live_error_open(gk_live_error *le, const gk_kiosk_config *c, int fw, int fh, gk_err *e)
{
    memset(le, 0, sizeof *le);
    le->frame_w = fw;
    le->frame_h = fh;
    le->sub = gk_truth_size(fw, fh, c->truth_max_w, c->truth_max_h, &le->w, &le->h);
    le->workers = gk_truth_worker_count(c->truth_workers);
    le->error = NAN;
    le->error_noise = NAN;
    le->current_point = -1;
    le->scene_index = -1;
    if (!(le->down = malloc((size_t)le->w * (size_t)le->h * 3 * sizeof(float))))
        return gk_fail(e, GK_ERUNTIME, "truth: out of memory");
    if (!(le->truth = gk_truth_create(le->workers, e))) {
        free(le->down);
        le->down = NULL;
        return -1;
    }
    gk_truth_stats st;
    gk_truth_get_stats(le->truth, &st);
    gk_log("truth: %d worker%s at %s, %dx%d (a truth pixel per %dx%d frame pixels)", le->workers,
           le->workers == 1 ? "" : "s", st.low_priority ? "the lowest priority" : "normal priority (refused)", le->w,
           le->h, le->sub, le->sub);
    return 0;
}

void gk_live_error_close(gk_live_error *le)
{
    if (le->truth) {
        gk_truth_stats st;
        gk_truth_get_stats(le->truth, &st);
        gk_log("truth: %llu samples traced, %llu tiles left part-way by restarts; %llu samples finished after their "
               "view was stopped (%llu views stopped, %d workers)",
               (unsigned long long)st.samples, (unsigned long long)st.aborted_tiles,
               (unsigned long long)st.samples_after_stop, (unsigned long long)st.retired_views, st.workers);
    }
    gk_truth_destroy(le->truth);
    gk_truth_view_free(&le->view);
    free(le->down);
    memset(le, 0, sizeof *le);
}

/* A committed reference of this view and size: SCENES_DIR/../../tests/references/SCENE.exr. */
static bool use_committed(gk_live_error *le, const char *scene_name, const char *scenes_dir)
{
    if (le->sub != 1)
        return false;
    char path[1200];
    snprintf(path, sizeof path, "%s/../../tests/references/%s.exr", scenes_dir ? scenes_dir : ".", scene_name);
    gk_image ref = {0};
    gk_err e = {0};
    if (gk_image_read(path, &ref, &e) != 0)
        return false;
    bool fits = ref.width == le->w && ref.height == le->h && ref.channels >= 3;
    if (fits) {
        float *rgb = malloc((size_t)le->w * le->h * 3 * sizeof *rgb);
        fits = rgb != NULL;
        for (size_t p = 0; fits && p < (size_t)le->w * le->h; p++)
            for (int ch = 0; ch < 3; ch++)
                rgb[3 * p + ch] = ref.pixels[p * ref.channels + ch];
        char spp_s[32] = "", noise_s[32] = "";
        gk_image_read_attr(path, "gikiosk:spp", spp_s, sizeof spp_s, &e);
        gk_image_read_attr(path, "gikiosk:noise_floor", noise_s, sizeof noise_s, &e);
        if (fits) {
            gk_truth_use_fixed(le->truth, rgb, le->w, le->h, atol(spp_s), noise_s[0] ? atof(noise_s) : NAN);
            gk_log("truth: %s is the committed reference %s (%s spp)", scene_name, path, spp_s[0] ? spp_s : "?");
        }
        free(rgb);
    }
    gk_image_free(&ref);
    return fits;
}

/* Forgets the last measurement: the view it was taken on is gone. */
static void forget_error(gk_live_error *le)
{
    le->error = NAN;
    le->error_noise = NAN;
    le->error_spp = 0;
    le->next_measure_s = 0;
}

/* Flattens the scene as evaluated at anim_t and restarts the tracer on it; or says why not. */
static void trace_view(gk_live_error *le, double anim_t)
{
    gk_scene *s = le->scene;
    gk_scene_evaluate(s, (float)anim_t);
    mat4 view, proj;
    vec3 eye;
    gk_scene_camera(s, (float)le->frame_w / (float)le->frame_h, &view, &proj, &eye);
    gk_ref_scene rs;
    gk_err e = {0};
    if (gk_ref_scene_build(&rs, s, view, proj, eye, le->frame_w, le->frame_h, &e) != 0) {
        snprintf(le->note, sizeof le->note, "no truth: %.140s", e.msg);
        gk_log("truth: %s: %s", le->scene_name, e.msg);
        return;
    }
    uint64_t g = gk_truth_restart(le->truth, &rs, le->w, le->h, le->sub, 1);
    if (s->anim_duration > 0)
        gk_log("truth: %s restarted at animation time %.3f s (view %llu)", le->scene_name, anim_t,
               (unsigned long long)g);
    else
        gk_log("truth: %s restarted (view %llu)", le->scene_name, (unsigned long long)g);
}

void gk_live_error_scene(gk_live_error *le, gk_scene *s, int scene_index, const char *scene_name,
                         const char *scenes_dir)
{
    gk_truth_stop(le->truth); /* workers leave the last view at once */
    le->scene = s;
    snprintf(le->scene_name, sizeof le->scene_name, "%s", scene_name);
    le->scene_index = scene_index >= 0 && scene_index < GK_MAX_PLAYLIST ? scene_index : 0;
    le->current_point = -1;
    le->frozen = false;
    forget_error(le);
    le->note[0] = '\0';
    if (s->anim_duration > 0) {
        snprintf(le->note, sizeof le->note, "%s", NOTE_MOVES);
        gk_log("truth: %s is animated; no ground truth while it moves (prev held pauses it)", scene_name);
        return;
    }
    if (use_committed(le, scene_name, scenes_dir))
        return;
    trace_view(le, 0.0);
}

void gk_live_error_pause(gk_live_error *le, bool paused, double anim_t)
{
    if (!le->scene || le->scene->anim_duration <= 0 || (paused == le->frozen && (!paused || anim_t == le->frozen_t)))
        return; /* a still scene's truth never depends on the pause; nothing changed */
    gk_truth_stop(le->truth); /* resumed, or frozen at another time: the workers leave the old view */
    forget_error(le);
    le->frozen = paused;
    le->frozen_t = anim_t;
    if (!paused) {
        le->check_stop = true;
        snprintf(le->note, sizeof le->note, "%s", NOTE_MOVES);
        gk_log("truth: %s moves again; its ground truth stopped", le->scene_name);
        return;
    }
    le->note[0] = '\0';
    trace_view(le, anim_t);
}

double gk_live_error_measure(const float *rgba, int fw, int fh, int sub, const float *truth, int w, int h,
                             float *down)
{
    (void)fh;
    const float inv = 1.0f / (float)(sub * sub);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float acc[3] = {0, 0, 0};
            for (int sy = 0; sy < sub; sy++)
                for (int sx = 0; sx < sub; sx++) {
                    const float *p = rgba + 4 * ((size_t)(y * sub + sy) * (size_t)fw + (size_t)(x * sub + sx));
                    for (int c = 0; c < 3; c++)
                        acc[c] += p[c];
                }
            for (int c = 0; c < 3; c++)
                down[3 * ((size_t)y * w + x) + c] = acc[c] * inv;
        }
    return gk_ref_rel_rmse(down, truth, (size_t)w * (size_t)h * 3);
}

static gk_live_point *point_for(gk_live_error *le, const char *method, const char *levels)
{
    int si = le->scene_index < 0 ? 0 : le->scene_index;
    gk_live_point *pts = le->points[si];
    for (int i = 0; i < le->n_points[si]; i++)
        if (!strcmp(pts[i].method, method) && !strcmp(pts[i].levels, levels)) {
            le->current_point = i;
            return &pts[i];
        }
    int slot = le->n_points[si];
    if (slot == GK_LIVE_MAX_POINTS) {
        /* full: the point with the fewest frames gives way (the levels the scheduler only passed
           through while stepping down), so the configuration now shown always has its point */
        slot = 0;
        for (int i = 1; i < GK_LIVE_MAX_POINTS; i++)
            if (pts[i].frames < pts[slot].frames)
                slot = i;
    } else {
        le->n_points[si]++;
    }
    gk_live_point *p = &pts[slot];
    memset(p, 0, sizeof *p);
    snprintf(p->method, sizeof p->method, "%s", method);
    snprintf(p->levels, sizeof p->levels, "%s", levels);
    p->error = NAN;
    le->current_point = slot;
    return p;
}

void gk_live_error_method(gk_live_error *le)
{
    le->error = NAN;
    le->settle = true;
}

bool gk_live_error_frame(gk_live_error *le, gk_renderer *r, double now, const char *method, const char *levels,
                         double frame_ms, bool judged)
{
    if (le->check_stop) { /* the frame after a resume: have the workers left the stopped view? */
        le->check_stop = false;
        gk_log("truth: one frame after the stop the workers are %s",
               gk_truth_busy(le->truth) ? "still finishing their sample" : "idle");
    }
    gk_live_point *pt = point_for(le, method, levels);
    if (pt && judged) {
        pt->ms_sum += frame_ms;
        pt->frames++;
    }
    if (le->settle) {
        le->settle = false;
        le->next_measure_s = now + GK_LIVE_SETTLE_S;
    }
    if (!gk_truth_snapshot(le->truth, &le->view) || now < le->next_measure_s)
        return false;
    le->next_measure_s = now + GK_LIVE_ERROR_PERIOD_S;
    gk_image img = {0};
    gk_err e = {0};
    if (gk_renderer_read_linear(r, &img, &e) != 0) {
        gk_log("truth: reading the frame failed: %s", e.msg);
        return false;
    }
    le->error = gk_live_error_measure(img.pixels, img.width, img.height, le->sub, le->view.rgb, le->w, le->h, le->down);
    le->error_spp = le->view.spp;
    le->error_noise = le->view.noise;
    gk_image_free(&img);
    if (pt)
        pt->error = le->error;
    return true;
}
