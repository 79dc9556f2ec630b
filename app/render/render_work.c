/* What the bench divides by a pass's time (#21, app/gl/pass_work.h): the renderer's own passes'
 * useful work, and the GI method's. Each is counted by a counting variant of its pass's shader that
 * adds to a storage buffer, in frames the bench does not time:
 *   shadow.shadow_depth (DEPTH_COUNT_FRAGMENTS, shadow/depth.frag): the shadow maps' depth draws'
 *     fragments, every face of every shadowed light's map (the environment's lights' too), drawn
 *     without face culling, occluded and alpha-masked ones included, at the roofline's fill rate
 *     (a depth-only fill writes no colour: it can read above the kind's limit). Only frames that
 *     render the maps count: a static scene's kiosk frames reuse them (render_frame.c), so the bench
 *     counts them where it re-renders them (a shadow sweep, --rebuild-gi).
 *   shadow.vssm_prefilter, shadow.cssm_prefilter: VSSM's and CSSM's compute passes over those
 *     maps (and CSSM's mipmaps), from their parameters (app/render/shadow/shadow_prefilter_work.h),
 *     added in the same frames.
 *   gbuffer (GBUFFER_COUNT_FRAGMENTS, gbuffer/gbuffer.frag): the draws' fragments, every fragment
 *     rasterized after face culling (occluded and alpha-masked ones included: with the atomic the
 *     depth test runs after the shader), at the roofline's fill rate. The pass is bound by the
 *     raster and its 4-5 render targets' writes; its material texture fetches are not counted.
 *   direct: the shadow lookups depend on the data (PCSS shrinks its PCF grid with the penumbra,
 *     VSSM subdivides kernels that straddle depths), so SHADOW_COUNT_FETCHES (shaders_gles/shadow/
 *     common.glsl) counts them per format.
 *   glass (GLASS_COUNT_FETCHES, glass/refract.frag): per glass fragment rasterized (hidden ones
 *     included) its read of the opaque scene's depth, and for each one in front of the opaque scene
 *     its two bilinear lookups of the image behind (bent and unbent), plus the copy of that image
 *     into the glass target the pass starts with, one lookup a pixel (from the render size): the
 *     draws' vertex work and blending are not counted.
 *   gi.blend_hold, gi.blend (the GI cross-fade, render_gi_blend.c), from the render size: the copy
 *     of the image before GI, a blit of one RGBA16F texel a pixel (unfiltered: the roofline's
 *     unfiltered kind, whose 16-byte texels are twice these), and during a transition the blend's
 *     three bilinear lookups a pixel (the image before GI, the new one and the held contribution);
 *     at a transition's first frame the hold of the last frame's GI contribution, two bilinear
 *     lookups (the image shown and the one before GI) a pixel of the last frame's render size, in
 *     gi.blend_hold beside the copy's texels.
 *   gi.occlusion (render_gi_occlusion.c), from the render size: per pixel the G-buffer depth read of
 *     its background test and the pre-GI image's texel; its ao reads are not counted.
 *   blend (BLEND_COUNT_FRAGMENTS, blend/forward.frag): the alpha-blended meshes' fragments, every
 *     draw (the ambient one and one per light), hidden ones included, at the roofline's fill rate.
 *   compose (HDR_COUNT_FETCHES, compose/compose.frag): one bilinear lookup of the RGBA16F HDR
 *     image per output pixel, the upsample when render_scale < 1 -- a constant of the output size,
 *     counted all the same so that a test holds the pass to it (tests/gpu/test_render_work.c).
 * The GBuffer and HDR counters sit on binding 6 as the shadow counters do: one pass at a time. */
#include "gl/gl_counters.h"
#include "render_gi.h"
#include "renderer_internal.h"

bool gk_renderer_count_work(gk_renderer *r, bool on)
{
    r->count_work = on && gk_counters_in_fragment_shaders();
    return r->count_work || !on;
}

/* Zeroes and binds c (n counters at binding 6) when this frame counts: the define of its pass's
   counting variant, else "". */
static const char *count_begin(gk_counters *c, bool on, int n, const char *define)
{
    const char *d = gk_counters_variant(c, on, n, 6, define);
    return d ? d : "";
}

const char *gk_render_work_begin(gk_renderer *r)
{
    return count_begin(&r->shadow_fetches, r->count_work, 5, "#define SHADOW_COUNT_FETCHES 1\n");
}

void gk_render_work_end(gk_renderer *r) { gk_counters_end(&r->shadow_fetches); }

const char *gk_render_work_shadow_begin(gk_renderer *r)
{
    r->prefilter_work = (gk_pf_frame_work){0}; /* a frame that keeps its maps prefilters nothing */
    r->occlusion_pixels = 0.0;                 /* the frame's first pass: nothing occluded yet */
    return count_begin(&r->depth_fragments, r->count_work, 1, "#define DEPTH_COUNT_FRAGMENTS 1\n");
}

void gk_render_work_shadow_end(gk_renderer *r) { gk_counters_end(&r->depth_fragments); }

const char *gk_render_work_gbuffer_begin(gk_renderer *r)
{
    return count_begin(&r->gbuffer_fragments, r->count_work, 1, "#define GBUFFER_COUNT_FRAGMENTS 1\n");
}

void gk_render_work_gbuffer_end(gk_renderer *r) { gk_counters_end(&r->gbuffer_fragments); }

const char *gk_render_work_glass_begin(gk_renderer *r)
{
    return count_begin(&r->glass_fetches, r->count_work, 2, "#define GLASS_COUNT_FETCHES 1\n");
}

