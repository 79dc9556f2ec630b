/* The lightmap method's GPU passes' work (#21, app/gl/pass_work.h). The worker's photon tracing and
 * AIM updates run on the CPU: no pass of the frame. Modelled:
 *   lightmap_compose (compose.frag): one bilinear lookup of the light map (RGBA16F) per pixel whose
 *     visible surface is charted; which pixels those are depends on the view, so a variant of the
 *     pass counts them (COMPOSE_COUNT_FETCHES, one atomic add per lookup) in the bench's untimed
 *     counting frame. Its G-buffer and UV-target reads are not counted (as no pass's G-buffer reads
 *     are).
 *   lightmap_caustic_filter (caustic_filter.frag): every pixel of the filtered tiles reads the
 *     count texels of its 7x7 neighbourhood that lie on the screen, unfiltered single-channel
 *     texels (R8, or R16F with lightmap_count=float: the roofline's R16F kind stands for both), from
 *     the tiles' rects (lm_caustic_filter_reads).
 * tests/gpu/test_lightmap_work.c checks the compose's count against the pixels a CPU count of the
 * G-buffer finds charted geometry in; tests/gpu/test_lightmap_caustics.c the filter's reads against
 * a pixel-by-pixel count.
 *   lightmap_uv (uv.frag): the charted geometry drawn into the UV target with a depth test and
 *     without culling, bound by the raster: every fragment it rasterizes (hidden ones included:
 *     with the atomic the depth test runs after the shader), at the roofline's fill rate, counted by
 *     a variant (UV_COUNT_FRAGMENTS) on binding 5: the compose's counters sit on 6 across this draw.
 *   lightmap_blend (iim_blend.comp): every atlas texel mixes the shown IIM with the gathered one,
 *     two unfiltered RGBA16F texelFetches (the roofline's unfiltered RGBA32F kind stands for them),
 *     counted by a variant (BLEND_COUNT_FETCHES) so that a test holds the dispatch to the atlas.
 * tests/gpu/test_lightmap_work.c checks the UV pass's count against the charted pixels and the
 * blend's against 2 x the atlas's texels.
 *   lightmap_caustic_count (caustic_count.frag): the caustic photons drawn as points, one fragment
 *     each that lands on the screen (hidden ones included: the shader discards them), additive
 *     blend and stencil increment, at the fill rate; counted by a variant (CAUSTIC_COUNT_FRAGMENTS).
 *   lightmap_caustic_cull: per tile a full-screen triangle scissored to the tile dilated by the
 *     kernel's 3 pixels, under the stencil test and an occlusion query: the rects' areas, from the
 *     parameters (lm_caustic_gpu.c), at the fill rate.
 * tests/gpu/test_lightmap_caustics.c checks both against hand counts.
 *   lightmap_gather: the reduction's reads, res² RGBA32UI texels (16 bytes: the roofline's RGBA32F
 *     kind) per gathered texel's tile, counted by a variant of gather_reduce.comp
 *     (REDUCE_COUNT_FETCHES); tests/gpu/test_lightmap_gather.c checks res² per job. And the same
 *     pass's draws, the charted scene rendered into every tile (most of its time): their fragments,
 *     hidden ones included, at the fill rate, and each charted fragment's bilinear AIM lookup
 *     (RGBA16F), counted by a variant of gather.frag (GATHER_COUNT_FRAGMENTS); which surfaces a tile
 *     sees depends on the scene. tests/gpu/test_lightmap_gather_work.c checks both against res² per
 *     job inside a closed box (every tile pixel sees exactly one wall). */
#include "lm_internal.h"

void lm_work_frame(lm_state *s, const gk_gi_frame *f)
{
    s->counting = f->count_work;
    s->compose_lookups.counted = false; /* a frame without the compose reports none */
    s->uv_fragments.counted = false;
    s->blend_fetches.counted = false;
    s->caustic_reads = -1.0;
    s->caustic_points_drawn = -1.0;
    s->caustic_cull_fragments = 0.0;
    s->caustic.count_work = s->counting;
    s->gather.reduce_fetches.counted = false; /* a frame without a gather reports none */
    s->gather_draws.counted = false;
}

