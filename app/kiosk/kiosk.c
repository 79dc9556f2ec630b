/* The kiosk loop (see kiosk.h). Per frame: poll input (no wait), apply actions, attract mode,
 * draw with the scheduler's budgets, HUD, present, record times. Logging is one line per event
 * (scene, method, budget change, input), never per frame. On mock the virtual clock drives dwell
 * times and the button script, so runs are deterministic apart from the measured frame times. */
#include "kiosk.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/log.h"
#include "base/sd_notify.h"
#include "gi/gi_catalogue.h"
#include "../render/renderer.h"
#include "../sched/calibration.h"
#include "../sched/scheduler.h"
#include "hud.h"
#include "live_error.h"
#include "playlist.h"
#include "stats.h"
#include "visit_memory.h"

typedef struct kiosk {
    const gk_kiosk_opts *o;
    const gk_kiosk_config *c;
    gk_platform *plat;
    gk_renderer *r;
    gk_hud *hud;
    gk_live_error *live;                 /* the live ground truth ([truth] enabled), or NULL */
    int width, height;
    gk_playlist pl;
    gk_scene *scenes[GK_MAX_PLAYLIST];  /* loaded on first visit, kept */
    gk_budget budget;
    gk_sched sched;
    gk_sched_params sched_params;
    gk_recent recent;
    gk_summary summary;
    gk_stats_csv *csv;
    long frame;                          /* frames drawn */
    int sched_skip;                      /* frames the scheduler does not see: the first at a new level */
    gk_visit_memory *visits;             /* levels and cost model per (scene, method) for the run */
    gk_calibration calibration;          /* measured speed and error per scene x method */
    bool have_calibration;
    int visit_scene, visit_method;       /* the (scene, catalogue index) now shown; -1 before the first */
    bool have_frame;                     /* a frame of the current visit is drawn and not captured */
    double last_frame_ms;                /* newest measured frame (the HUD's number) */
    long last_frame;
    long last_logged_spp;                /* the truth's spp at the last error logged */
    char last_scene[GK_NAME_LEN], last_method[GK_METHOD_LEN];
    long floor_over;                     /* judged frames of this visit over the target at the floor */
    gk_notify notify;                    /* systemd readiness + watchdog (Type=notify) */
    char stop_after[16];                 /* the pass that ran last when a frame was abandoned */
    /* Test hook (GIKIOSK_TEST_SIGTERM_AT=FRAME:PASS, tests/e2e/stop_mid_frame.sh): raise SIGTERM
       as that frame's pass begins, the worst moment for a stop (all of that pass runs after it). */
    long test_sigterm_frame;
    char test_sigterm_pass[16];
} kiosk;

/* Judged frames over the target at the floor before the kiosk says (once a visit) that the scene
 * cannot meet it: more than a stray slow frame, few enough to say it within the visit. */
#define FLOOR_OVER_TO_SAY 5

static const char *button_name(enum gk_button b)
{
    static const char *const n[] = {"next", "prev", "mode", "info"};
    return b >= 0 && b < GK_BTN_COUNT ? n[b] : "?";
}

static const char *kind_name(enum gk_input_kind k)
{
    static const char *const n[] = {"press", "release", "click", "hold", "quit"};
    return k >= 0 && k <= GK_INPUT_QUIT ? n[k] : "?";
}

static int catalogue_index(const char *method)
{
    int n;
    const gk_gi_entry *all = gk_gi_catalogue(&n);
    const gk_gi_entry *e = gk_gi_catalogue_find(method);
    return e ? (int)(e - all) : -1;
}

/* Hands the scheduler this visit's calibration: the default row of (scene, method) and, per active
 * knob, the rows of its levels (app/sched/calibration.h). Logs the automatic levels the calibration
 * shows no more accurate than the level below them: the scheduler does not climb to them here. */
