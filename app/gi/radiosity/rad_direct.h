/* Direct light at the surfels, the seed of the first bounce (seed 001 ch. 4 offers two ways: direct
 * light through the nodes' light links -- its speed-up -- or the renderer's shadowed direct light;
 * research dong-001.md §2.3). We take the second kind, computed where the radiosity needs it: at
 * each leaf surfel, the irradiance from every light of the scene (point, spot, directional, sun,
 * sphere/disc/rectangle area lights; the environment map too, unless the caller takes it through
 * the empty bins instead, rad_env.h) with shadow rays through the reference tracer's own scene
 * (app/ref), so the bounce starts from exactly the direct light the references have, shadows
 * included, and needs no GPU read-back. Why not light links: our lights are not geometry (a
 * Cornell light is a rectangle of scene.h, not a mesh), and point/spot lights have no area to link.
 * Emissive surfaces are not sampled here: they are geometry with an initial radiance (the seed's
 * "area lights are ordinary geometry"), gathered through the links like any other surface. */
#ifndef GK_RAD_DIRECT_H
#define GK_RAD_DIRECT_H

#include "ref/ref_scene.h"
#include "rad_tree.h"

/* E (RGB, lux) at leaves [first, first + count) of t into out (3 floats a leaf, indexed by leaf),
 * `samples` samples per area light (1 for delta lights), deterministic per leaf. */
void rad_direct_irradiance(const gk_ref_scene *rs, const rad_tree *t, int samples, int first, int count, float *out);
/* The same without light `skip` of rs (-1: none): the environment light (rs->env_light) when it
   comes through the empty bins instead (rad_env.h). */
void rad_direct_irradiance_except(const gk_ref_scene *rs, const rad_tree *t, int samples, int skip, int first,
                                  int count, float *out);

#endif
