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
 * a pixel-by-pixel count. Not modelled: the UV pass (rasterized), the final gather and the IIM
 * blend, the caustic count and cull passes. */
#include "lm_internal.h"

void lm_work_frame(lm_state *s, const gk_gi_frame *f)
{
    s->counting = f->count_work;
    s->compose_lookups.counted = false; /* a frame without the compose reports none */
    s->caustic_reads = -1.0;
}

const char *lm_work_compose_begin(lm_state *s)
{
    s->compose_lookups.n = 1;
    s->compose_lookups.binding = 6; /* lightmap/compose.frag ComposeFetches */
    return gk_counters_begin(&s->compose_lookups, s->counting) ? "#define COMPOSE_COUNT_FETCHES 1\n" : NULL;
}

void lm_work_compose_end(lm_state *s) { gk_counters_end(&s->compose_lookups); }

void lm_work_caustics(lm_state *s)
{
    if (s->counting)
        s->caustic_reads = s->caustic.n_points > 0 ? s->caustic.filter_reads : -1.0;
}

int lm_pass_work(void *self, gk_pass_work *out, int max)
{
    const lm_state *s = self;
    int n = 0;
    if (s->compose_lookups.counted && s->compose_lookups.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_compose", .kind = "tex2d_rgba16f_trilinear",
                                  .fetches = s->compose_lookups.value[0]};
    if (s->caustic_reads > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.lightmap_caustic_filter", .kind = "tex2d_r16f_nearest",
                                  .fetches = s->caustic_reads};
    return n;
}

void lm_work_free(lm_state *s) { gk_counters_free(&s->compose_lookups); }
