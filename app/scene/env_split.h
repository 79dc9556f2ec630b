/* The environment split into area lights for the rasterizer: seed 001 ch. 5 §5.3.2 (research
 * dong-001.md §3.5), the thesis's greedy fit, each light then shadowed like any area light (CSSM).
 *
 * The thesis, per cube-map face:  seed = the brightest pixel as a 1x1 light; try to enlarge each of
 * its four sides by one pixel, accepting when E_delta / E_total > t; when no side grows, emit the
 * light, remove its energy from the map but leave a residual "equal to the average amount of
 * energy", and start again. Here, on the lat-long map itself (the choice of domain is ours: one
 * domain, no face seams; energies are weighted by each pixel's exact solid angle):
 *   - energy = luminance x solid angle of the radiance above the residual map's mean radiance (per
 *     channel, clamped at 0): what a light takes is the excess over the mean, and the mean stays
 *     behind as the residual, so lights + residual = the map exactly;
 *   - a light is a directional disc (a sun of angular radius r with the rectangle's solid angle,
 *     2 pi (1 - cos r) = Omega) towards the excess-weighted centroid, carrying the excess's
 *     illuminance ∫ L dω per channel, the BRDF evaluated towards its centre as the thesis does;
 *   - the average left behind is the residual's mean at the time (each light lowers it, so later
 *     lights reach into the sky's gradient once the panels are out);
 *   - t = GK_ENV_SPLIT_T (measured below) and a light spans at most a quarter of the map's height
 *     and width (a sun disc must stay a cone a shadow map can cover);
 *   - the lights come out brightest first, so the first N of a run are the run stopped at N: the
 *     renderer's budget knob env_lights draws the first N and the residual after N as ambient.
 * The residual (the map minus the first k lights) is unshadowed ambient: its irradiance as
 * order-2 spherical harmonics, E(n) = sum_i c_i Y_i(n) (Ramamoorthi and Hanrahan 2001: the
 * radiance's coefficients times pi, 2 pi / 3, pi / 4 per band), ambient_sh[k] for every k. */
#ifndef GK_ENV_SPLIT_H
#define GK_ENV_SPLIT_H

#include "scene.h"

#define GK_ENV_MAX_LIGHTS 32
/* Grow a side while the strip adds more than this fraction of the enlarged light's energy (on a
   uniform patch a light grows to 1/t - 1 pixels a side, here up to the size cap). Measured on
   env-studio at 160x120, rel_rmse of method none against the direct-light reference, t = 0.08 /
   0.04 / 0.02 / 0.01: 0.135 / 0.134 / 0.124 / 0.111 with 4 lights, 0.105 / 0.099 / 0.0945 / 0.0947
   with 32 (the thesis's values are in its lost Fig. 5.6). */
#define GK_ENV_SPLIT_T 0.01f

/* Appends up to max_lights env_part directional lights (and their nodes) for s->environment and
 * fills env_light_first, n_env_lights and ambient_sh. Does nothing without an environment. */
int gk_env_split(gk_scene *s, int max_lights, gk_err *e);

/* The order-2 real SH basis at unit n (the same constants as shaders_gles/direct/env_ambient.frag). */
void gk_sh9_basis(vec3 n, float y[9]);

/* Irradiance at normal n from the SH coefficients c (9 x RGB). */
vec3 gk_sh9_irradiance(const float c[9][3], vec3 n);

#endif
