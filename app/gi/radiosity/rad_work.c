/* The radiosity method's GPU passes' work (#21, app/gl/pass_work.h):
 *   radiosity_bounce: per bounce every leaf gathers the unshot radiance of the nodes its links name
 *     (radiosity/gather.comp), one vec4 storage-buffer load per link, at the roofline's
 *     storage-buffer kind. The links are the worker's published set (rad_links.h), so the count is
 *     bounces x links, from the parameters: nothing to count on the GPU. The link records' own loads
 *     (uvec2, beside the radiance they name), the pull-up's children and the publication's image
 *     stores are not counted. tests/gpu/test_radiosity.c checks the count against the CPU oracle's
 *     own link set.
 *   radiosity_display: the mesh drawn over the screen without depth test or culling (each fragment
 *     then tests the G-buffer's depth itself, radiosity/display.frag), so the pass is bound by the
 *     raster: every fragment the draw rasterizes, hidden and discarded ones included, at the
 *     roofline's fill rate. Which pixels the mesh covers depends on the view, so a variant of the
 *     pass counts them (DISPLAY_COUNT_FRAGMENTS) in the bench's untimed counting frame.
 *     tests/gpu/test_radiosity_work.c checks the count against the pixels a CPU count of the
 *     G-buffer finds a lone floor in (the mesh's one layer). Its G-buffer reads are not counted. */
#include "rad_internal.h"

const char *rad_work_display_begin(rad_state *s, const gk_gi_frame *f)
{
    /* radiosity/display.frag DisplayFragments */
    return gk_counters_variant(&s->display_fragments, f->count_work, 1, 6, "#define DISPLAY_COUNT_FRAGMENTS 1\n");
}

void rad_work_display_end(rad_state *s) { gk_counters_end(&s->display_fragments); }

int rad_pass_work(void *self, gk_pass_work *out, int max)
{
    const rad_state *s = self;
    int n = 0;
    if (s->st.bounces > 0 && s->gpu.link_count > 0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.radiosity_bounce", .kind = "ssbo_rgba32f_load",
                                  .fetches = (double)s->st.bounces * (double)s->gpu.link_count};
    if (s->display_fragments.counted && s->display_fragments.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.radiosity_display", .kind = "raster_r16f_depth_fill",
                                  .fetches = s->display_fragments.value[0]};
    return n;
}
