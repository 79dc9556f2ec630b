/* The gather's work (#21, app/gl/pass_work.h): how many fetches vpl_gather needs. Per pixel of the
 * indirect buffer its VPL subset (n / block² VPLs) is read from the VPL table (2 fetches, a third
 * for a VPL that can light it), and each VPL that faces the pixel asks its VAL's visibility: 4
 * table fetches, then by the visibility in use 1 depth texel (exact), 2 RGBA8 + 3 16-bit lookups
 * plus 2 more RGBA8 where the search kernel found blockers (CSSM), 2 moment lookups (VSM), none
 * (vpl_vis=none). That depends on the data (which VPLs face which pixels, where blockers are), so
 * the gather counts it in the bench's counting frame (vpl/gather.frag GATHER_COUNT_FETCHES, the
 * interleaved gather only) and the bench reads the count. The VAL maps (vpl_valsm) are rasterized,
 * not fetched: no model. */
#include "vpl_internal.h"

const char *vpl_work_begin(vpl_state *s, const gk_gi_frame *f)
{
    s->gather_fetches.n = 3;
    s->gather_fetches.binding = 6; /* vpl/gather.frag GatherFetches */
    return gk_counters_begin(&s->gather_fetches, f->count_work) ? "#define GATHER_COUNT_FETCHES 1\n" : "";
}

void vpl_work_end(vpl_state *s) { gk_counters_end(&s->gather_fetches); }

int vpl_pass_work(void *self, gk_pass_work *out, int max)
{
    const vpl_state *s = self;
    /* the VPL and VAL tables are RGBA32F, read unfiltered; CSSM's cos/sin bases RGBA8 and its z
       bases, depth and VSM's moments 16-bit float, all filtered between mips */
    static const char *const kinds[3] = {"tex2d_rgba32f_nearest", "tex2d_rgba8_trilinear", "tex2d_rgba16f_trilinear"};
    int n = 0;
    for (int k = 0; k < 3 && s->gather_fetches.counted; k++)
        if (s->gather_fetches.value[k] > 0.0 && n < max)
            out[n++] = (gk_pass_work){.pass = "gi.vpl_gather", .kind = kinds[k], .fetches = s->gather_fetches.value[k]};
    return n;
}

void vpl_work_free(vpl_state *s) { gk_counters_free(&s->gather_fetches); }
