/* The renderer's budget knobs with their cost priors (relative cost, cheapest = 1). */
#include "renderer_internal.h"

/* Pixel work scales with the pixel count: 0.5^2 : 0.75^2 : 1. */
static const gk_knob_def knob_render_scale = {
    .name = "render_scale", .owner = "render", .n_values = 3,
    .values = {"0.5", "0.75", "1"}, .cost = {1.0f, 2.25f, 4.0f}, .default_level = 2,
};

/* PCSS: 6^2 blocker + 12^2 PCF fetches per pixel and light against 1 for hard shadows; the
 * lighting arithmetic around them keeps the ratio near 20 rather than 180. */
static const gk_knob_def knob_shadow = {
    .name = "shadow", .owner = "render", .n_values = 2,
    .values = {"hard", "pcss"}, .cost = {1.0f, 20.0f}, .default_level = 1,
};

/* Map rendering: a fixed geometry part plus fill ∝ texels (4x per step); lookups do not grow. */
static const gk_knob_def knob_shadow_map = {
    .name = "shadow_map", .owner = "render", .n_values = 4,
    .values = {"256", "512", "1024", "2048"}, .cost = {1.0f, 1.6f, 3.4f, 10.6f}, .default_level = 2,
};

void gk_renderer_declare_knobs(gk_renderer *r, gk_budget *b)
{
    (void)r;
    gk_budget_add(b, &knob_render_scale);
    gk_budget_add(b, &knob_shadow);
    gk_budget_add(b, &knob_shadow_map);
    /* GI methods declare theirs here once implemented (none yet). */
}
