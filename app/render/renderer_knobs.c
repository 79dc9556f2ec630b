/* The renderer's budget knobs with their cost priors (relative cost, cheapest = 1). */
#include "render_gi.h"
#include "renderer_internal.h"

/* Pixel work scales with the pixel count: 0.5^2 : 0.75^2 : 1. */
static const gk_knob_def knob_render_scale = {
    .name = "render_scale", .owner = "render", .n_values = 3,
    .values = {"0.5", "0.75", "1"}, .cost = {1.0f, 2.25f, 4.0f}, .default_level = 2,
};

/* Ordered by measurement, not by the documents' cost claims (issue: PCSS was the "most expensive"
 * level while it measured cheaper and more accurate). `make bench` shadow sweep on llvmpipe, 640x360
 * frame time with the maps rendered every frame / error at 160x120 against the direct reference:
 *   shadow-planes  hard 37 ms / 0.161   pcss 58 ms / 0.026   vssm 401 ms / 0.024   cssm 430 ms / 0.158
 *   cornell        hard 25 ms / 0.050   pcss 70 ms / 0.030   vssm 393 ms / 0.084   cssm 422 ms / 0.122
 *   cornell-spot   hard 20 ms / 0.017   pcss 21 ms / 0.027   vssm 158 ms / 0.022   cssm 144 ms / 0.017
 * (with static maps kept, the direct pass alone: hard 27/17/12, pcss 50/58/15, vssm 205/197/106,
 * cssm 48/48/36 ms). PCSS is within noise of the best error at 1.5-3x hard's cost; VSSM and CSSM
 * cost 6-20x PCSS on this platform without being more accurate, so the scheduler climbs hard -> pcss
 * and stops (auto_max_level); vssm and cssm stay selectable (`--budget shadow=vssm`, the thesis's
 * methods, measured side by side by `make bench`). The seeds' claim that VSSM beats PCSS for large
 * penumbrae is about GPU texture bandwidth; a GPU calibration may reorder these (within the automatic
 * levels the calibration's knob rows already skip, per scene, a level measured no more accurate;
 * promoting vssm/cssm into them from a board's calibration is a follow-up). DESIGN §5 names VSSM the default; the default is
 * PCSS because it measured better here (README, "Soft shadows"). Cost priors: the frame ratios
 * above, hard 1 : pcss 2 : vssm 12 : cssm 13. */
static const gk_knob_def knob_shadow = {
    .name = "shadow", .owner = "render", .n_values = 4,
    .values = {"hard", "pcss", "vssm", "cssm"}, .cost = {1.0f, 2.0f, 12.0f, 13.0f}, .default_level = 1,
    .auto_max_level = 1,
};

/* Map rendering: a fixed geometry part plus fill ∝ texels (4x per step); lookups do not grow, so
 * the knob scales the `shadow` pass (which is ~0 when a static scene's maps are kept). */
static const gk_knob_def knob_shadow_map = {
    .name = "shadow_map", .owner = "render", .n_values = 4,
    .values = {"256", "512", "1024", "2048"}, .cost = {1.0f, 1.6f, 3.4f, 10.6f}, .default_level = 2,
    .scales_pass = "shadow",
};

/* VSSM kernel subdivision depth (dong-001.md §5.2; read by shadow/shadow_vssm.c, no effect for the
 * other shadow methods): level -> (m x m blocker grid, quadtree height H) = (1,0) (2,1) (3,2)
 * (5,3) (8,4); 3 is the thesis's default, 4 a reference level the scheduler does not pick itself.
 * Cost prior after §8.2's T_vssm(SM_res^2, penumbra_px): about half of a VSSM frame is the SAT
 * build and half the shadow lookups (Tables 7.1/7.2: SAT 2.5-4.8 ms, shadow 2-3.8 ms), the knob
 * only changes the lookups of NON-PLANAR kernels, taken as 10% of penumbra pixels, whose
 * worst-case fetches grow as m^2 x 12 + (sum_l 4^l) x 8 + 4^H x 4 + 40 = 64 / 144 / 380 / 1276 /
 * 4560. Cost = 0.5 + 0.5 (0.9 + 0.1 fetches / 64): 1, 1.06, 1.25, 1.95, 4.5. */
