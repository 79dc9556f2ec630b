/* Brute-force PCSS (dong-001.md §1.2): blocker search + penumbra estimate + PCF over the shared
 * depth maps (shaders_gles/shadow/pcss.glsl). Sample counts are compile-time (PCSS_BLOCKER_N,
 * PCSS_PCF_N) so loops unroll; the defaults trade banding for per-pixel noise at 6^2 + 12^2
 * fetches. */
#include <stdlib.h>

#include "shadow.h"

static void *pcss_create(void) { return calloc(1, sizeof(gk_shadow_maps)); }

static void pcss_destroy(void *self)
{
    if (self)
        gk_shadow_maps_free(self);
    free(self);
}

static int pcss_render(void *self, const gk_shadow_ctx *ctx, int slot, const gk_shadow_view *v, gk_err *e)
{
    return gk_shadow_maps_render(self, ctx, slot, v, e);
}

static int pcss_bind(void *self, gk_program_cache *progs, int slot, const gk_shadow_view *v, GLuint prog, int unit,
                gk_err *e)
{
    return gk_shadow_maps_bind(self, progs, slot, v, prog, unit, e);
}

const gk_shadow_method gk_shadow_pcss = {
    .name = "pcss",
    .glsl_define = "#define SHADOW_PCSS 1\n",
    .create = pcss_create,
    .destroy = pcss_destroy,
    .render = pcss_render,
    .bind = pcss_bind,
};
