/* Caustic photons (seed 004 §5; photon-mapping-000-004.md B.1.6, B.6 #7, M15): the CPU part,
 * independent of threads and GL.
 *
 * Caustic photons are shot only toward the known caustic generators: the triangles whose surface
 * is purely specular (no non-delta lobe: mirrors, clear glass). For each point or spot light the
 * generators' world bounding sphere subtends a cone; photon k of the light takes its direction in
 * that cone from the Halton pair (bases 2, 3) of its index ("QMC Halton to lower the noise and avoid
 * flickering") and carries I x (cone solid angle) / (the light's photons) (spot: x its falloff);
 * the cones follow the generators when they move (lm_caustics_aim).
 * A photon follows delta bounces only (its own PCG stream chooses between a dielectric's
 * reflection and refraction, so a retrace in an unchanged scene repeats it bit for bit) and is
 * kept where it first meets a surface with a non-delta lobe after at least one specular bounce: a
 * L S+ D path, the reference's `caustics` term. Anything else is no caustic photon (a kept
 * photon's slot stays empty). The hits are a plain list, no groups ("caustics are localised").
 *
 * Progressive retracing: a light's photons are cut into W runs of consecutive Halton indices (each
 * covers the cone evenly); run s is retraced in the ticks t with s = t mod W (W the window,
 * the seed's 10,000 photons over 8 frames), every photon in the first tick after a change of the
 * photon count or the window. A moving generator therefore leaves a trail that is gone after W
 * ticks, each tick replacing 1/W of it (tests/unit/test_lightmap_caustics.c).
 * Area, directional and mesh lights shoot no caustic photons. */
#ifndef GK_LM_CAUSTICS_H
#define GK_LM_CAUSTICS_H

#include <stdbool.h>
#include <stdint.h>

#include "base/err.h"
#include "ref/ref_scene.h"

typedef struct lm_caustic_light {
    int light;               /* index into the tracer's lights */
    vec3 axis;               /* toward the generators' bounding sphere */
    float cos_max;           /* of the cone around axis (-1: the whole sphere, light inside it) */
    int first, count;        /* its photons: first .. first + count */
} lm_caustic_light;

typedef struct lm_caustics {
    int n;                   /* photons */
    int window;              /* W: ticks over which every photon is retraced once */
    lm_caustic_light *lights;
    int n_lights;
    vec3 *pos;               /* per photon: its caustic hit (world) */
    vec3 *power;             /* its flux (0 and has[k] false when the photon made no caustic) */
    bool *has;
    uint64_t ticks;          /* updates made */
    int retraced;            /* photons traced by the last update */
    bool changed;            /* the last update changed a hit */
} lm_caustics;

/* The generators and cones of rs's point and spot lights; n photons (split evenly among those
 * lights), window W >= 1. No generator or no such light: n becomes 0 (nothing to trace). */
int lm_caustics_init(lm_caustics *c, const gk_ref_scene *rs, int n, int window, gk_err *e);
void lm_caustics_free(lm_caustics *c);
/* Re-aims the cones at the generators where rs has them now (after a node moved): photons keep
 * their Halton numbers, so each one's new path is found when its slice is retraced. */
void lm_caustics_aim(lm_caustics *c, const gk_ref_scene *rs);

/* Photon k's run (0 .. W-1), and whether the next update retraces it (its run is the tick's, or
 * it is the first update). */
int lm_caustics_slice(const lm_caustics *c, int k);
bool lm_caustics_due(const lm_caustics *c, int k);
/* Traces photon k through rs (thread-safe: reads only rs and c's cones); writes its hit. */
void lm_caustics_trace(const lm_caustics *c, const gk_ref_scene *rs, int k, vec3 *pos, vec3 *power, bool *has);
/* Takes the fresh traces of the due photons (arrays of n, the others not read), counts the tick;
 * returns whether a hit changed. The worker traces them over its pool first. */
bool lm_caustics_apply(lm_caustics *c, const vec3 *pos, const vec3 *power, const bool *has);
/* One progressive update on the calling thread (trace the due photons, apply). */
void lm_caustics_update(lm_caustics *c, const gk_ref_scene *rs);

/* The seed's screen-space filter weight, eq. (4): sqrt(1 + 2k² - (i² + j²)), k = 3. */
float lm_caustic_weight(int i, int j);
#define LM_CAUSTIC_K 3

#endif
