/* Rendering a reference image: pthreads over a tile work queue (eye paths) and light-path chunks
 * (caustics seen directly), deterministic for a seed whatever the thread count: every pixel sample
 * and every light path has its own random stream, seeded from (seed, pixel or path, sample), and
 * the light-path chunks are fixed (not per thread) and summed in a fixed order.
 *
 * Noise floor: the samples are split into two independent halves (samples [0, S/2) and [S/2, S));
 * with the halves' images h1 and h2, rel RMSE(h1, h2) = sigma sqrt(1/n1 + 1/n2) / mean, so the
 * floor of the full S-sample image is rel RMSE(h1, h2) / sqrt(S (1/n1 + 1/n2)) (= /2 for equal
 * halves) — statistically the same as two renders with different seeds divided by sqrt(2), scaled
 * to S samples, at no extra cost. Rel RMSE (binding definition, shared with the metrics):
 *   sqrt(mean over pixels and RGB of (t - r)^2) / (mean over pixels and RGB of r). */
#ifndef GK_REF_RENDER_H
#define GK_REF_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include "caustic_emit.h"
#include "ref_scene.h"
#include "trace.h"

typedef struct gk_ref_options {
    int spp;             /* samples per pixel (and light paths per pixel for caustics) */
    int threads;         /* >= 1 */
    int max_depth;       /* path vertices after the camera; 32 by default */
    int rr_depth;        /* Russian roulette from this vertex on (4 by default; > max_depth: never) */
    uint64_t seed;
    unsigned paths;      /* GK_PATH_* mask */
    int max_diffuse;     /* most D vertices per path, the eye's first surface included (1: direct
                            light, 2: direct + one bounce); GK_BOUNCES_UNLIMITED by default */
    bool progress;       /* draw a progress bar on stderr */
    int caustic_emit;    /* GK_CAUSTIC_EMIT_GUIDED (default: caustic photons towards the delta
                            surfaces, caustic_emit.h) or GK_CAUSTIC_EMIT_LIGHT (the lights' own
                            emission); both unbiased, the image differs only in noise */
    int caustic_grid;    /* cells per axis of the guided photons' target grid (default 1) */
    int caustic_specular; /* the light tracer's caustic paths with at most this many mirror/glass
                            vertices, L S{1..N} D E (GK_BOUNCES_UNLIMITED by default): the ruler of
                            a caustic method with N specular bounces (ispm's ispm_bounces) */
    unsigned terms;      /* GK_TERM_* mask (trace.h): with a medium, the seed's image terms rendered
                            (default all); --paths then restricts the surfaces term */
} gk_ref_options;

typedef struct gk_ref_result {
    float *rgb;          /* width * height * 3, linear radiance, top row first */
    double noise_floor;  /* relative RMSE floor of this image (NAN when spp < 2 or the image is black) */
    double seconds;
    uint64_t rays;
    uint64_t samples;    /* camera samples (pixels x spp) */
    uint64_t light_paths;
    float *half[2];      /* the images of samples [0, spp/2) and [spp/2, spp) (NULL when spp < 2) */
    int n_half[2];       /* their sample counts */
} gk_ref_result;

void gk_ref_options_default(gk_ref_options *o);
/* What the light pass connects for these options (GK_TERM_SURFACES: L S+ D E, GK_TERM_VCAUSTICS:
 * L S+ V E; the eye pass leaves those paths to it), 0 when the scene needs no light pass (no lights
 * or no delta surfaces). Shared with the kiosk's progressive truth, so both split paths alike. */
unsigned gk_ref_light_terms(const gk_ref_scene *rs, const gk_ref_options *o);
int gk_ref_render(const gk_ref_scene *rs, const gk_ref_options *o, gk_ref_result *r, gk_err *e);
void gk_ref_result_free(gk_ref_result *r);

/* The noise floor (as above) over the pixels whose mask byte is non-zero (inside) or zero (!inside):
 * sqrt(mean of (h1 - h2)^2) / mean of the image, both over those pixels, / sqrt(S (1/n1 + 1/n2)).
 * NAN when the selection is empty, black or the render has no halves. */
double gk_ref_noise_floor_masked(const gk_ref_result *r, int width, int height, const unsigned char *mask,
                                 bool inside);

/* Relative RMSE of t against r (n floats each), as defined above; NAN if mean(r) is 0. */
double gk_ref_rel_rmse(const float *t, const float *r, size_t n);

/* "all", "direct", "indirect", "caustics" <-> mask; -1 if unknown. */
int gk_ref_paths_parse(const char *s);
const char *gk_ref_paths_name(unsigned mask);

/* "all", "airlight", "vcaustics", "surfaces", "multiple" or a '+'-joined list ("airlight+vcaustics")
   <-> GK_TERM_* mask; -1 if unknown. The name is written into buf (at least 64 bytes). */
int gk_ref_terms_parse(const char *s);
const char *gk_ref_terms_name(unsigned terms, char *buf, size_t len);

/* "unlimited" or an integer in [0, 1000] <-> max_diffuse; -2 if invalid. The name is written into
   buf (at least 16 bytes) and returned. */
int gk_ref_bounces_parse(const char *s);
const char *gk_ref_bounces_name(int max_diffuse, char *buf, size_t len);

#endif
