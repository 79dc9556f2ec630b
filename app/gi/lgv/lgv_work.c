/* The lgv passes' work (#21, app/gl/pass_work.h): what each pass fetches, by the roofline's kinds.
 *   lgv_maps (frames that render the maps: the first of a scene, --rebuild-gi) is rasterized: its
 *     work is the fragments of the scene drawn into every face of every map, at the fill rate,
 *     counted by cubemap.frag's variant (MAPS_COUNT_FRAGMENTS, one atomic add per fragment, in the
 *     bench's untimed counting frame); the min mips (3 levels) are not counted.
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
 *     accumulator, the volume pass each cell's sum (gk_lgv_gather_loads). The geometry volume
 *     (rebuilt when the maps change) is not counted.
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

static const char *begin(gk_counters *c, int n, GLuint binding, bool on, const char *define)
{
    c->n = n;
    c->binding = binding;
    return gk_counters_begin(c, on) ? define : "";
}

const char *lgv_work_trace_begin(lgv_state *s)
{
    return begin(&s->trace_work, 2, 5, s->count_work, "#define TRACE_COUNT_FETCHES 1\n"); /* trace.comp TraceWork */
}

void lgv_work_trace_end(lgv_state *s) { gk_counters_end(&s->trace_work); }

const char *lgv_work_maps_begin(lgv_state *s)
{
    return begin(&s->map_fragments, 1, 6, s->count_work, "#define MAPS_COUNT_FRAGMENTS 1\n"); /* cubemap.frag */
}

void lgv_work_maps_end(lgv_state *s) { gk_counters_end(&s->map_fragments); }

const char *lgv_work_sslgv_begin(lgv_state *s)
{
    return begin(&s->sslgv_loads, 2, 11, s->count_work, "#define SSLGV_COUNT_LOADS 1\n"); /* sslgv_gather.comp */
}

void lgv_work_sslgv_end(lgv_state *s) { gk_counters_end(&s->sslgv_loads); }

const char *lgv_work_lookup_begin(lgv_state *s)
{
    return begin(&s->lookup_fetches, 2, 6, s->count_work, "#define LOOKUP_COUNT_FETCHES 1\n"); /* lookup.frag */
}

void lgv_work_lookup_end(lgv_state *s) { gk_counters_end(&s->lookup_fetches); }

static void add(gk_pass_work *out, int *n, int max, const char *pass, const char *kind, double fetches)
{
    if (fetches > 0.0 && *n < max)
        out[(*n)++] = (gk_pass_work){.pass = pass, .kind = kind, .fetches = fetches};
}

int lgv_pass_work(void *self, gk_pass_work *out, int max)
{
    lgv_state *s = self;
    const gk_lgv_stats *st = gk_lgv_get_stats(s);
    int n = 0;
    if (s->maps_ran && s->map_fragments.counted)
        add(out, &n, max, "gi.lgv_maps", "raster_r16f_depth_fill", s->map_fragments.value[0]);
    if (s->trace_work.counted)
        add(out, &n, max, "gi.lgv_trace", "tex2d_r32ui_nearest", s->trace_work.value[0]);
    if (s->trace_work.counted)
        add(out, &n, max, "gi.lgv_trace", "ssbo_r32ui_atomic", s->trace_work.value[1] + (double)st->caustic);
    if (s->lgv_cells > 0)
        add(out, &n, max, "gi.lgv_gather", "ssbo_rgba32f_load",
            gk_lgv_gather_loads(s->dims, s->iters, s->iters > 0 && s->dbg.occlusion));
    add(out, &n, max, "gi.lgv_sslgv", "ssbo_r32ui_atomic", 12.0 * st->sslgv_accepted);
    if (s->sslgv_loads.counted) {
        add(out, &n, max, "gi.lgv_sslgv", "ssbo_rgba32f_load", s->sslgv_loads.value[0]);
        add(out, &n, max, "gi.lgv_sslgv", "tex2d_depth32f_nearest", s->sslgv_loads.value[1]);
    }
    if (s->lookup_fetches.counted) {
        add(out, &n, max, "gi.lgv_lookup", "tex3d_rgba16f_trilinear", s->lookup_fetches.value[0]);
        add(out, &n, max, "gi.lgv_lookup", "tex2d_rgba16f_trilinear", s->lookup_fetches.value[1]);
    }
    return n;
}

void lgv_work_free(lgv_state *s)
{
    gk_counters_free(&s->trace_work);
    gk_counters_free(&s->map_fragments);
    gk_counters_free(&s->sslgv_loads);
    gk_counters_free(&s->lookup_fetches);
}
