/* Path integrators of the reference path tracer.
 *
 * Light paths are split by Heckbert's notation (E eye, L light, D diffuse or glossy vertex, S delta
 * specular vertex), reading from the light:
 *   direct    = L D S* E  +  L S* E   (direct lighting, and emission seen directly or via mirrors)
 *   caustics  = L S+ D S* E           (light focused by mirrors or glass onto one diffuse vertex)
 *   indirect  = every path with two or more D vertices
 * The three classes partition all paths, so direct + indirect + caustics = all.
 *
 * Eye paths (gk_trace_eye) use next-event estimation with multiple importance sampling (power
 * heuristic) between light sampling and BSDF sampling, Russian roulette (unbiased) after a few
 * bounces, and classify each contribution by the D and S vertices seen so far.
 * Caustics seen directly, L S+ D E, come from light tracing (gk_trace_light) for every light type:
 * photons from the lights (chosen by power) through specular chains to the first diffuse hit,
 * connected to the pinhole camera; by default point and spot lights emit them only towards the
 * delta surfaces (caustic_emit.h), where every caustic path starts. Eye paths cannot find them for delta lights (no BSDF sample hits
 * a point, no light sample leaves a delta vertex) and find them only with huge variance for small
 * area lights. So the eye pass drops every caustic path whose first vertex from the eye is D
 * (E D S+ L) and keeps the caustics seen through a mirror or glass (E S+ D S+ L) — nothing is
 * counted twice. Not rendered (known bias, usually tiny): caustics of delta lights seen through a
 * mirror or glass, L_delta S+ D S+ E, which neither pass can connect.
 *
 * Bounce limit (orthogonal to the classes): max_diffuse keeps only paths with at most that many D
 * vertices, the first surface the eye sees included — 1 = L D S* E + L S* E + L S+ D S* E (direct
 * light and caustics), 2 = that plus one diffuse bounce (L D D E ...), GK_BOUNCES_UNLIMITED = all.
 * It restricts the integrand, not the sampling: the random stream is used as without the limit up to
 * the point where no kept path can follow, so Russian roulette stays unbiased, and a render with a
 * limit equals the unlimited one minus the dropped paths, sample by sample. */
#ifndef GK_REF_TRACE_H
#define GK_REF_TRACE_H

#include <stdbool.h>
#include <stdint.h>

#include "ref_scene.h"
#include "sample.h"

enum { GK_PATH_DIRECT = 1, GK_PATH_INDIRECT = 2, GK_PATH_CAUSTICS = 4, GK_PATH_ALL = 7 };

/* With a participating medium (medium.h), paths are also split into the seed's image terms
 * (001 ch. 8, research dong-001.md §6.1), by their medium vertices V (scattering events):
 *   airlight  (A) = L V S* E        one scattering event lit directly by the light: airlight and
 *                                   volumetric shadows (single scattering);
 *   vcaustics (B) = L S+ V E        one scattering event lit via mirrors or glass: volume caustics;
 *   surfaces  (C) = paths without V surface light (the --paths classes above), every segment
 *                                   attenuated by the medium;
 *   multiple  (M) = the rest        two or more scattering events, or scattering plus a diffuse or
 *                                   glossy vertex: what the single-scattering model leaves out.
 * A + B + C + M = all. B comes from light tracing (a point on each specular segment of a photon,
 * connected to the camera), as surface caustics do, so the eye pass drops E S* V S+ L; E S+ V S+ L
 * (volume caustics seen through a mirror) is found by neither pass: a known bias like the one above.
 * --paths restricts C only. */
enum { GK_TERM_AIRLIGHT = 1, GK_TERM_VCAUSTICS = 2, GK_TERM_SURFACES = 4, GK_TERM_MULTIPLE = 8, GK_TERM_ALL = 15 };
enum { GK_BOUNCES_UNLIMITED = -1 };

typedef struct gk_trace_stats {
    uint64_t rays;   /* closest-hit and shadow rays */
} gk_trace_stats;

typedef struct gk_scene_hit {
    float t;
    int tri;         /* triangle index, or -1 */
    int light;       /* area-light index when the ray hit a light's geometry, else -1 */
    float b1, b2;
} gk_scene_hit;

bool gk_scene_intersect(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax, gk_scene_hit *h);
bool gk_scene_occluded(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax);
/* glTF doubleSided false (single-sided materials): the camera sees such a surface from its front
 * only, as the rasterizer culls its back faces in the G-buffer. A camera ray (gk_trace_eye's first
 * segment) passes through back faces of single-sided materials; every other ray (bounces, shadow
 * rays, photons) hits both faces, as the shadow maps and the GI methods' scene passes draw both: a
 * closed mesh casts its shadow whichever side faces the light. The front is the winding's (ng). */
bool gk_scene_intersect_camera(const gk_ref_scene *rs, vec3 o, vec3 d, float tmax, gk_scene_hit *h);
/* The eye sees point x under that rule (light tracing's connections to the camera). */
bool gk_scene_camera_sees(const gk_ref_scene *rs, vec3 x);

/* Radiance along one camera ray (o, d: its first segment passes single-sided back faces), restricted to the path classes in mask and to paths with at most
 * max_diffuse D vertices (GK_BOUNCES_UNLIMITED: no limit). Russian roulette (survival
 * min(0.95, max throughput)) applies from path vertex rr_depth on. */
vec3 gk_trace_eye(const gk_ref_scene *rs, vec3 o, vec3 d, unsigned mask, unsigned terms, int max_diffuse,
                  int max_depth, int rr_depth, gk_rng *rng, gk_trace_stats *st);

/* One light path (terms: GK_TERM_SURFACES connects surface caustics L S+ D E, GK_TERM_VCAUSTICS the
 * volume caustics L S+ V E); its camera connections are passed to splat(ctx, px, py, rgb)
 * as image-plane measurement contributions (to be divided by the number of light paths).
 * max_specular: connect only paths with at most that many specular vertices (GK_BOUNCES_UNLIMITED:
 * all); like max_diffuse it restricts the integrand, not the sampling.
 * em: photons emitted towards the specular geometry (caustic_emit.h); NULL: the lights' own
 * emission (gk_light_photon). Both are unbiased; em wastes no photon where no caustic can start. */
typedef void (*gk_splat_fn)(void *ctx, int px, int py, vec3 value);
struct gk_caustic_emitter;
void gk_trace_light(const gk_ref_scene *rs, const struct gk_caustic_emitter *em, unsigned terms, int max_depth,
                    int max_specular, gk_rng *rng, gk_splat_fn splat, void *ctx, gk_trace_stats *st);

#endif
