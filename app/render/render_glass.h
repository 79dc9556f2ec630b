/* The `glass` pass: transmissive surfaces drawn over the lit opaque scene by a screen-space
 * refraction lookup (render_glass.c). */
#ifndef GK_RENDER_GLASS_H
#define GK_RENDER_GLASS_H

#include <stdbool.h>

#include "base/err.h"
#include "gl/gbuffer_bind.h"

typedef struct gk_renderer gk_renderer;

/* Whether the scene has transmissive materials (then the G-buffer leaves them out and this pass
   draws them). */
bool gk_render_glass_needed(const gk_renderer *r);
/* Draws the glass over r->shown into the glass target and makes that the image shown. */
int gk_render_glass(gk_renderer *r, const gk_gbuffer_view *gb, gk_err *e);

#endif
