/* The real-time renderer: deferred GLES 3.1 pipeline (shadow maps -> G-buffer -> direct light ->
 * GI method -> compose/tonemap), owned HDR image, captures. The kiosk creates one per platform,
 * gives it a scene, and asks for frames. GL context must be current (the platform's). */
#ifndef GK_RENDERER_H
#define GK_RENDERER_H

#include <stdbool.h>

#include "base/err.h"
#include "../scene/scene.h"
#include "../sched/budget.h"
#include "gl/frame_report.h"
#include "gl/pass.h"
#include "gl/pass_work.h"


typedef struct gk_render_opts {
    int width, height;        /* output (panel or --size) */
    int gles_version;         /* 31 forces the portable path; 32 allows capability-checked 3.2 paths */
    const char *shader_dir;   /* NULL: the shaders embedded in the binary */
    bool gpu_timer_queries;   /* false on llvmpipe (meaningless there) */
    bool rerender_static_shadows; /* re-render shadow maps every frame even when nothing moved
                                     (the bench, to measure a method's per-frame cost) */
    bool rebuild_gi;          /* GI methods redo their cached static work every frame (the bench's
                                 --rebuild-gi: what a moving light or object costs) */
    int cpu_workers;          /* threads a GI method may run on the CPU ([cpu] workers), 0 = cores - 1 */
} gk_render_opts;

/* Drawn over the finished frame in target_fbo as the frame's last pass (`hud`), on the renderer's
 * clock: the kiosk's HUD. Never part of captures (they read the HDR image). */
typedef void (*gk_overlay_fn)(void *user, const gk_pass_ctx *ctx, unsigned target_fbo);

/* Asked before each top-level pass of a frame (shadow, gbuffer, direct, gi, compose, hud) with the
 * pass about to run and the one that ran last (NULL before the first): true abandons the frame.
 * The kiosk answers a stop request (SIGTERM) this way, so a stop waits for the pass in flight,
 * not for the rest of the frame. A GI method's own passes run as the one `gi` pass. */
typedef bool (*gk_frame_stop_fn)(void *user, const char *next_pass, const char *last_pass);

typedef struct gk_frame_params {
    double time_s;            /* animation time */
    const char *method;       /* GI method: "none", "vct", ... */
    const gk_budget *budget;  /* current knob levels */
    gk_overlay_fn overlay;    /* optional */
    void *overlay_user;
    gk_frame_stop_fn stop;    /* optional */
    void *stop_user;
} gk_frame_params;

/* gk_renderer_draw's result for a frame that fp->stop abandoned. */
#define GK_FRAME_ABANDONED 1

typedef struct gk_renderer gk_renderer;

gk_renderer *gk_renderer_create(const gk_render_opts *opts, gk_err *e);
void gk_renderer_destroy(gk_renderer *r);

/* Declares the renderer's knobs (render_scale, shadow method, shadow map size, ...) and those of
 * every GI method into b. */
void gk_renderer_declare_knobs(gk_renderer *r, gk_budget *b);

/* Uploads a scene (meshes, textures, materials). The renderer keeps a pointer; the scene outlives
 * it or the next set_scene. Errors are GK_ERUNTIME (GPU). */
int gk_renderer_set_scene(gk_renderer *r, gk_scene *s, gk_err *e);

/* Names of the GI methods that apply to the current scene, "none" first. */
int gk_renderer_methods(const gk_renderer *r, const char **names, int max);

/* Changes opts.rerender_static_shadows: the bench turns it on while it sweeps shadow knobs. */
void gk_renderer_set_rerender_static_shadows(gk_renderer *r, bool on);
/* Changes opts.rebuild_gi. */
void gk_renderer_set_rebuild_gi(gk_renderer *r, bool on);

/* Renders one frame into target_fbo (the platform's framebuffer) and fills the frame report
 * (report may be NULL): top-level passes shadow, gbuffer, direct, gi (the GI method's passes nested
 * under it), compose, hud; total_ms is their sum. On llvmpipe the report is this frame's; with GPU
 * timer queries it is GK_TIMER_LAG frames old. A GI method that fails is reported once through
 * gk_renderer_gi_failed and the frame keeps its direct light. Returns 0, -1 on error, or
 * GK_FRAME_ABANDONED when fp->stop asked to stop between passes: target_fbo and the HDR image
 * then hold part of a frame, which must be neither presented nor captured (gk_renderer_capture
 * refuses until a frame is finished). */
int gk_renderer_draw(gk_renderer *r, const gk_frame_params *fp, unsigned target_fbo, gk_frame_report *report,
                     gk_err *e);
/* The last frame's knob levels as they ran: its budget, with the levels a pass could not run
 * replaced by what it ran (vct_res=256 -> 128 past the storage-buffer limit). NULL when the frame
 * had no budget. What the HUD, the stats and the bench report. */
const gk_budget *gk_renderer_budget_ran(const gk_renderer *r);
/* A cut: the next frame shows its GI at once, without the cross-fade from the last frame's (a
 * change of method or knob levels otherwise fades over `gi_blend` frames). The bench cuts between
 * configurations so each one is measured as itself. */
void gk_renderer_cut(gk_renderer *r);
/* True when the GI method failed on the current scene (logged once by the renderer; it is not
 * run again until the next scene). */
bool gk_renderer_gi_failed(const gk_renderer *r, const char *method);
/* The bench's efficiency (#21, render_work.c). While on, passes run a variant that counts their
 * work (atomic adds per fragment or pixel: not for timed frames): the G-buffer's fragments, the
 * direct pass's shadow lookups, the compose's HDR lookups, and the GI method's (gk_gi_frame.
 * count_work). Returns false, and counts nothing, where the fragment stage has no storage buffers. */
bool gk_renderer_count_work(gk_renderer *r, bool on);
/* The useful fetches of the last frame's passes (app/gl/pass_work.h) when that frame counted them:
 * the `gbuffer` pass's fragments, the `direct` pass's shadow lookups and the `compose` pass's HDR
 * lookups, then GI method `method`'s passes. Up to max entries,
 * returns how many. May stall on a GPU counter. */
int gk_renderer_pass_work(const gk_renderer *r, const char *method, gk_pass_work *out, int max);

/* Writes the last frame: png_path display-referred (tonemapped, as shown), exr_path linear scene
 * radiance before exposure (either may be NULL). */
int gk_renderer_capture(gk_renderer *r, const char *png_path, const char *exr_path, gk_err *e);

/* The last frame's display image (as gk_renderer_capture's png) with overlay drawn over it, as the
 * frame's last pass draws it on screen: the kiosk's HUD captures. */
int gk_renderer_capture_overlay(gk_renderer *r, const char *png_path, gk_overlay_fn overlay, void *user, gk_err *e);

/* Added by the renderer: the last frame's linear image (RGBA float, output size, top row first,
 * before exposure) without writing a file -- for tests and in-process metrics. */
struct gk_image;
int gk_renderer_read_linear(gk_renderer *r, struct gk_image *img, gk_err *e);
/* The display exposure in use (a scale factor, tonemap.h); fixed per scene. */
float gk_renderer_exposure(const gk_renderer *r);

#endif
