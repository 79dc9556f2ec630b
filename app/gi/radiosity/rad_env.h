/* The environment through empty leaf bins (seed 001 ch. 4, "Light sources"; research dong-001.md
 * §2.3): the environment has no geometry; "any empty bin (in the leaf nodes) can see the lighting
 * environment and therefore receives light from it", which the seed's direct-lighting step gathers.
 *
 * Per bin, the environment's mean radiance over the bin's direction set (rad_env_bin_radiance: the
 * lat-long map integrated over the bin once per scene and bin resolution, RAD_ENV_SUBSAMPLES² directions
 * a bin weighted by their solid angle), then per leaf
 *   E_env(leaf) = Σ_{empty bins b} max(0, n_leaf · ω_b) Ω_b L̄_env(b)
 * (ω_b, Ω_b at the bin's texel centre: the `bin` reading of the link weight, rad_links.h, which is
 * exact for a bin wholly seen). E_env joins the direct irradiance that seeds the bounces,
 * B0 = Le + ρ/π (E_direct + E_env) (rad_solve.h), so the environment's light is unshot energy the
 * bounces distribute; it is not displayed itself: the renderer's direct pass already draws the
 * environment's split lights and ambient (render_env.h), and radiosity's display adds only the
 * bounces. */
#ifndef GK_RAD_ENV_H
#define GK_RAD_ENV_H

#include "rad_links.h"
#include "scene/scene.h"

/* Directions per bin side when integrating the map over a bin (once per scene and bin resolution:
   6 x 16² x 16² lookups at 6x16²). Measured on the studio map (tests/unit/test_radiosity_env.c),
   against 64² directions: the worst bin (on a panel's edge) differs by 9.3%, the total by 5e-4; 8²
   gave 41% and 2e-3. */
#define RAD_ENV_SUBSAMPLES 16

/* out (3 floats a bin, 6 n_face² bins): the environment's mean radiance over each bin's directions,
   `sub` x `sub` of them per bin; zeros without an environment. */
void rad_env_bin_radiance(const gk_environment *env, int n_face, int sub, float *out);

/* E_env (3 floats a leaf) of every leaf of t through its empty bins (L: the links of t), from the bin
   means `bin_radiance` (rad_env_bin_radiance at L's resolution).
   rest = false: the seed's, every empty bin in front of the leaf whole.
   rest = true [ours, the `rest` switch]: the same bins, scaled so that their cos-weighted solid
   angle is at most what the leaf's links leave of the hemisphere, π - Σ link weights (never scaled
   up). Why: an element is linked in the one bin of its centre's direction, so one that subtends
   several bins leaves the others empty and the environment shines through it (research 2.6's
   "element entirely visible or occluded"); the links' spill weights (rad_links.h) already count
   the element's whole solid angle, so the bins and the links together covered more than the
   hemisphere. Measured on the floor of a unit box open at the top (tests/unit/
   test_radiosity_env.c): see README "radiosity". */
void rad_env_irradiance(const rad_tree *t, const rad_links *L, const float *bin_radiance, bool rest, float *out);

#endif
