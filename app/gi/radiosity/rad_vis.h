/* Explicit link visibility [ours, a variant of the seed's method; issue 11]: the seed's visibility is
 * implicit (rad_links.h: a bin keeps only its shortest link, which hides what lies behind it in that
 * direction). It cannot see a wall thinner than the elements around it: a surfel at the foot of
 * light-leak's 2 cm wall sees the wall's near face edge-on (the wall's elements lie in directions
 * along its plane, not in the bins that look through it), so the bins that look through the wall
 * hold the lit room's ceiling and far wall, and light crosses (RMSE 0.56 against the black
 * reference at the default tessellation, falling only slowly with finer meshes, rad_links.h).
 *
 * This pass keeps the hierarchy, the bins and the weights, and tests each leaf link that carries
 * light once with a shadow ray through the reference tracer's scene (the one the direct light's
 * shadow rays use, rad_direct.h): from the receiving surfel's centre, off its surface as the tracer
 * offsets its shadow rays, to the target node's position (a leaf's surfel centre, an inner node's
 * average of its children's). An occluded link's weight becomes 0: it still hides what its bin hid.
 * One ray per link is a point sample of visibility: a link to a coarse node that is partly hidden is
 * kept or dropped whole (the seed's "elements entirely visible or occluded", now with a real test). */
#ifndef GK_RAD_VIS_H
#define GK_RAD_VIS_H

#include "rad_links.h"
#include "ref/ref_scene.h"

/* Zeroes the weights of L's leaf links (over t) whose segment is blocked in rs; returns how many. */
long rad_links_cull_occluded(rad_links *L, const rad_tree *t, const gk_ref_scene *rs);

#endif
