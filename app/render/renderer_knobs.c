/* The renderer's budget knobs with their cost priors (relative cost, cheapest = 1). */
#include "render_gi.h"
#include "renderer_internal.h"

/* Pixel work scales with the pixel count: 0.5^2 : 0.75^2 : 1. */
static const gk_knob_def knob_render_scale = {
    .name = "render_scale", .owner = "render", .n_values = 3,
    .values = {"0.5", "0.75", "1"}, .cost = {1.0f, 2.25f, 4.0f}, .default_level = 2,
};

/* PCSS: 6^2 blocker + 12^2 PCF fetches per pixel and light against 1 for hard shadows; the
 * lighting arithmetic around them keeps the ratio near 20 rather than 180. CSSM (mipmaps): 6
 * filtered fetches per pixel plus basis generation and 5 mip chains per light (Table 5.1: ~4 ms of
 * a 256^2 light on an 8800 GTX) -> 3. VSSM: ~40 SAT/HSM fetches in penumbrae, more where kernels
 * are non-planar, plus the SAT build that dominates at 1024^2 (Tables 7.1/7.2: SAT 2.5-4.8 ms +
 * shadow 2-3.8 ms, "an order of magnitude faster than PCSS" for large penumbrae) -> 5. The
 * default is VSSM (DESIGN §5). */
static const gk_knob_def knob_shadow = {
    .name = "shadow", .owner = "render", .n_values = 4,
    .values = {"hard", "cssm", "vssm", "pcss"}, .cost = {1.0f, 3.0f, 5.0f, 20.0f}, .default_level = 2,
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
    gk_render_gi_declare_knobs(b);
}
