/* The `lgv` GI method (seed 002, Fei & Wang; research vct-003-grid-photon-002.md Part B): photons
 * traced against K distance cube-maps (angle-partition initial point + secant refinement, at most
 * two maps per ray), gathered into a 3D light-gathering volume of 2-band SH vectors (smooth
 * indirect light, eq. 4-7) and a screen-space grid (SSLGV) for caustic photons. The vtable is
 * gk_gi_lgv (gi_registry.c); this header is the test and tool interface. */
#ifndef GK_LGV_H
#define GK_LGV_H

#include <stdbool.h>
#include <stdint.h>

#include "gi/gi.h"

enum { GK_LGV_PART_LGV = 1, GK_LGV_PART_SSLGV = 2, GK_LGV_PART_ALL = 3 };
enum { GK_LGV_ITP_ANGLE = 0, GK_LGV_ITP_PLANAR = 1 };

typedef struct gk_lgv_debug {
    int parts;         /* GK_LGV_PART_*: what the lookup adds (tests measure them apart) */
    int itp_mode;      /* GK_LGV_ITP_ANGLE (the seed) or GK_LGV_ITP_PLANAR (Fig. 4's comparison) */
    unsigned seed;     /* added to the frame index in the photons' hash keys */
    float c0;          /* the SSLGV's bandwidth factor C0 of h = C0 sqrt(A / N) (default LGV_C0) */
    bool snap_hits;    /* diffuse hits moved onto the surface the map's texel holds (default; false: the secant's point) */
    bool plane_hits;   /* the LGV's photons injected where the ray meets the plane of the map's texel (its surface point
                          and normal; default), not at the snapped point (snap_hits: still the caustic photons' and the
                          bounce's; false: the LGV's too, the texels' pattern on the walls, README lgv) */
    bool occlusion;    /* eq. (6)'s fuzzy occlusion G from the geometry volume (default; false: G = 1, leaks) */
    bool bounds_hits;  /* a ray reaching the bounds where the map sees a surface met it there (default; false: left the scene) */
    bool refractor_surface; /* glass hits placed on its refractor map, normals interpolated there (default; false: the hit map's texel) */
    bool sphere_normals; /* tests: glass normals from the refractor map's centre (exact for a sphere centred there) */
    bool exit_maps;    /* a photon leaving glass is traced on that glass's exit map (default; false: on the lattice maps) */
    bool refractor_entry; /* a photon on a specular chain meets glass where its refractor map says (default; false: where the lattice maps do) */
    int sslgv_iters;   /* tests: the SSLGV's gathering iterations (0: LGV_SSLGV_ITERS) */
    bool seeing_maps;  /* a ray's maps: the nearest that see its point (tracer.glsl lgv_seeing_map) */
    bool inject_lobe;  /* eq. (4)-(5) inject a cosine lobe around -n without (Theta, n)+ (research B.2.4's A/B, the default: eq. 4's (Theta, n)+ counts the arrival angle twice; false: the seed's) */
    float lookup_offset; /* eq. (7) reads the LGV this many cells along the normal (0.5, research B.5 item 8) when lookup_own_cell is off */
    bool lookup_own_cell; /* eq. (7) reads the surface's own cell at its centre along the axis nearest the normal (default;
                             false: lookup_offset cells along the normal, which reads 1 - f of a surface f of a cell inside it) */
    int max_events;    /* longest photon path in surface events (0: LGV_BOUNCES) */
    bool gather_replace; /* the lookup reads the last gathering iteration alone (default false: their sum, LPV's) */
} gk_lgv_debug;

typedef struct gk_lgv_stats {
    unsigned rays, injected, caustic, escaped, sslgv_accepted;
    int n_maps, n_refractors, dims[3];
    float cell;
} gk_lgv_stats;

void gk_lgv_default_debug(gk_lgv_debug *d);
void gk_lgv_set_debug(void *self, const gk_lgv_debug *d);
/* Counters of the last frame (read synchronously after it). */
const gk_lgv_stats *gk_lgv_get_stats(void *self);
/* Traces n rays (origin, direction: 6 floats each) once against the maps of the last frame and
 * writes where each first met the scene (hit xyz and 1, or 0 0 0 0 when it left): 4 floats each.
 * With fetches, the counting variant (lgv_work.c) says how many distance-map texels the rays read.
 * Returns n or -1. */
int gk_lgv_probe(void *self, const float *rays, int n, float *hits, double *fetches, gk_err *e);
/* The gathering pass's storage-buffer loads in vec4s (lgv_work.c): LGV dims, iterations, occlusion. */
double gk_lgv_gather_loads(const int dims[3], int iters, bool occlusion);
/* The min mips' image loads (lgv_work.c): 4 per texel of levels 1 .. levels - 1 of `layers` layers of
   res² (mip_min.comp). */
double gk_lgv_mip_loads(int res, int layers, int levels);
/* Map centres of the current scene (xyz, w) and their count (lattice first, then refractors, then
 * the refractors' exit maps). */
int gk_lgv_centres(const void *self, float *out, int cap);
/* The LGV the last frame's lookup read (the iterations' sum, or the last one), 12 floats per cell (R, G, B x 4 SH; x fastest, dims in
 * the stats), into out (cap floats); the count or -1. */
long gk_lgv_read_lgv(void *self, float *out, long cap, gk_err *e);
/* The geometry volume (eq. 6's G, built at the first frame with gathering iterations): 3 opacities
 * (projected areas / l^2 along x, y, z) per LGV cell corner, dims = the LGV's + 1; the count or -1. */
long gk_lgv_read_geometry(void *self, float *out, long cap, int dims[3], gk_err *e);

/* The maps' material codes (lgv/common.glsl: 0 diffuse, 1 mirror, 128 + 32 r + q glass of refractor
 * map r), level 0 of the lattice and refractor maps' layers as gk_lgv_read_maps lays out its level 0,
 * into out (cap bytes); the count or -1. */
long gk_lgv_read_codes(void *self, uint8_t *out, long cap, gk_err *e);
/* The last frame's caustic photons (trace.comp's list, in no particular order): position xyz and
 * power rgb, 6 floats each, into out (cap floats); how many photons, or -1. */
long gk_lgv_read_caustics(void *self, float *out, long cap, gk_err *e);

/* The distance maps and what the tracer reads them with (tests replay the tracer on the CPU). */
typedef struct gk_lgv_maps_info {
    int res, levels, layers, n_maps; /* level 0's side, the min mips, 6 per map (lattice, then refractors) */
    vec3 bmin, bmax;                 /* the scene's bounds as the tracer pads them */
    float itp_eps;                   /* the partition stops when its ITP moves less (m) */
    int q, loops, secant_steps;      /* the partition's intervals and loops, the secant's steps */
} gk_lgv_maps_info;
/* Every level of every layer of the distance maps (R32UI float bits), level by level, each layer's
   rows from y = 0, into out (cap texels); the count or -1. */
long gk_lgv_read_maps(void *self, uint32_t *out, long cap, gk_lgv_maps_info *info, gk_err *e);

#endif
