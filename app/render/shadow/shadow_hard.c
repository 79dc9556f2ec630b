/* Hard shadows: the shared depth maps and one comparison per pixel (shaders_gles/shadow/hard.glsl). */
#include <stdlib.h>

#include "shadow.h"

static void *hard_create(void) { return calloc(1, sizeof(gk_shadow_maps)); }

static void hard_destroy(void *self)
{
    if (self)
        gk_shadow_maps_free(self);
    free(self);
}

static int hard_render(void *self, const gk_shadow_ctx *ctx, int slot, const gk_shadow_view *v, gk_err *e)
{
    return gk_shadow_maps_render(self, ctx, slot, v, e);
}

static int hard_bind(void *self, gk_program_cache *progs, int slot, const gk_shadow_view *v, GLuint prog, int unit,
                gk_err *e)
{
    return gk_shadow_maps_bind(self, progs, slot, v, prog, unit, e);
}

const gk_shadow_method gk_shadow_hard = {
    .name = "hard",
    .glsl_define = "#define SHADOW_HARD 1\n",
    .create = hard_create,
    .destroy = hard_destroy,
    .render = hard_render,
    .bind = hard_bind,
};