static void calibrate_visit(kiosk *k, const char *scene, const char *method, const bool *active)
{
    const gk_calib_row *def = k->have_calibration ? gk_calibration_find(&k->calibration, scene, method) : NULL;
    if (!def)
        return;
    gk_sched_calibrate(&k->sched, def->frame_ms, def->error);
    char skipped[512] = "";
    int knobs = 0;
    for (int i = 0; i < k->budget.n; i++) {
        const gk_knob_def *d = k->budget.def[i];
        if (!active[i] || d->fixed)
            continue;
        double ms[GK_MAX_KNOB_VALUES], err[GK_MAX_KNOB_VALUES], pass[GK_MAX_KNOB_VALUES];
        int found = 0;
        for (int l = 0; l < d->n_values; l++) {
            const gk_calib_row *r = l == d->default_level
                                        ? def
                                        : gk_calibration_find_level(&k->calibration, scene, method, d->name, d->values[l]);
            ms[l] = r ? r->frame_ms : NAN;
            err[l] = r ? r->error : NAN;
            pass[l] = r && d->scales_pass ? gk_calib_row_pass_ms(r, d->scales_pass) : NAN;
            found += r && r != def;
        }
        if (!found)
            continue; /* a table of the first format, or a knob newer than it: the priors */
        gk_sched_calibrate_knob(&k->sched, i, ms, err, pass, d->n_values);
        knobs++;
        int top = d->auto_max_level > 0 ? d->auto_max_level : d->n_values - 1;
        for (int l = 1; l <= top; l++)
            if (!isnan(err[l]) && !isnan(err[l - 1]) && err[l] >= err[l - 1] && strlen(skipped) < sizeof skipped - 64)
                snprintf(skipped + strlen(skipped), sizeof skipped - strlen(skipped), "%s%s=%s", skipped[0] ? "," : "",
                         d->name, d->values[l]);
    }
    if (knobs)
        gk_log("visit: %s with %s: %d knobs calibrated; levels not climbed to (measured no more accurate than the "
               "level below): %s", scene, method, knobs, skipped[0] ? skipped : "none");
}

/* Starts showing the playlist's current (scene, method): the visit before it is remembered, and
 * this one starts from its own remembered levels and cost model, or from the knobs' defaults on a
 * first visit -- never from the previous scene's levels. Knobs that affect frames now: the
 * renderer's own and those of the current method (a knob whose owner is a method name of the
 * catalogue belongs to that method). */
static void begin_visit(kiosk *k)
{
    char levels[512];
    if (k->visit_scene >= 0) {
        gk_visit_save(k->visits, k->visit_scene, k->visit_method, &k->budget, &k->sched);
        /* after the last frame's scheduler step: what the next visit resumes at */
        int n_cat;
        const char *left = k->visit_method >= 0 ? gk_gi_catalogue(&n_cat)[k->visit_method].name : "none";
        gk_budget_format_active(&k->budget, left, levels, sizeof levels);
        gk_log("visit: %s with %s leaves at %s", k->scenes[k->visit_scene] ? k->scenes[k->visit_scene]->name : "?",
               left, levels);
    }
    const char *method = gk_playlist_method(&k->pl);
    k->visit_scene = k->pl.current;
    k->visit_method = catalogue_index(method);
    if (gk_visit_restore(k->visits, k->visit_scene, k->visit_method, &k->budget, &k->sched)) {
        gk_budget_format_active(&k->budget, method, levels, sizeof levels);
        gk_log("visit: %s with %s resumes at %s", gk_playlist_scene(&k->pl), method, levels);
    } else {
        bool active[GK_MAX_KNOBS];
        for (int i = 0; i < k->budget.n; i++) {
            const char *owner = k->budget.def[i]->owner ? k->budget.def[i]->owner : "";
            active[i] = !gk_gi_is_method(owner) || !strcmp(owner, method);
        }
        gk_budget_reset_defaults(&k->budget);
        gk_sched_reset(&k->sched, &k->sched_params, &k->budget, active);
        calibrate_visit(k, gk_playlist_scene(&k->pl), method, active);
    }
    gk_recent_clear(&k->recent);
    if (k->live)
        gk_live_error_method(k->live); /* the last method's error is not this one's */
    k->floor_over = 0;
    k->sched_skip = 0; /* the scheduler's own warm-up (gk_sched_params.warmup) covers a new visit */
}

