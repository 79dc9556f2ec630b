/* The lgv passes' work (#21, app/gl/pass_work.h): what each pass fetches, by the roofline's kinds.
 *   lgv_maps (frames that render the maps: the first of a scene, --rebuild-gi) is rasterized: its
 *     work is the fragments of the scene drawn into every face of every map, at the fill rate,
 *     counted by cubemap.frag's variant (MAPS_COUNT_FRAGMENTS, one atomic add per fragment, in the
 *     bench's untimed counting frame); the min mips that follow in the same pass load 4 texels of
 *     level l per texel of level l + 1, every layer (mip_min.comp), from the parameters
 *     (gk_lgv_mip_loads), as image loads: the roofline's only image kind is 3D RGBA16F's, so read
 *     their efficiency as against that rate, not a measured R32UI 2D one.
 *   lgv_trace reads the R32UI distance maps texel by texel (texelFetch): the angle partition's fan
 *     (Q + 1 a loop, up to 3 loops, and the ITP), the secant's bracket and refinement, the map
 *     choice and the snap. How many depends on the rays, so tracer.glsl counts them
 *     (TRACE_COUNT_FETCHES); the hits' normal and albedo reads (RGBA8, 2 an event) have no roofline
 *     kind and are not counted. Its injection's atomics into the LGV, counted by the same variant
 *     (12 per injected photon: eq. 5's 3 colours x 4 SH, which the test checks against the stats'
 *     injected photons), and one per caustic photon appended to the list (the stats).
 *   lgv_gather loads storage buffers, modelled in vec4s (12 floats of a cell: 3) from the grid's
 *     size: the resolve reads each cell's 12 ints, every iteration each cell's neighbours that lie
 *     in the grid (12 floats each, + 4 geometry uints with the occlusion: one vec4) and its own
 *     accumulator, the volume pass each cell's sum (gk_lgv_gather_loads). In frames that rebuild the
 *     geometry volume (the maps changed, with the occlusion: lgv_iters > 0) the same pass also reads
 *     each lattice map texel's distance and adds 3 opacities (atomics) for each texel that sees an
 *     opaque surface, counted by lgv_geometry.comp's variant (GEOMETRY_COUNT_FETCHES); its normal
 *     and albedo reads (RGBA8) and the merge's loads are not counted.
 *   lgv_sslgv: 12 atomics per caustic photon the screen grid accepts (the stats), and the
 *     iterations' loads, counted by sslgv_gather.comp's variant (SSLGV_COUNT_LOADS: a pixel's and
 *     its accepted neighbours' 12 floats, 3 vec4s each, and every G-buffer depth read).
 *   lgv_lookup: per shaded pixel 3 trilinear reads of the RGBA16F volumes and the SSLGV images'
 *     (3 filtered reads, or 3 per texel of a footprint larger than a pixel), counted by lookup.frag's
 *     variant (LOOKUP_COUNT_FETCHES).
 * tests/gpu/test_lgv.c checks each against a hand count on the furnace box. */
#include "lgv_internal.h"

static double neighbour_pairs(const int d[3])
{
    double pairs = 0.0;
    for (int a = 0; a < 3; a++)
        pairs += 2.0 * (d[a] - 1) * d[(a + 1) % 3] * d[(a + 2) % 3];
    return pairs;
}

double gk_lgv_gather_loads(const int dims[3], int iters, bool occlusion)
{
    double cells = (double)dims[0] * dims[1] * dims[2];
    double per_iter = neighbour_pairs(dims) * (occlusion ? 4.0 : 3.0) + 3.0 * cells;
    return 3.0 * cells + iters * per_iter + 3.0 * cells;
}

double gk_lgv_mip_loads(int res, int layers, int levels)
{
    double texels = 0.0;
    for (int l = 1; l < levels; l++)
        texels += (double)(res >> l) * (res >> l);
    return 4.0 * layers * texels;
}

