/* The radiosity bounces' work (#21, app/gl/pass_work.h): per bounce every leaf gathers the unshot
 * radiance of the nodes its links name (radiosity/gather.comp), one vec4 storage-buffer load per
 * link, at the roofline's storage-buffer kind. The links are the worker's published set
 * (rad_links.h), so the count is bounces x links, from the parameters: nothing to count on the GPU.
 * The link records' own loads (uvec2, beside the radiance they name), the pull-up's children and
 * the publication's image stores are not counted. tests/gpu/test_radiosity.c checks the count
 * against the CPU oracle's own link set. The display pass (rasterized) has no model. */
#include "rad_internal.h"

int rad_pass_work(void *self, gk_pass_work *out, int max)
{
    const rad_state *s = self;
    if (s->st.bounces <= 0 || s->gpu.link_count <= 0 || max < 1)
        return 0;
    out[0] = (gk_pass_work){.pass = "gi.radiosity_bounce", .kind = "ssbo_rgba32f_load",
                            .fetches = (double)s->st.bounces * (double)s->gpu.link_count};
    return 1;
}