static void draw_hud(void *user, const gk_pass_ctx *ctx, unsigned fbo);

static int capture(kiosk *k, long frame, const char *scene, const char *method, gk_err *e)
{
    char png[4096], exr[4096];
    int n = snprintf(png, sizeof png, "%s/%06ld-%s-%s.png", k->o->capture_dir, frame, scene, method);
    snprintf(exr, sizeof exr, "%s/%06ld-%s-%s.exr", k->o->capture_dir, frame, scene, method);
    if (n < 0 || (size_t)n >= sizeof png) /* never a capture under a cut name */
        return gk_fail(e, GK_EINPUT, "--capture: the path '%s/...' is too long", k->o->capture_dir);
    if (gk_renderer_capture(k->r, png, k->o->hdr ? exr : NULL, e))
        return gk_fail_prefix(e, "capture: ");
    gk_log("capture: %s", png);
    if (k->o->capture_hud && k->hud) {
        char hud[4096];
        snprintf(hud, sizeof hud, "%.*s-hud.png", (int)strlen(png) - 4, png);
        if (gk_renderer_capture_overlay(k->r, hud, draw_hud, k, e))
            return gk_fail_prefix(e, "capture: ");
        gk_log("capture: %s", hud);
    }
    return 0;
}

/* Default capture mode: the last frame of each scene visit. */
static int capture_visit_end(kiosk *k, gk_err *e)
{
    if (!k->o->capture_dir || k->o->capture_every || !k->have_frame)
        return 0;
    k->have_frame = false;
    return capture(k, k->last_frame, k->last_scene, k->last_method, e);
}

/* Loads (first visit) and uploads the playlist's current scene; skips scenes that fail, with a
 * log line. Returns -1 when no scene is left. */
