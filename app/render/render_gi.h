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
/* Adds the method's indirect light to the renderer's HDR target; the method's own pass times
 * are appended to times. "none" or an unknown method add nothing. */
int gk_render_gi_run(gk_render_gi *g, gk_renderer *r, const char *method, const gk_budget *b,
                     const mat4 *view, const mat4 *proj, vec3 eye, gk_pass_times *times, gk_err *e);
/* GPU memory of a method's state at its current budget (0 when not created). */
long gk_render_gi_memory(const gk_render_gi *g, const char *method);

#endif
