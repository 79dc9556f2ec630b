/* The kiosk's HUD: scene, method, frame time (current, median, p95) with a frame-time graph against
 * the target line, the live error and its speed-vs-error plot ([truth] enabled), and the budget
 * knobs, laid out in the corners by panel size and never over the image centre (the middle third
 * in both directions: GK_HUD_CENTRE_* below), on semi-transparent panels, drawn with alpha blending over the final image after
 * gk_renderer_draw (so it is never in the renderer's captures). Text comes from a DejaVu Sans atlas
 * sized for the panel height; without the font the HUD shows the graph only. GL state it changes
 * is restored. */
#ifndef GK_KIOSK_HUD_H
#define GK_KIOSK_HUD_H

#include "base/err.h"
#include "../sched/budget.h"
#include "stats.h"

typedef struct gk_hud gk_hud;

/* The image centre the panels keep clear of: [W/3, 2W/3) x [H/3, 2H/3) (the split view's truth
 * image and divider are the exception: they are the image). */
#define GK_HUD_CENTRE_LO (1.0 / 3.0)
#define GK_HUD_CENTRE_HI (2.0 / 3.0)

typedef struct gk_hud_info {
    const char *scene, *method;
    const char *method_mode;      /* "auto" (the kiosk's choice) or "forced" (mode button, --method); may be NULL */
    double frame_ms, median_ms, p95_ms, target_ms;
    const gk_recent *recent;
    const gk_budget *budget;
    bool panels_hidden;           /* info clicked: no panels (the split view may still show) */
    /* The live error (live_error.h). truth_note NULL: [truth] is off, nothing of it is drawn; "":
       the truth runs; else why there is none. */
    const char *truth_note;
    double error, truth_noise;    /* the last measurement (NAN before the first) */
    long truth_spp;
    const struct gk_live_point *points; /* this scene's speed-vs-error points, current highlighted */
    int n_points, current_point;
    /* Split view: the truth's estimate (truth_w x truth_h RGB, a pixel per truth_sub^2 frame
       pixels) over the right half, tonemapped with exposure as the frame is. */
    bool split;
    const float *truth_rgb;
    int truth_w, truth_h, truth_sub;
    float exposure;
} gk_hud_info;

/* font_path NULL: DejaVu Sans. A missing font is logged, not an error; a shader or GL failure is
 * GK_ERUNTIME. */
gk_hud *gk_hud_create(int width, int height, const char *shader_dir, int gles, const char *font_path, gk_err *e);
void gk_hud_destroy(gk_hud *h);
/* Draws into fbo (the platform's framebuffer) of the size given at creation. */
void gk_hud_draw(gk_hud *h, unsigned fbo, const gk_hud_info *info);
/* True when the font loaded (text is drawn). */
int gk_hud_has_text(const gk_hud *h);

#endif