void gk_render_work_glass_end(gk_renderer *r, long copy_lookups)
{
    gk_counters_end(&r->glass_fetches);
    r->glass_copy_lookups = copy_lookups;
}

const char *gk_render_work_compose_begin(gk_renderer *r)
{
    return count_begin(&r->compose_fetches, r->count_work, 1, "#define HDR_COUNT_FETCHES 1\n");
}

void gk_render_work_compose_end(gk_renderer *r) { gk_counters_end(&r->compose_fetches); }

const char *gk_render_work_blend_begin(gk_renderer *r)
{
    return count_begin(&r->blend_fragments, r->count_work, 1, "#define BLEND_COUNT_FRAGMENTS 1\n");
}

void gk_render_work_blend_end(gk_renderer *r) { gk_counters_end(&r->blend_fragments); }

void gk_render_work_destroy(gk_renderer *r)
{
    gk_counters_free(&r->depth_fragments);
    gk_counters_free(&r->gbuffer_fragments);
    gk_counters_free(&r->shadow_fetches);
    gk_counters_free(&r->compose_fetches);
    gk_counters_free(&r->glass_fetches);
    gk_counters_free(&r->blend_fragments);
}

/* Appends c's first counter as pass/kind when it counted some. */
static int add_counted(const gk_counters *c, const char *pass, const char *kind, gk_pass_work *out, int n, int max)
{
    if (c->counted && c->value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = pass, .kind = kind, .fetches = c->value[0]};
    return n;
}

int gk_renderer_pass_work(const gk_renderer *r, const char *method, gk_pass_work *out, int max)
{
    int n = add_counted(&r->depth_fragments, "shadow.shadow_depth", "raster_r16f_depth_fill", out, 0, max);
    /* VSSM's and CSSM's prefilters, from their parameters (shadow_prefilter_work.h): the depth map's
       reads, the R32F depth's, the image loads (pyramid, SAT columns, CSSM's range), CSSM's mips' */
    static const char *const pf_kinds[4] = {"tex2d_depth32f_nearest", "tex2d_r32f_nearest", "image3d_rgba16f_load",
                                            "tex2d_rgba16f_trilinear"};
    const gk_pf_work *pf[2] = {&r->prefilter_work.vssm, &r->prefilter_work.cssm};
    static const char *const pf_pass[2] = {"shadow.vssm_prefilter", "shadow.cssm_prefilter"};
    for (int m = 0; m < 2; m++) {
        const double f[4] = {pf[m]->depth_reads, pf[m]->r32f_reads, pf[m]->image_loads, pf[m]->mip_lookups};
        for (int k = 0; k < 4; k++)
            if (f[k] > 0.0 && n < max)
                out[n++] = (gk_pass_work){.pass = pf_pass[m], .kind = pf_kinds[k], .fetches = f[k]};
    }
    n = add_counted(&r->gbuffer_fragments, "gbuffer", "raster_r16f_depth_fill", out, n, max);
    /* by the format read, in the order of direct/light.frag's ShadowFetches: the 32-bit depth map,
       R32F min/max mips and CSSM's range, R32UI SATs, CSSM_SAT's RGBA32UI bases (16-byte texels
       as RGBA32F's), all unfiltered; CSSM's mipmapped RGBA16F bases */
    static const char *const kinds[5] = {"tex2d_depth32f_nearest", "tex2d_r32f_nearest", "tex2d_r32ui_nearest",
                                         "tex2d_rgba32f_nearest", "tex2d_rgba16f_trilinear"};
    for (int k = 0; k < 5 && r->shadow_fetches.counted; k++)
        if (r->shadow_fetches.value[k] > 0.0 && n < max)
            out[n++] = (gk_pass_work){.pass = "direct", .kind = kinds[k], .fetches = r->shadow_fetches.value[k]};
    /* the glass target's depth reads (the G-buffer's 32-bit depth, unfiltered), then its lookups of
       the RGBA16F image behind, the copy's included (bilinear at one level: they can read above the
       trilinear kind's limit, as the compose's do) */
    const gk_counters *g = &r->glass_fetches;
    if (g->counted && g->value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "glass", .kind = "tex2d_depth32f_nearest", .fetches = g->value[0]};
    if (g->counted && g->value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "glass", .kind = "tex2d_rgba16f_trilinear",
                                  .fetches = g->value[1] + (double)r->glass_copy_lookups};
    if (r->blend.work_hold > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.blend_hold", .kind = "tex2d_rgba32f_nearest", .fetches = r->blend.work_hold};
    if (r->blend.work_capture > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.blend_hold", .kind = "tex2d_rgba16f_trilinear", .fetches = r->blend.work_capture};
    if (r->blend.work_blend > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.blend", .kind = "tex2d_rgba16f_trilinear", .fetches = r->blend.work_blend};
    /* the occlusion texture on GI: per pixel the pre-GI image's texel (RGBA16F, unfiltered) and the
       G-buffer's depth; the ao reads where a surface is are not counted */
    if (r->occlusion_pixels > 0.0 && n + 1 < max) {
        out[n++] = (gk_pass_work){.pass = "gi.occlusion", .kind = "tex2d_rgba32f_nearest", .fetches = r->occlusion_pixels};
        out[n++] = (gk_pass_work){.pass = "gi.occlusion", .kind = "tex2d_depth32f_nearest", .fetches = r->occlusion_pixels};
    }
    n = add_counted(&r->blend_fragments, "blend", "raster_r16f_depth_fill", out, n, max);
    n = add_counted(&r->compose_fetches, "compose", "tex2d_rgba16f_trilinear", out, n, max);
    return n + gk_render_gi_pass_work(r->gi, method, out + n, max - n);
}
