/* The GI layer of the renderer: runs the GI method chosen for a frame (app/gi/gi.h). */
#ifndef GK_RENDER_GI_H
#define GK_RENDER_GI_H

#include "../gi/gi.h"
#include "renderer.h"

#define GK_GI_MAX_LIGHTS 4   /* lights past this inject no light into GI */

typedef struct gk_render_gi gk_render_gi;

gk_render_gi *gk_render_gi_create(void);
void gk_render_gi_destroy(gk_render_gi *g);
/* Every registered method's knobs. */
void gk_render_gi_declare_knobs(gk_budget *b);
/* "none" + the implemented methods the scene needs and that apply to it. */
int gk_render_gi_methods(const gk_scene *s, const char **names, int max);
/* Adds the method's indirect light to the renderer's HDR target; the method times its passes on
 * ctx's clock (nested under the caller's `gi` pass). "none" or an unknown method add nothing. A
 * method that fails (create, scene upload or a frame) returns -1 once with e filled and is then
 * skipped -- not retried, not logged again -- until the renderer gets another scene. */
int gk_render_gi_run(gk_render_gi *g, gk_renderer *r, const char *method, const gk_pass_ctx *ctx, gk_err *e);
/* Soft-shadow masks of the method for this frame's lights (gi.h shadow_mask), before the direct
 * pass (ctx's G-buffer drawn): masks[i] for the light on node nodes[i], 0 where the method leaves the
 * light to the shadow maps (no hook, its knob says so, or a light it does not see). A failure is
 * handled as gk_render_gi_run's (-1 once, then skipped on this scene; every mask 0). */
int gk_render_gi_shadow_masks(gk_render_gi *g, gk_renderer *r, const char *method, const gk_pass_ctx *ctx,
                              const int *nodes, int n, unsigned *masks, gk_err *e);
/* True when `method` failed on the current scene (the kiosk then shows the scene without it). */
bool gk_render_gi_failed(const gk_render_gi *g, const gk_renderer *r, const char *method);
/* The useful fetches of the method's last frame (gk_gi_method.pass_work); 0 entries when it has
 * no model or was not created. */
int gk_render_gi_pass_work(const gk_render_gi *g, const char *method, gk_pass_work *out, int max);
/* GPU memory of a method's state at its current budget (0 when not created). */
long gk_render_gi_memory(const gk_render_gi *g, const char *method);

#endif
