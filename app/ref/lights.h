/* Lights for the path tracer: sampling from a shading point (next-event estimation), the pdf of
 * that sampling for a direction found by BSDF sampling (multiple importance sampling), emission
 * seen by a ray, intersection of area-light geometry, and photon emission for light tracing. Units and shapes per scene.h and brdf_spec.md:
 *   point/spot: E = I cos / d^2, spot falloff t^2 with t = clamp((cos - cos_o)/(cos_i - cos_o)),
 *   range window clamp(1 - (d/range)^4, 0, 1)^2; directional: E = lux cos; sun disc of angular
 *   radius R: radiance lux / (2 pi (1 - cos R)); sphere/disc/rectangle: radiance I/area as in
 *   scene.h (disc masked by the spot cone); emissive triangles: emissive nits, front face unless
 *   double-sided. */
#ifndef GK_REF_LIGHTS_H
#define GK_REF_LIGHTS_H

#include <stdbool.h>

#include "ref_scene.h"
#include "sample.h"

typedef struct gk_light_sample {
    vec3 wi;        /* unit direction from the shading point towards the light */
    float dist;     /* distance to the sampled point (INFINITY for directional lights) */
    vec3 li;        /* incident radiance (area) or irradiance at normal incidence (delta) */
    float pdf;      /* solid-angle pdf including the light choice; delta: the choice probability */
    bool delta;
} gk_light_sample;

/* Picks a light in proportion to power and samples it from p. Returns false if nothing to sample. */
bool gk_light_sample_from(const gk_ref_scene *rs, vec3 p, gk_rng *rng, gk_light_sample *out);

/* Samples light li itself from p (no choice among lights: pdf is the light's own; u3 picks the
 * mesh light's triangle): for methods that want one light's direct light (radiosity's surfels). */
bool gk_light_sample_one(const gk_ref_scene *rs, int li, vec3 p, float u1, float u2, float u3, gk_light_sample *out);

/* Closest area-light surface (sphere, disc, rectangle) along the ray before tmax: index or -1. */
int gk_area_lights_intersect(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax, float *t);
bool gk_area_lights_occlude(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax);

/* Radiance leaving area light li towards -d at its point o + t d (0 on its back). */
vec3 gk_area_light_emission(const gk_ref_scene *rs, int li, vec3 d);
/* Radiance of an emissive triangle seen along d (0 from the back unless double-sided). */
vec3 gk_tri_emission(const gk_ref_scene *rs, const gk_ref_tri *t, float b1, float b2, vec3 d);
/* Radiance of the sky's sun discs along an escaping direction d (the environment map, a light of
   its own, is rs->env: gk_env_radiance). */
vec3 gk_sky_emission(const gk_ref_scene *rs, vec3 d, int *light);

/* Solid-angle pdf with which gk_light_sample_from would have produced the point x on light li
 * (for a triangle of the mesh light, tri >= 0) seen from p along unit d. */
float gk_light_pdf(const gk_ref_scene *rs, int li, int tri, vec3 p, vec3 x, vec3 d);

/* Emits a photon from a light picked in proportion to power (the same choice as next-event
 * estimation): origin, direction and flux, already divided by the pick, position and direction
 * pdfs (area emitters: cosine-weighted directions). Returns false without lights. *light receives
 * the light's index (for the range window at the first hit). */
bool gk_light_photon(const gk_ref_scene *rs, gk_rng *rng, vec3 *o, vec3 *d, vec3 *flux, int *light);

/* Picks a light in proportion to power (the choice of gk_light_photon and next-event estimation)
 * from a uniform u: its index (-1 without lights) and, in *prob, the probability of that pick. */
int gk_light_pick(const gk_ref_scene *rs, float u, float *prob);
/* gk_light_photon's emission from light li once picked with probability pl, from five uniforms:
 * the flux is divided by pl. (gk_light_photon = gk_light_pick + this, drawing the same numbers.) */
bool gk_light_photon_of(const gk_ref_scene *rs, int li, float pl, const float u[5], vec3 *o, vec3 *d, vec3 *flux);

/* The range window of a point/spot light at distance dist (1 when range is 0). */
float gk_light_window(const gk_ref_light *L, float dist);
/* Spot cone factor t^2 for an emission direction w (unit, leaving the light). */
float gk_spot_falloff(const gk_ref_light *L, vec3 w);

#endif