/* Per LGV_WORK_* pass: its counters, their buffer block's binding in the shader, the variant. */
static const struct {
    int n;
    GLuint binding;
    const char *define;
} variants[LGV_WORK_N] = {
    [LGV_WORK_TRACE] = {2, 5, "#define TRACE_COUNT_FETCHES 1\n"},    /* trace.comp TraceWork */
    [LGV_WORK_MAPS] = {1, 6, "#define MAPS_COUNT_FRAGMENTS 1\n"},    /* cubemap.frag MapFragments */
    [LGV_WORK_SSLGV] = {2, 11, "#define SSLGV_COUNT_LOADS 1\n"},     /* sslgv_gather.comp SslgvLoads */
    [LGV_WORK_LOOKUP] = {2, 6, "#define LOOKUP_COUNT_FETCHES 1\n"},  /* lookup.frag LookupFetches */
    [LGV_WORK_GEOMETRY] = {2, 5, "#define GEOMETRY_COUNT_FETCHES 1\n"}, /* lgv_geometry.comp GeometryWork */
};

const char *lgv_work_begin(lgv_state *s, int pass)
{
    gk_counters *c = &s->work[pass];
    c->n = variants[pass].n;
    c->binding = variants[pass].binding;
    return gk_counters_begin(c, s->count_work) ? variants[pass].define : "";
}

void lgv_work_end(lgv_state *s, int pass) { gk_counters_end(&s->work[pass]); }

static void add(gk_pass_work *out, int *n, int max, const char *pass, const char *kind, double fetches)
{
    if (fetches > 0.0 && *n < max)
        out[(*n)++] = (gk_pass_work){.pass = pass, .kind = kind, .fetches = fetches};
}

int lgv_pass_work(void *self, gk_pass_work *out, int max)
{
    lgv_state *s = self;
    const gk_lgv_stats *st = gk_lgv_get_stats(s);
    const gk_counters *trace = &s->work[LGV_WORK_TRACE], *maps = &s->work[LGV_WORK_MAPS];
    const gk_counters *sslgv = &s->work[LGV_WORK_SSLGV], *lookup = &s->work[LGV_WORK_LOOKUP];
    const gk_counters *geometry = &s->work[LGV_WORK_GEOMETRY];
    int n = 0;
    if (s->maps_ran && maps->counted) {
        add(out, &n, max, "gi.lgv_maps", "raster_r16f_depth_fill", maps->value[0]);
        add(out, &n, max, "gi.lgv_maps", "image3d_rgba16f_load", gk_lgv_mip_loads(s->maps_res, 6 * s->maps_count, s->levels));
    }
    if (trace->counted) {
        add(out, &n, max, "gi.lgv_trace", "tex2d_r32ui_nearest", trace->value[0]);
        add(out, &n, max, "gi.lgv_trace", "ssbo_r32ui_atomic", trace->value[1] + (double)st->caustic);
    }
    if (s->lgv_cells > 0)
        add(out, &n, max, "gi.lgv_gather", "ssbo_rgba32f_load",
            gk_lgv_gather_loads(s->dims, s->iters, s->iters > 0 && s->dbg.occlusion));
    if (geometry->counted) { /* the geometry volume, rebuilt in this frame's gathering pass */
        add(out, &n, max, "gi.lgv_gather", "tex2d_r32ui_nearest", geometry->value[0]);
        add(out, &n, max, "gi.lgv_gather", "ssbo_r32ui_atomic", geometry->value[1]);
    }
    add(out, &n, max, "gi.lgv_sslgv", "ssbo_r32ui_atomic", 12.0 * st->sslgv_accepted);
    if (sslgv->counted) {
        add(out, &n, max, "gi.lgv_sslgv", "ssbo_rgba32f_load", sslgv->value[0]);
        add(out, &n, max, "gi.lgv_sslgv", "tex2d_depth32f_nearest", sslgv->value[1]);
    }
    if (lookup->counted) {
        add(out, &n, max, "gi.lgv_lookup", "tex3d_rgba16f_trilinear", lookup->value[0]);
        add(out, &n, max, "gi.lgv_lookup", "tex2d_rgba16f_trilinear", lookup->value[1]);
    }
    return n;
}

void lgv_work_free(lgv_state *s)
{
    for (int k = 0; k < LGV_WORK_N; k++)
        gk_counters_free(&s->work[k]);
}