static const gk_knob_def knob_shadow_subdiv = {
    .name = "shadow_subdiv", .owner = "render", .n_values = 5,
    .values = {"0", "1", "2", "3", "4"}, .cost = {1.0f, 1.06f, 1.25f, 1.95f, 4.5f}, .default_level = 3,
    .auto_max_level = 3,
};

/* Frames a change of GI method or budget is cross-faded over (render_gi_blend.c); 0 = off, the
 * method's result shows at once (for measuring the pop itself). A switch, not a trade: the fade
 * costs one HDR blit per frame with GI (timed as gi.blend_hold), the scheduler never moves it. 4
 * frames: each frame of a switch moves a quarter of the jump (tests/gpu/test_gi_blend.c). */
static const gk_knob_def knob_gi_blend = {
    .name = "gi_blend", .owner = "render", .n_values = 2,
    .values = {"0", "4"}, .cost = {1.0f, 1.0f}, .default_level = 1, .fixed = true,
};

/* How many of the environment's area lights (scene/env_split.h: brightest first) the frame draws,
 * each a directional disc light shadowed with CSSM; the rest of the map is the unshadowed SH ambient.
 * No effect on a scene without an environment. Cost prior: each light is one shadow map (kept while
 * the scene is static) and one full-screen lighting pass, so the cost grows with N. The thesis's
 * counts are 30 / 45 / 60 (Fig. 5.10: 45 "visually almost indistinguishable"); the levels stop at
 * GK_ENV_MAX_LIGHTS = 32. The default level: README "Environment lighting" (error against N). */
static const gk_knob_def knob_env_lights = {
    .name = "env_lights", .owner = "render", .n_values = 4,
    .values = {"4", "8", "16", "32"}, .cost = {1.0f, 2.0f, 4.0f, 8.0f}, .default_level = 2,
};

void gk_render_knobs_init(gk_render_knobs *k)
{
    k->scale = (gk_knob){&knob_render_scale, -1};
    k->shadow = (gk_knob){&knob_shadow, -1};
    k->shadow_map = (gk_knob){&knob_shadow_map, -1};
    k->shadow_subdiv = (gk_knob){&knob_shadow_subdiv, -1};
    k->gi_blend = (gk_knob){&knob_gi_blend, -1};
    k->env_lights = (gk_knob){&knob_env_lights, -1};
    k->shadow_table_def = NULL;
    k->shadow_without_budget = gk_shadow_method_find("pcss");
}

void gk_render_knobs_read(gk_render_knobs *k, const gk_budget *b, gk_frame_knobs *out)
{
    out->render_scale = gk_knob_number(b, &k->scale, 1.0f);
    if (!(out->render_scale > 0.0f) || out->render_scale > 1.0f)
        out->render_scale = 1.0f;
    /* The level -> method table is built by name once per definition of the knob: the renderer's
       own, or a test's with extra variants (shadow_variants.c) */
    const gk_knob_def *d = gk_knob_def_in(b, &k->shadow);
    if (d && d != k->shadow_table_def) {
        for (int i = 0; i < d->n_values; i++)
            k->shadow_of_level[i] = gk_shadow_method_find(d->values[i]);
        k->shadow_table_def = d;
    }
    int shadow = d ? gk_knob_level(b, &k->shadow, -1) : -1;
    out->shadow = shadow >= 0 ? k->shadow_of_level[shadow] : k->shadow_without_budget;
    out->shadow_map = (int)gk_knob_number(b, &k->shadow_map, 1024.0f);
    out->shadow_subdiv = gk_knob_level(b, &k->shadow_subdiv, knob_shadow_subdiv.default_level);
    out->gi_blend = (int)gk_knob_number(b, &k->gi_blend, 0.0f); /* no budget: one-off frames, nothing to fade */
    out->env_lights = (int)gk_knob_number(b, &k->env_lights, 16.0f);
}

void gk_renderer_declare_knobs(gk_renderer *r, gk_budget *b)
{
    (void)r;
    gk_budget_add(b, &knob_render_scale);
    gk_budget_add(b, &knob_shadow);
    gk_budget_add(b, &knob_shadow_map);
    gk_budget_add(b, &knob_shadow_subdiv);
    gk_budget_add(b, &knob_gi_blend);
    gk_budget_add(b, &knob_env_lights);
    gk_render_gi_declare_knobs(b);
}
