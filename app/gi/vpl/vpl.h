/* The `vpl` GI method (seed 001 ch. 6 + 000 §3.2; dong-001.md §4): RSM -> N VPLs at Halton
 * positions -> k-means into M VALs -> one paraboloid CSSM (or two-moment) map per VAL -> interleaved
 * gather where VPL i uses its VAL's soft visibility -> geometry-aware blur -> added to the HDR image.
 * This header is the method's own: the state, the debug switches the failure-mode tests flip, and
 * the statistics they read. The renderer sees only `gk_gi_vpl` (gi.h). */
#ifndef GK_GI_VPL_H
#define GK_GI_VPL_H

#include <stdbool.h>

#include "../gi.h"
#include "vpl_cluster.h"

extern const gk_gi_method gk_gi_vpl;

enum gk_vpl_vis { GK_VPL_VIS_VSM, GK_VPL_VIS_CSSM, GK_VPL_VIS_EXACT, GK_VPL_VIS_NONE };

/* Switches for tests and oracles (defaults: the faithful method plus our clamp). */
typedef struct gk_vpl_debug {
    bool random_pattern;     /* F8 oracle: a random VPL pattern per frame instead of fixed Halton */
    bool warm_start;         /* F9 oracle: k-means starts from last frame's centres */
    float w_pos, w_nrm;      /* k-means weights (0.7, 0.3); F12 sets w_nrm = 0 */
    float clamp_scale;       /* d_min = clamp_scale · mean VPL spacing (when vpl_clamp=on) */
    int fade_frames;         /* crossfade length when M changes (0: pop) */
    bool measure;            /* read back the gather to fill stats.clamp_removed (slow) */
    int vis_override;        /* -1: from the vpl_vis knob; else a gk_vpl_vis */
    float adaptive_drop;     /* vpl_m=adaptive: stop doubling M below this relative error drop */
    bool centroid_origin;    /* faithful: render each VAL map from the cluster centroid (default:
                                from the member VPL nearest to it, see gk_val.origin) */
    bool vis_per_vpl;        /* tests: the VAL's visibility evaluated per VPL, as the sum is written,
                                even where once per VAL per receiver is cheaper (the same values;
                                default false: vpl_gather.c vpl_per_val_define) */
} gk_vpl_debug;

typedef struct gk_vpl_stats {
    int n, n_valid;          /* VPLs generated / with flux */
    int m, empty, iters;     /* clusters used, empty ones, k-means iterations */
    double cluster_error;    /* mean k-means distance */
    float spacing, dmin;     /* mean VPL spacing and clamp distance (m) */
    double clamp_removed;    /* fraction of the gathered irradiance the clamp removed (measure) */
    int mr_regions;          /* multires: regions shaded over all levels (measure) */
    bool vis_per_val;        /* the last gather evaluated each VAL's visibility once per receiver
                                (gather.frag VIS_PER_VAL), not once per VPL */
    int fade_left;
    gk_vpl vpl[GK_VPL_MAX_N];
    int labels[GK_VPL_MAX_N];
    gk_val vals[GK_VPL_MAX_M];
} gk_vpl_stats;

/* Render targets: RGBA32F where EXT_color_buffer_float exists, else RGBA16F (the GLES 3.1 floor with
 * EXT_color_buffer_half_float, or 3.2 core); without either create fails with a clear message.
 * The environment variable GK_VPL_TARGETS=half forces the RGBA16F path on a driver that has both
 * (read once by create; tests and the bench use it to exercise the fallback on llvmpipe),
 * GK_VPL_TARGETS=float insists on RGBA32F. True when this instance runs on RGBA16F targets. */
bool gk_vpl_half_targets(const void *self);
void gk_vpl_set_debug(void *self, const gk_vpl_debug *d);
void gk_vpl_default_debug(gk_vpl_debug *d);
const gk_vpl_stats *gk_vpl_get_stats(const void *self);

#endif
