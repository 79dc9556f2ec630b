/* What the bench divides by a pass's time (#21, app/gl/pass_work.h): the renderer's own passes'
 * useful fetches, and the GI method's. The direct pass's shadow lookups depend on the data (PCSS
 * shrinks its PCF grid with the penumbra, VSSM subdivides kernels that straddle depths), so they
 * are counted: a counting variant of the lighting pass (SHADOW_COUNT_FETCHES, shaders_gles/shadow/
 * common.glsl) adds each pixel's fetches to a storage buffer, in frames the bench does not time. */
#include "gl/gl_counters.h"
#include "render_gi.h"
#include "renderer_internal.h"

bool gk_renderer_count_work(gk_renderer *r, bool on)
{
    r->count_work = on && gk_counters_in_fragment_shaders();
    return r->count_work || !on;
}

const char *gk_render_work_begin(gk_renderer *r)
{
    r->shadow_fetches.n = 5;
    r->shadow_fetches.binding = 6; /* direct/light.frag ShadowFetches */
    return gk_counters_begin(&r->shadow_fetches, r->count_work) ? "#define SHADOW_COUNT_FETCHES 1\n" : "";
}

void gk_render_work_end(gk_renderer *r) { gk_counters_end(&r->shadow_fetches); }

void gk_render_work_destroy(gk_renderer *r) { gk_counters_free(&r->shadow_fetches); }

int gk_renderer_pass_work(const gk_renderer *r, const char *method, gk_pass_work *out, int max)
{
    int n = 0;
    /* by the format read, in the order of direct/light.frag's ShadowFetches: the 32-bit depth map,
       R32F min/max mips and CSSM's range, R32UI SATs, CSSM_SAT's RGBA32UI bases (16-byte texels
       as RGBA32F's), all unfiltered; CSSM's mipmapped RGBA16F bases */
    static const char *const kinds[5] = {"tex2d_depth32f_nearest", "tex2d_r32f_nearest", "tex2d_r32ui_nearest",
                                         "tex2d_rgba32f_nearest", "tex2d_rgba16f_trilinear"};
    for (int k = 0; k < 5 && r->shadow_fetches.counted; k++)
        if (r->shadow_fetches.value[k] > 0.0 && n < max)
            out[n++] = (gk_pass_work){.pass = "direct", .kind = kinds[k], .fetches = r->shadow_fetches.value[k]};
    return n + gk_render_gi_pass_work(r->gi, method, out + n, max - n);
}
