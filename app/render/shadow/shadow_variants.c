/* Diagnostic shadow methods, selectable by name (gk_shadow_method_find) but not offered to the
 * scheduler's `shadow` knob: they exist to measure failure modes (tests/gpu/test_shadow*.c).
 *   pcss8   brute-force PCSS with 4x4 blocker and 8x8 PCF samples ("PCSS 8x8 shows steps",
 *           failure test F5 of dong-001.md §10) -- the shared pcss.glsl with smaller grids, always
 *           the full 8x8 (PCSS_ADAPTIVE 0). */
#include <stdlib.h>

#include "shadow.h"

static void *maps_create(void) { return calloc(1, sizeof(gk_shadow_maps)); }

static void maps_destroy(void *self)
{
    if (self)
        gk_shadow_maps_free(self);
    free(self);
}

static int maps_render(void *self, const gk_shadow_ctx *ctx, int slot, const gk_shadow_view *v, gk_err *e)
{
    return gk_shadow_maps_render(self, ctx, slot, v, e);
}

static int maps_bind(void *self, gk_program_cache *progs, int slot, const gk_shadow_view *v, GLuint prog, int unit,
                gk_err *e)
{
    return gk_shadow_maps_bind(self, progs, slot, v, prog, unit, e);
}

const gk_shadow_method gk_shadow_pcss8 = {
    .name = "pcss8",
    .glsl_define = "#define SHADOW_PCSS 1\n#define PCSS_BLOCKER_N 4\n#define PCSS_PCF_N 8\n#define PCSS_ADAPTIVE 0\n",
    .create = maps_create,
    .destroy = maps_destroy,
    .render = maps_render,
    .bind = maps_bind,
};