const char *lm_work_compose_begin(lm_state *s)
{
    s->compose_lookups.n = 1;
    s->compose_lookups.binding = 6; /* lightmap/compose.frag ComposeFetches */
    return gk_counters_begin(&s->compose_lookups, s->counting) ? "#define COMPOSE_COUNT_FETCHES 1\n" : NULL;
}

void lm_work_compose_end(lm_state *s) { gk_counters_end(&s->compose_lookups); }

const char *lm_work_uv_begin(lm_state *s)
{
    /* lightmap/uv.frag UvFragments */
    return gk_counters_variant(&s->uv_fragments, s->counting, 1, 5, "#define UV_COUNT_FRAGMENTS 1\n");
}

void lm_work_uv_end(lm_state *s) { gk_counters_end(&s->uv_fragments); }

const char *lm_work_blend_begin(lm_state *s)
{
    /* lightmap/iim_blend.comp BlendFetches */
    return gk_counters_variant(&s->blend_fetches, s->counting, 1, 6, "#define BLEND_COUNT_FETCHES 1\n");
}

void lm_work_blend_end(lm_state *s) { gk_counters_end(&s->blend_fetches); }

const char *lm_work_gather_begin(lm_state *s)
{
    /* lightmap/gather.frag GatherFragments: fragments, AIM lookups */
    return gk_counters_variant(&s->gather_draws, s->counting, 2, 5, "#define GATHER_COUNT_FRAGMENTS 1\n");
}

void lm_work_gather_end(lm_state *s) { gk_counters_end(&s->gather_draws); }

void lm_work_caustics(lm_state *s)
{
    if (s->counting)
    {
        s->caustic_reads = s->caustic.n_points > 0 ? s->caustic.filter_reads : -1.0;
        s->caustic_points_drawn = s->caustic.count_fragments.counted ? s->caustic.count_fragments.value[0] : -1.0;
        s->caustic_cull_fragments = s->caustic.cull_fragments;
    }
}

int lm_pass_work(void *self, gk_pass_work *out, int max)
{
    const lm_state *s = self;
    int n = 0;
    if (s->compose_lookups.counted && s->compose_lookups.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_compose", .kind = "tex2d_rgba16f_trilinear",
                                  .fetches = s->compose_lookups.value[0]};
    if (s->uv_fragments.counted && s->uv_fragments.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_uv", .kind = "raster_r16f_depth_fill",
                                  .fetches = s->uv_fragments.value[0]};
    if (s->blend_fetches.counted && s->blend_fetches.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_blend", .kind = "tex2d_rgba32f_nearest",
                                  .fetches = s->blend_fetches.value[0]};
    if (s->gather.reduce_fetches.counted && s->gather.reduce_fetches.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_gather", .kind = "tex2d_rgba32f_nearest",
                                  .fetches = s->gather.reduce_fetches.value[0]};
    if (s->gather_draws.counted && s->gather_draws.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_gather", .kind = "raster_r16f_depth_fill",
                                  .fetches = s->gather_draws.value[0]};
    if (s->gather_draws.counted && s->gather_draws.value[1] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_gather", .kind = "tex2d_rgba16f_trilinear",
                                  .fetches = s->gather_draws.value[1]};
    if (s->caustic_points_drawn > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_caustic_count", .kind = "raster_r16f_depth_fill",
                                  .fetches = s->caustic_points_drawn};
    if (s->caustic_cull_fragments > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_caustic_cull", .kind = "raster_r16f_depth_fill",
                                  .fetches = s->caustic_cull_fragments};
    if (s->caustic_reads > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_caustic_filter", .kind = "tex2d_r16f_nearest",
                                  .fetches = s->caustic_reads};
    return n;
}

void lm_work_free(lm_state *s)
{
    gk_counters_free(&s->compose_lookups);
    gk_counters_free(&s->uv_fragments);
    gk_counters_free(&s->blend_fetches);
    gk_counters_free(&s->gather_draws);
}
