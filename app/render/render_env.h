/* The scene environment in the rasterizer: seed 001 ch. 5 §5.3.2 (research dong-001.md §3.5). The
 * loader split the map into area lights (scene/env_split.h: the thesis's greedy fit, brightest
 * first), scene lights with env_part set, which the frame draws like any directional disc light
 * (the BRDF evaluated towards the light's centre, as the thesis does) but always shadowed with CSSM
 * (mipmapped, the thesis's choice for many lights) at GK_ENV_SHADOW_MAP texels, whatever the
 * `shadow` knob says for the scene's own lights. The knob env_lights draws the first N of them; the
 * rest of the map, the residual after those N, is added unshadowed by this module's pass as order-2
 * SH irradiance times the diffuse BRDF (the split's light-less remainder; the thesis fits lights
 * until the whole map is covered and has none), and the background pixels show the map itself. */
#ifndef GK_RENDER_ENV_H
#define GK_RENDER_ENV_H

#include <stdbool.h>

#include "gl/gbuffer_bind.h"
#include "shadow/shadow.h"

/* Shadow-map size of each environment light: the thesis's 256^2 for environment lighting
   (Table 5.1, Figs. 5.10, 5.11: 30 to 60 lights at 256^2 each). */
#define GK_ENV_SHADOW_MAP 256

struct gk_renderer;

/* How many of the environment's lights the frame draws at knob value env_lights. */
int gk_render_env_lights_drawn(const gk_scene *s, int env_lights);
/* Whether scene light li is drawn at knob value env_lights (every light outside the environment is). */
bool gk_render_env_light_on(const gk_scene *s, int li, int env_lights);
/* The shadow method of the environment's lights (CSSM, mipmapped). */
const gk_shadow_method *gk_render_env_shadow_method(void);

/* Adds, into the bound HDR target with additive blending on, the residual's ambient on surfaces
 * and the map's radiance in the background. Nothing without an environment. */
int gk_render_env_pass(struct gk_renderer *r, const gk_gbuffer_view *gb, int env_lights, gk_err *e);

#endif
