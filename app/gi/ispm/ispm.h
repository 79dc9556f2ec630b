/* The `ispm` GI method (seed 000 §3.3, photon-mapping-000-004.md Part A): image-space photon
 * mapping for caustics on top of the vpl method's diffuse indirect light.
 *   RSM of the light aimed at the specular geometry -> integer-count mip pyramid of its specular
 *   mask -> photons per mask block (power of the whole block) -> Russian roulette + Phong lobe ->
 *   per-pixel linked lists of the camera frustum (tier A, fragment SSBO atomics) or K-layer depth
 *   peeling (tier B) -> compute march through the lists -> instanced oriented disk splats at reduced
 *   resolution -> joint bilateral upsampling, added as ρ_d/π · E to the HDR image.
 * This header is the method's own: the switches the failure-mode tests flip and the statistics they
 * read. The renderer sees only `gk_gi_ispm` (gi.h). */
#ifndef GK_GI_ISPM_H
#define GK_GI_ISPM_H

#include <stdbool.h>

#include "../gi.h"

extern const gk_gi_method gk_gi_ispm;

enum gk_ispm_tier { GK_ISPM_TIER_PEEL = 0, GK_ISPM_TIER_LISTS = 1 };

/* Switches for tests (defaults: the seed with the research's errata fixed). */
typedef struct gk_ispm_debug {
    bool faithful_blocks;    /* the seed's selection: l = ceil(log4(M/N)), full blocks only (L12) */
    bool rng_by_slot;        /* random numbers by compacted photon index, not by RSM block (L13) */
    unsigned shuffle;        /* != 0: permute the block order per frame with this seed (emulates a
                                GPU's nondeterministic compaction order on llvmpipe, L13) */
    bool no_backface_rule;   /* L9: keep hits on surfaces the ray leaves */
    bool faithful_hit;       /* the seed's |Δz| < ε instead of the plane test (trace.comp) */
    bool flat_mirror_normal; /* ispm_bounces > 1: reflect about a node's own normal, not about the
                                normal its shape operator gives at the hit (trace.comp) */
    float hit_px;            /* the plane test's reach around a pixel centre, in trace pixels */
    float edge_on_cos;       /* nodes seen at a smaller |cos| are edge-on (trace.comp) */
    float edge_reach;        /* an edge-on node's plane hit: at most this many pixel footprints off */
    bool faithful_kernel;    /* L15: the seed's 1/(πh²) normalisation */
    bool cone_kernel;        /* cone instead of the Gaussian */
    float delta;             /* Gaussian δ (0.25) */
    float c0;                /* splat radius constant C0 */
    float cos_min;           /* L14: cosθ clamp in the radius */
    float h_min_rel, h_max_rel; /* L14: radius clamps, fractions of the scene diameter */
    float h_pixels;          /* least radius in splat pixels (in kernel samples with ispm_radius=footprint) */
    int pixel_samples;       /* ispm_radius=footprint: its kernel averaged over n x n points per splat
                                pixel (the seed's and the density's disks: at the pixel centre) */
    float eps_abs_rel;       /* hit threshold: constant part, fraction of the scene diameter */
    float eps_slope;         /* hit threshold: multiple of the ray's depth step (0: the seed's constant ε) */
    float upsample_k;        /* normal exponent of the bilateral weights */
    float density_k;         /* ispm_radius=density: photons a disk holds (density.comp) */
    float density_cell;      /* its grid's cell side in output pixels */
    long pool_nodes;         /* > 0: the list pool holds this many nodes, whatever ispm_pool says (L11) */
    bool caustics_only;      /* leave out vpl's indirect light (tests of the caustic alone) */
    bool measure;            /* read the counters back every frame (synchronously) */
} gk_ispm_debug;

typedef struct gk_ispm_stats {
    int tier;                /* the tier that ran (gk_ispm_tier) */
    bool lists_available;    /* the start-up probe found >= 4 fragment storage blocks */
    int rsm_res, trace_res, splat_w, splat_h, budget, capacity;
    bool has_specular;       /* specular geometry lit by the light this frame */
    /* counters of the last measured frame (every frame with debug.measure, else one frame late) */
    unsigned specular_texels;    /* M */
    unsigned level;              /* mask level the photons came from */
    unsigned photons;            /* first hits (photon slots written) */
    unsigned reflected;          /* survived Russian roulette and the lobe */
    unsigned hits;               /* second hits found by the trace */
    unsigned trace_work;         /* march steps + list nodes the trace visited (L19's work count) */
    unsigned photon_overflow;    /* photons dropped: buffer full */
    unsigned fragments;          /* list nodes wanted this frame (tier A: every frustum fragment) */
    unsigned list_overflow;      /* fragments dropped: the pool was full (L11) */
} gk_ispm_stats;

void gk_ispm_default_debug(gk_ispm_debug *d);
void gk_ispm_set_debug(void *self, const gk_ispm_debug *d);
const gk_ispm_stats *gk_ispm_get_stats(const void *self);

/* Test access to the last frame's GPU data (reads back synchronously; buffers as in
 * shaders_gles/ispm/common.glsl). Each returns the element count copied (≤ cap), -1 on error. */
typedef struct gk_ispm_photon { float org[4], dir[4], pow_d1[4]; } gk_ispm_photon;
/* a hit's pos_valid[3]: its path's specular bounces (1 … ispm_bounces), 0 = none */
typedef struct gk_ispm_hit { float pos_valid[4], nrm_h[4], pow_dist[4]; } gk_ispm_hit;
typedef struct gk_ispm_pixel { int head; unsigned zmin, zmax, count; } gk_ispm_pixel;
int gk_ispm_read_photons(void *self, gk_ispm_photon *out, int cap);
int gk_ispm_read_hits(void *self, gk_ispm_hit *out, int cap);
int gk_ispm_read_pixels(void *self, gk_ispm_pixel *out, int cap); /* trace_res² list heads */
/* The caustic irradiance E (RGBA32F-readable floats, splat_w × splat_h × 4) of the last frame. */
int gk_ispm_read_splat(void *self, float *out, int cap_floats);
/* The view the lists were built with (the trace resolution's pixels): world -> trace pixel. */
bool gk_ispm_trace_pixel(const void *self, vec3 world, float out_px[2]);

#endif
