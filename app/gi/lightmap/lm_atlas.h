/* Light-map parameterisation of the scene's surfaces (seed 004 §3–4; photon-mapping-000-004.md
 * B.1.4, B.2, M9): generated at scene load, from the geometry alone, nothing cached on disk.
 *
 * A *surface* (the seed's hand-made partition) is here a chart: the triangles of one drawn
 * (node, mesh) pair that lie in one plane and on one side of the walls that cross it
 * (scene/wall_split.h) (same geometric normal within 0.9999 and the same plane
 * offset within 1e-4 of the scene's diameter). Each chart is projected orthographically onto its
 * plane, so its triangles never overlap in the atlas, and gets w x h texels at one texel size for
 * the whole scene: the seed's resolution rule, "the big surfaces on the walls have textures of 5
 * by 5 texels" -- the texel is the largest chart's longer side / texels_across (5 by default).
 * A chart is at least 1 x 1 texel.
 *
 * Every chart's interior rect is surrounded by a one-texel gutter that belongs to it alone
 * (lm_atlas_dilate copies the nearest interior texel into it). A point of a chart maps into its
 * interior rect, so a bilinear lookup there reads at most half a texel outside the rect: only
 * the chart's own gutter, never another chart (tests/gpu/test_lightmap_atlas.c renders it).
 * Charts are packed on shelves by decreasing height. Light proxies are not charted (their area
 * light stands in for them, scene.h). */
#ifndef GK_LM_ATLAS_H
#define GK_LM_ATLAS_H

#include <stdint.h>

#include "base/err.h"
#include "core/vecmath.h"
#include "scene/scene.h"
#include "scene/wall_split.h"

#define LM_GUTTER 1
#define LM_MAX_ATLAS 4096

typedef struct lm_chart {
    int node, mesh, material;
    int x, y, w, h;          /* interior rect in atlas texels; the gutter is the ring around it */
    vec3 tu, tv, n;          /* object-space plane frame: p = u tu + v tv + plane_d n */
    float plane_d;
    float u0, v0;            /* chart coordinates of the rect's corner (object units) */
    float su, sv;            /* texels per object unit along tu and tv */
    float area;              /* world-space area of its triangles (m²), at set-up */
    vec3 wmin, wmax, wn;     /* world bounds and unit normal, at set-up */
} lm_chart;

/* One (node, mesh) pair as drawn with light-map UVs: n_verts vertices from first_vert
 * (3 per triangle, unindexed, because charts split vertices). */
typedef struct lm_draw {
    int node, mesh;
    int first_vert, n_verts;
    bool charted;            /* false for light proxies: drawn (they occlude) with uv = -1 */
} lm_draw;

typedef struct lm_atlas {
    int width, height;       /* texels */
    float texel_size;        /* metres (world) per texel */
    int texels_across;       /* the rule's parameter */
    lm_chart *charts;
    int n_charts;
    lm_draw *draws;
    int n_draws;
    float *verts;            /* per vertex: object position xyz, light-map uv (0..1 of the atlas) */
    int n_verts;
    int *vert_chart;         /* per triangle of verts (n_verts / 3): its chart, -1 uncharted */
    /* per triangle of gk_ref_scene_build's flattening of the scene (same order: nodes, meshes,
       triangles, light proxies and degenerate triangles left out): its chart */
    int *ref_chart;
    uint32_t n_ref;
    int *texel_chart;        /* width x height: the chart whose rect or gutter holds the texel, -1 */
    /* The surfaces that "could contribute" to a chart's photon map (seed 004 §3): for a chart
       smaller than a texel, the charts reached from it over touching charts that face within 25
       degrees of it, until their area reaches a texel's (at most 64) -- the facets of a curved or
       finely split surface, whose photons a small chart needs. CSR: chart c's are
       contrib[contrib_first[c] .. contrib_first[c + 1]), itself not included. */
    int *contrib_first;
    int *contrib;
} lm_atlas;

#define LM_VERT_FLOATS 5

/* Builds the atlas of s (evaluated: node world matrices valid). texels_across >= 1. */
int lm_atlas_build(lm_atlas *a, const gk_scene *s, int texels_across, gk_err *e);
/* The same, keeping triangles of different region labels (scene/wall_split.h; NULL: none) in different
 * charts. */
int lm_atlas_build_regions(lm_atlas *a, const gk_scene *s, int texels_across, const gk_wall_regions *regions, gk_err *e);
void lm_atlas_free(lm_atlas *a);

/* Texel coordinates (continuous, texel centres at +0.5) of an object-space point of chart c. */
void lm_chart_texel(const lm_chart *c, vec3 p_obj, float *tx, float *ty);
/* Object-space point at the centre of interior texel (i, j) of chart c (i < w, j < h). */
vec3 lm_chart_point(const lm_chart *c, int i, int j);

/* Copies each chart's border texels into its gutter ring (and corners), for a texture of
 * `channels` floats per texel: bilinear lookups inside a chart then never mix in another's. */
void lm_atlas_dilate(const lm_atlas *a, float *texels, int channels);

#endif