static int enter_scene(kiosk *k, gk_err *e)
{
    for (;;) {
        if (gk_playlist_usable(&k->pl) == 0)
            return gk_fail(e, GK_ERUNTIME, "no scene of the playlist could be loaded (see the messages above)");
        int i = k->pl.current;
        const char *name = k->pl.names[i];
        gk_err se = {0};
        if (!k->scenes[i]) {
            char path[1024];
            if (gk_scene_find(k->o->scenes_dir, name, path, sizeof path) != 0) {
                gk_fail(&se, GK_EINPUT, "%s: no scene '%s' (.gltf or .glb)", k->o->scenes_dir, name);
            } else {
                k->scenes[i] = gk_scene_load(path, &se);
            }
        }
        if (k->scenes[i] && gk_renderer_set_scene(k->r, k->scenes[i], &se) == 0)
            break;
        gk_log("scene %s skipped: %s", name, se.msg);
        gk_playlist_mark_failed(&k->pl, i);
        if (gk_playlist_usable(&k->pl) > 0)
            gk_playlist_step(&k->pl, +1, gk_platform_now(k->plat));
    }
    const char *applicable[GK_PL_MAX_METHODS];
    int n_app = gk_renderer_methods(k->r, applicable, GK_PL_MAX_METHODS);
    const char *name = gk_playlist_scene(&k->pl);
    const gk_scene *s = k->scenes[k->pl.current];
    const char *configured = gk_kiosk_config_methods(k->c, name);
    if (!configured && s->methods[0])
        configured = s->methods;
    char methods[GK_PL_MAX_METHODS][GK_METHOD_LEN], note[512];
    int def;
    int n = gk_methods_for_scene(applicable, n_app, configured, k->o->method, methods, &def, note, sizeof note);
    if (note[0])
        gk_log("scene %s: %s", name, note);
    if (!k->o->method && k->have_calibration) {
        /* Attract mode chooses from measurement: the lowest calibrated error that fits the target,
           never a method worse than none (the mode button still forces any method). */
        const char *names[GK_PL_MAX_METHODS];
        for (int m = 0; m < n; m++)
            names[m] = methods[m];
        char why[512];
        int pick = gk_calibration_choose(&k->calibration, name, names, n, k->c->target_ms,
                                         (double)k->width * k->height, why, sizeof why);
        if (pick >= 0) {
            def = pick;
            gk_log("scene %s: automatic choice %s", name, why);
        }
    }
    gk_playlist_set_methods(&k->pl, methods, n, def);
    char list[256] = "";
    for (int m = 0; m < n; m++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", m ? "," : "", methods[m]);
    gk_log("scene %s (method %s; methods %s)", name, gk_playlist_method(&k->pl), list);
    if (k->live)
        gk_live_error_scene(k->live, k->scenes[k->pl.current], k->pl.current, name, k->o->scenes_dir);
    begin_visit(k);
    return 0;
}

static int setup_budget(kiosk *k, gk_err *e)
{
    gk_budget_init(&k->budget);
    gk_renderer_declare_knobs(k->r, &k->budget);
    if (gk_kiosk_config_apply_budgets(k->c, &k->budget, e))
        return -1;
    if (k->o->budget_pins && gk_budget_pin_list(&k->budget, k->o->budget_pins, e))
        return -1;
    gk_sched_params_defaults(&k->sched_params, k->c->target_ms);
    return 0;
}

static int open_outputs(kiosk *k, gk_err *e)
{
    if (k->o->capture_dir && mkdir(k->o->capture_dir, 0777) != 0 && errno != EEXIST)
        return gk_fail(e, GK_ERUNTIME, "--capture: cannot create '%s': %s", k->o->capture_dir, strerror(errno));
    if (k->o->stats_path && !(k->csv = gk_stats_csv_open_truth(k->o->stats_path, k->live != NULL, e)))
        return -1;
    return 0;
}

static void log_budget_changes(kiosk *k, const gk_sched_change *ch, int n, double frame_ms)
{
    for (int i = 0; i < n; i++) {
        const gk_knob_def *d = k->budget.def[ch[i].knob];
        gk_log("budget: %s %s -> %s (frame %.1f ms, target %.1f ms)", d->name, d->values[ch[i].from],
               d->values[ch[i].to], frame_ms, k->c->target_ms);
    }
}

/* The levels as this frame ran them (a clamped knob shows what ran, not what was asked). */
static const gk_budget *ran_budget(const kiosk *k)
{
    const gk_budget *ran = gk_renderer_budget_ran(k->r);
    return ran ? ran : &k->budget;
}

/* The HUD, drawn by the renderer as the frame's last pass (`hud`, on its clock). It shows the
 * newest complete frame report: the previous frame's (or older with GPU timer queries). */
static void draw_hud(void *user, const gk_pass_ctx *ctx, unsigned fbo)
{
    (void)ctx;
    kiosk *k = user;
    gk_hud_info info = {
        .scene = gk_playlist_scene(&k->pl), .method = gk_playlist_method(&k->pl), .frame_ms = k->last_frame_ms,
        .method_mode = k->o->method || k->pl.method != k->pl.default_method ? "forced" : "auto",
        .median_ms = gk_recent_percentile(&k->recent, 0.5f), .p95_ms = gk_recent_percentile(&k->recent, 0.95f),
        .target_ms = k->c->target_ms, .recent = &k->recent, .budget = ran_budget(k),
        .panels_hidden = !k->pl.hud_visible, .error = NAN, .truth_noise = NAN,
    };
    if (k->live) {
        const gk_live_error *le = k->live;
        int si = le->scene_index < 0 ? 0 : le->scene_index;
        info.truth_note = le->note;
        info.error = le->error;
        info.truth_noise = le->error_noise;
        info.truth_spp = le->error_spp;
        info.points = le->points[si];
        info.n_points = le->n_points[si];
        info.current_point = le->current_point;
        info.split = k->pl.split_view;
        info.truth_rgb = le->view.generation ? le->view.rgb : NULL;
        info.truth_w = le->view.width;
        info.truth_h = le->view.height;
        info.truth_sub = le->sub;
        info.exposure = gk_renderer_exposure(k->r);
    }
    gk_hud_draw(k->hud, fbo, &info);
}

/* A GI method that failed on this scene (logged once by the renderer) leaves the scene's method
 * list for this visit, so the HUD, the stats and the scheduler name what is really shown. */
static void drop_failed_method(kiosk *k)
{
    const char *method = gk_playlist_method(&k->pl);
    if (strcmp(method, "none") == 0 || !gk_renderer_gi_failed(k->r, method))
        return;
    char methods[GK_PL_MAX_METHODS][GK_METHOD_LEN];
    int n = 0;
    for (int i = 0; i < k->pl.n_methods; i++)
        if (strcmp(k->pl.methods[i], method) != 0)
            snprintf(methods[n++], GK_METHOD_LEN, "%s", k->pl.methods[i]);
    if (n == 0) /* the failed method was forced (--method): show the scene with direct light */
        snprintf(methods[n++], GK_METHOD_LEN, "none");
    gk_log("scene %s: method %s failed, showing the scene with %s", gk_playlist_scene(&k->pl), method,
           n ? methods[0] : "none");
    gk_playlist_set_methods(&k->pl, methods, n, 0);
    begin_visit(k);
}

/* The renderer's stop question, asked before each top-level pass (gk_frame_stop_fn): a stop
 * signal (SIGTERM, SIGINT, SIGHUP, SIGQUIT) abandons the frame, so systemd's stop timeout has to
 * cover one pass, not one frame. The mock's end of script is no signal: that frame finishes. */
static bool stop_between_passes(void *user, const char *next_pass, const char *last_pass)
{
    kiosk *k = user;
    bool stop = gk_platform_quit_requested(k->plat);
    snprintf(k->stop_after, sizeof k->stop_after, "%s", last_pass ? last_pass : "(none)");
    if (!stop && k->test_sigterm_pass[0] && k->frame == k->test_sigterm_frame &&
        strcmp(next_pass, k->test_sigterm_pass) == 0) {
        gk_log("test hook: SIGTERM raised as frame %ld's %s pass begins", k->frame, next_pass);
        raise(SIGTERM);
    }
    return stop;
}

/* Reads GIKIOSK_TEST_SIGTERM_AT=FRAME:PASS (the test hook above); anything else is ignored. */
static void read_test_hook(kiosk *k)
{
    const char *v = getenv("GIKIOSK_TEST_SIGTERM_AT");
    char pass[16];
    if (v && sscanf(v, "%ld:%15[a-z]", &k->test_sigterm_frame, pass) == 2)
        snprintf(k->test_sigterm_pass, sizeof k->test_sigterm_pass, "%s", pass);
}

/* One frame: draw (HUD included), present, record. Returns 1 when a stop request abandoned the
 * frame between its passes (nothing presented, recorded or captured), 0 when it was shown. */
static int frame(kiosk *k, double now, gk_err *e)
{
    const char *scene = gk_playlist_scene(&k->pl), *method = gk_playlist_method(&k->pl);
    double anim_t = gk_playlist_anim_time(&k->pl, now);
    gk_frame_params fp = {.time_s = anim_t, .method = method, .budget = &k->budget};
    if (k->live)
        gk_live_error_pause(k->live, k->pl.paused, anim_t); /* before the frame: its error is on this view */
    if (k->hud && (k->pl.hud_visible || (k->pl.split_view && k->live))) {
        fp.overlay = draw_hud;
        fp.overlay_user = k;
    }
    gk_frame_report report;
    unsigned fbo = gk_platform_framebuffer(k->plat);
    fp.stop = stop_between_passes;
    fp.stop_user = k;
    int drawn = gk_renderer_draw(k->r, &fp, fbo, &report, e);
    if (drawn < 0)
        return -1;
    if (drawn == GK_FRAME_ABANDONED) {
        gk_log("stop requested: frame %ld abandoned after its %s pass (not shown, recorded or captured)", k->frame,
               k->stop_after);
        k->have_frame = false; /* the renderer's image is part of a frame: no visit-end capture */
        return 1;
    }
    /* The frame's cost is the report's total: the sum of the top-level passes on the renderer's one
     * clock (GPU time where it trusts timer queries, CPU time around a fence elsewhere). Present is
     * left out: on KMS it waits for the flip. With GPU timer queries the first GK_TIMER_LAG
     * reports are empty; those frames are not recorded as measured. */
    double frame_ms = report.total_ms;
    bool measured = report.n > 0;
    if (measured) {
        gk_recent_push(&k->recent, (float)frame_ms);
        k->last_frame_ms = frame_ms;
    }
    if (gk_platform_present(k->plat, e))
        return -1;
    gk_notify_frame(&k->notify); /* READY=1 after the first frame shown, then the watchdog's ping */
    /* Judged: what the scheduler holds against the target. Not judged: the warm-up frames of a
       visit and the first frame at a new level, which pay one-off costs (shader compiles,
       voxelizing, first shadow maps); the summary reports them apart. */
    bool judged = measured && k->sched.warm == 0 && k->sched_skip == 0;
    if (measured)
        gk_summary_add(&k->summary, scene, method, frame_ms, judged, ran_budget(k));
    if (judged && gk_sched_at_floor(&k->sched, &k->budget)) {
        /* every knob the scheduler may move is at its floor: budgets cannot help this visit */
        gk_summary_at_floor(&k->summary, scene, frame_ms, k->c->target_ms);
        if (frame_ms > k->c->target_ms && ++k->floor_over == FLOOR_OVER_TO_SAY)
            gk_log("scene %s: cannot meet the %.0f ms target with method %s: %d judged frames over it with every "
                   "knob at its floor (this one %.1f ms)", scene, k->c->target_ms, method, FLOOR_OVER_TO_SAY, frame_ms);
    }
    if (k->live) {
        char levels[160];
        gk_budget_format_active(ran_budget(k), method, levels, sizeof levels);
        if (gk_live_error_frame(k->live, k->r, now, method, levels, frame_ms, judged) && k->live->error_spp > 0 &&
            (k->live->error_spp >= 2 * k->last_logged_spp || k->live->error_spp < k->last_logged_spp)) {
            /* one line each time the truth's samples double (or a new view starts): how it converges */
            k->last_logged_spp = k->live->error_spp;
            gk_log("truth: %s with %s: error %.4f (truth %ld spp, noise %.4f)", scene, method, k->live->error,
                   k->live->error_spp, k->live->error_noise);
        }
        if (k->csv)
            gk_stats_csv_truth(k->csv, k->live->error, isfinite(k->live->error) ? k->live->error_spp : 0);
    }
    if (k->csv && gk_stats_csv_row(k->csv, k->frame, now, scene, method, &report, ran_budget(k), e))
        return -1;
    k->have_frame = true;
    k->last_frame = k->frame;
    snprintf(k->last_scene, sizeof k->last_scene, "%s", scene);
    snprintf(k->last_method, sizeof k->last_method, "%s", method);
    if (k->o->capture_dir && k->o->capture_every && (k->frame + 1) % k->o->capture_every == 0 &&
        capture(k, k->frame, scene, method, e))
        return -1;
    k->frame++;
    drop_failed_method(k);
    if (!measured)
        return 0;
    if (k->sched_skip > 0) {
        k->sched_skip--;
        return 0;
    }
    for (int i = 0; i < k->budget.n; i++)
        if (k->budget.def[i]->scales_pass)
            gk_sched_observe_pass(&k->sched, i, gk_frame_report_ms(&report, k->budget.def[i]->scales_pass));
    gk_sched_change ch[GK_MAX_KNOBS * GK_MAX_KNOB_VALUES];
    int n = gk_sched_update(&k->sched, &k->budget, frame_ms, ch, (int)(sizeof ch / sizeof ch[0]));
    log_budget_changes(k, ch, n, frame_ms);
    if (n > 0)
        k->sched_skip = 1; /* the first frame at a new level pays one-off costs (shader compiles,
                              reallocation, re-voxelizing) and would also spoil the step response */
    return 0;
}

/* Input and attract mode; returns 1 when the run should end. */
static int handle_input(kiosk *k, double now, bool *scene_changed, gk_err *e)
{
    gk_input_event ev[16];
    int n = gk_platform_poll(k->plat, 0, ev, 16);
    if (n < 0)
        return gk_fail(e, GK_ERUNTIME, "input: polling failed"), -1;
    for (int i = 0; i < n; i++) {
        if (ev[i].kind == GK_INPUT_QUIT) {
            gk_log("quit requested at %.2f s", ev[i].time_s);
            return 1;
        }
        int what = gk_playlist_input(&k->pl, &ev[i]);
        if (ev[i].kind == GK_INPUT_CLICK || ev[i].kind == GK_INPUT_HOLD)
            gk_log("input: %s %s at %.2f s", button_name(ev[i].button), kind_name(ev[i].kind), ev[i].time_s);
        if (what & GK_PL_SCENE)
            *scene_changed = true;
        if (what & GK_PL_METHOD) {
            gk_log("method %s (scene %s)", gk_playlist_method(&k->pl), gk_playlist_scene(&k->pl));
            begin_visit(k);
        }
        if (what & GK_PL_HUD)
            gk_log("HUD %s", k->pl.hud_visible ? "on" : "off");
        if (what & GK_PL_PAUSE) {
            const gk_scene *s = k->scenes[k->pl.current];
            gk_log("animation %s at %.3f s%s", k->pl.paused ? "paused" : "resumed",
                   gk_playlist_anim_time(&k->pl, ev[i].time_s),
                   s && s->anim_duration > 0 ? "" : " (this scene does not move)");
        }
        if (what & GK_PL_SPLIT)
            gk_log("split view %s%s", k->pl.split_view ? "on" : "off",
                   k->live ? "" : " (no ground truth: [truth] enabled = false)");
    }
    if (gk_playlist_tick(&k->pl, now) & GK_PL_SCENE) {
        gk_log("attract mode: next scene at %.2f s", now);
        *scene_changed = true;
    }
    return 0;
}

static int loop(kiosk *k, gk_err *e)
{
    gk_playlist_start(&k->pl, gk_platform_now(k->plat));
    if (enter_scene(k, e))
        return -1;
    for (;;) {
        double now = gk_platform_now(k->plat);
        if ((k->o->frames && k->frame >= k->o->frames) || (k->o->seconds > 0 && now >= k->o->seconds))
            break;
        bool scene_changed = false;
        int quit = handle_input(k, now, &scene_changed, e);
        if (quit < 0)
            return -1;
        if (quit)
            break;
        if (scene_changed) {
            if (capture_visit_end(k, e) || enter_scene(k, e))
                return -1;
        }
        int shown = frame(k, now, e);
        if (shown < 0)
            return -1;
        if (shown == 1)
            break;
    }
    return capture_visit_end(k, e);
}

static int open_platform(kiosk *k, gk_err *e)
{
    const gk_kiosk_config *c = k->c;
    gk_platform_desc d;
    gk_platform_desc_defaults(&d);
    d.kind = c->platform;
    /* On KMS the size picks a mode only when asked for (--size); the config's size is the mock's. */
    d.width = c->platform == GK_PLATFORM_KMS && !k->o->size_set ? 0 : c->width;
    d.height = c->platform == GK_PLATFORM_KMS && !k->o->size_set ? 0 : c->height;
    snprintf(d.device, sizeof d.device, "%s", c->device);
    snprintf(d.mode, sizeof d.mode, "%s", c->mode);
    d.buttons = c->buttons;
    if (k->o->script) {
        snprintf(d.script_path, sizeof d.script_path, "%s", k->o->script);
        /* A scripted run without --frames/--seconds ends when its script has played. */
        d.quit_at_script_end = !k->o->frames && !(k->o->seconds > 0);
    }
    if (!(k->plat = gk_platform_open(&d, e)))
        return -1;
    gk_platform_size(k->plat, &k->width, &k->height);
    gk_log("platform %s, %dx%d, GLES %d.%d", gk_platform_name(k->plat), k->width, k->height,
           gk_platform_gles_version(k->plat) / 10, gk_platform_gles_version(k->plat) % 10);
    return 0;
}

/* The platform's calibration (app/sched/calibration.h) beside the scenes: config/scenes ->
 * config/calibration/CLASS.csv. Missing: logged once, the playlist's order is kept. Malformed: an
 * error at start (exit 2, file:line), like a bad kiosk.ini. */
static int load_calibration(kiosk *k, const char *renderer, gk_err *e)
{
    char cls[64], path[1024];
    gk_calibration_class(renderer, cls, sizeof cls);
    gk_calibration_path(k->o->scenes_dir, renderer, path, sizeof path);
    gk_err ce = {0};
    if (gk_calibration_load(path, &k->calibration, &ce) == 0) {
        k->have_calibration = true;
        int defaults = 0;
        for (int i = 0; i < k->calibration.n; i++)
            defaults += k->calibration.rows[i].knob[0] == '\0';
        gk_log("calibration: %s (%d scene x method rows, %d knob-level rows)", path, defaults,
               k->calibration.n - defaults);
        return 0;
    }
    if (ce.code == GK_EINPUT) {
        *e = ce;
        return -1;
    }
    gk_log("no calibration for %s (%s): methods in the playlist's order", cls, ce.msg);
    return 0;
}

static int open_renderer(kiosk *k, gk_err *e)
{
    int gles = gk_platform_gles_version(k->plat);
    if (k->o->gles > gles)
        return gk_fail(e, GK_ERUNTIME, "--gles 3.2: the driver offers only GLES %d.%d", gles / 10, gles % 10);
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    bool software = renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe"));
    gk_render_opts ro = {
        .width = k->width, .height = k->height, .gles_version = k->o->gles ? k->o->gles : gles,
        .shader_dir = k->o->shader_dir, .gpu_timer_queries = !software, /* meaningless on llvmpipe */
        .cpu_workers = k->c->cpu_workers,
    };
    if (!(k->r = gk_renderer_create(&ro, e)))
        return -1;
    if (load_calibration(k, renderer, e) != 0)
        return -1;
    gk_err he = {0};
    k->hud = gk_hud_create(k->width, k->height, k->o->shader_dir, ro.gles_version >= 32 ? 32 : 31, NULL, &he);
    if (!k->hud)
        gk_log("running without HUD: %s", he.msg); /* the kiosk never dies for its overlay */
    if (k->c->truth_enabled) {
        gk_err te = {0};
        if (!(k->live = malloc(sizeof *k->live)) || gk_live_error_open(k->live, k->c, k->width, k->height, &te)) {
            gk_log("running without the live ground truth: %s", te.msg[0] ? te.msg : "out of memory");
            free(k->live);
            k->live = NULL;
        }
    }
    return 0;
}

int gk_kiosk_run(const gk_kiosk_opts *o, const gk_kiosk_config *c, gk_err *e)
{
    kiosk *k = calloc(1, sizeof *k);
    if (!k)
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    k->o = o;
    k->c = c;
    k->visit_scene = k->visit_method = -1;
    read_test_hook(k);
    if (!(k->visits = calloc(1, sizeof *k->visits))) {
        free(k);
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    }
    gk_summary_init(&k->summary);
    gk_notify_open(&k->notify);
    gk_playlist_init(&k->pl, c->scenes, c->n_scenes, c->dwell_s, c->pause_after_input_s);
    int rc = -1;
    if (open_platform(k, e) || open_renderer(k, e) || setup_budget(k, e) || open_outputs(k, e))
        goto done;
    rc = loop(k, e);
done:
    gk_notify_close(&k->notify); /* STOPPING=1: restoring the display and writing outputs */
    if (k->csv) {
        gk_err ce = {0};
        if (gk_stats_csv_close(k->csv, &k->budget, &ce) && rc == 0) {
            *e = ce;
            rc = -1;
        }
    }
    gk_summary_print(&k->summary, stdout);
    fflush(stdout);
    gk_summary_free(&k->summary);
    gk_hud_destroy(k->hud);
    if (k->live) {
        gk_live_error_close(k->live);
        free(k->live);
    }
    gk_renderer_destroy(k->r);
    for (int i = 0; i < GK_MAX_PLAYLIST; i++)
        gk_scene_free(k->scenes[i]);
    gk_platform_close(k->plat);
    free(k->visits);
    gk_calibration_free(&k->calibration);
    free(k);
    return rc;
}
