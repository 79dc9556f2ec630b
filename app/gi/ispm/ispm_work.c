/* The caustic passes' work (#21, app/gl/pass_work.h): what ispm_lists, ispm_trace and ispm_splat
 * need, by the roofline kind each is bound by. All three depend on the data, so they are counted:
 *   ispm_lists (tier A, ll_build.frag): every frustum fragment takes a node with five storage-buffer
 *     atomics (the pool's counter, the head exchange, the depth range's min and max, the pixel's
 *     count); one the full pool drops takes two (the counter and the overflow count). The counter
 *     buffer already holds both numbers. Tier B's peeled layers are rasterized, not modelled.
 *   ispm_trace (trace.comp): each march step loads its pixel's list head (a 16-byte Pixel) and each
 *     node it visits one Node: the shader's own work count (ISPM_PH_STEPS, research L19), one
 *     storage-buffer load each.
 *   ispm_splat (splat.frag): fragments, at the roofline's fill rate: each splat quad's fragments,
 *     discarded or not, counted by a variant (SPLAT_COUNT_FRAGMENTS, one atomic add per fragment) in
 *     the bench's untimed counting frame. With ispm_radius=density or footprint the pass's time also
 *     holds those radii's compute passes, which are not counted.
 *   ispm_upsample (upsample.frag): the joint bilateral upsample reads, for each lit pixel, the
 *     splat texels of its 3x3 low-resolution neighbourhood that have a bilinear weight and a
 *     surface: the bilinear footprint, 1 texel at ispm_splat=1 (the pixel's own) and 4 below (2 a
 *     side; one more a side next to the screen's edge, where a tap clamped to the target gets a
 *     weight; fewer next to the background) -- unfiltered texelFetches of the RGBA32F (or RGBA16F)
 *     splat target, the roofline's RGBA32F kind for both. Which pixels are lit depends on the view,
 *     so a variant counts them (UPSAMPLE_COUNT_FETCHES). Its G-buffer reads (depth and normal per
 *     tap) are not counted, as no pass's are.
 * The lists' and the trace's numbers are read back with the frame's other counters, synchronously in
 * a counting frame (not one frame late). tests/gpu/test_ispm_work.c checks them against a hand count
 * (the lists, the upsample's taps) and CPU replays (the march, the quads' rasterization).
 * ispm_photons: the RSM is rasterized, its fragments (the scene in the light's frustum framed on the
 * specular geometry, discarded ones included) counted by rsm.frag's variant (RSM_COUNT_FRAGMENTS),
 * at the fill rate; the mask pyramid and the emission's compute passes that follow it in the same
 * pass are modelled below (tests/gpu/test_ispm_work.c replays the RSM's rasterization of the mirror).
 * The mask pyramid (mask.comp) reads the RSM's mask bit, one RGB10_A2 texel per texel of level 0,
 * then 4 counts (uint storage-buffer loads) per texel of levels 1..8, and adds one atomic per
 * block holding a specular texel at every level (the header's ph_nonzero). The emission (emit.comp)
 * runs one invocation per block of the level it picks (ph_level = l): each loads its count; each
 * block that emits (ph_count of them: any specular texel, or a full block when faithful) reads its
 * 4^l mask texels, takes a slot (an atomic; one more where the buffer is full, ph_overflow), and a
 * photon that gets a slot reads its representative texel's normal, specular and diffuse texels and
 * its depth, and one more atomic where it is reflected (ph_reflected). So the work is the header's
 * numbers and the RSM's size (ispm_photons_model); RGB10_A2 and RGBA8 texels as the roofline's
 * unfiltered 32-bit kind, the 4-byte counts against its 16-byte storage loads. The level choice's
 * header reads (every invocation repeats them) are not counted. tests/gpu/test_ispm_work.c checks
 * the model against the shaders' counting variant (PHOTONS_COUNT_FETCHES). */
#include "ispm_internal.h"

/* ll_build.frag's atomics per fragment kept in the lists and per fragment the full pool dropped */
enum { LIST_ATOMICS_KEPT = 5, LIST_ATOMICS_DROPPED = 2 };

void ispm_work_frame(ispm_state *s, const gk_gi_frame *f)
{
    s->counting = f->count_work;
    s->work_counted = false;
    s->splat_fragments.counted = false; /* a frame without splats reports none */
    s->upsample_fetches.counted = false;
    s->rsm_fragments.counted = false;
    s->photons_modelled = false; /* a frame without photons (no specular geometry) models none */
}

const char *ispm_work_splat_begin(ispm_state *s)
{
    s->splat_fragments.n = 1;
    s->splat_fragments.binding = 6; /* ispm/splat.frag SplatFragments */
    return gk_counters_begin(&s->splat_fragments, s->counting) ? "#define SPLAT_COUNT_FRAGMENTS 1\n" : NULL;
}

void ispm_work_splat_end(ispm_state *s) { gk_counters_end(&s->splat_fragments); }

const char *ispm_work_upsample_begin(ispm_state *s)
{
    /* ispm/upsample.frag UpsampleFetches */
    return gk_counters_variant(&s->upsample_fetches, s->counting, 1, 6, "#define UPSAMPLE_COUNT_FETCHES 1\n");
}

void ispm_work_upsample_end(ispm_state *s) { gk_counters_end(&s->upsample_fetches); }

const char *ispm_work_rsm_begin(ispm_state *s)
{
    /* ispm/rsm.frag RsmFragments */
    return gk_counters_variant(&s->rsm_fragments, s->counting, 1, 6, "#define RSM_COUNT_FRAGMENTS 1\n");
}

void ispm_work_rsm_end(ispm_state *s) { gk_counters_end(&s->rsm_fragments); }

const char *ispm_work_photons_begin(ispm_state *s)
{
    /* mask.comp's and emit.comp's PhotonsFetches: RSM texels, depths, loads, atomics */
    return gk_counters_variant(&s->photons_fetches, s->counting, 4, 6, "#define PHOTONS_COUNT_FETCHES 1\n");
}

void ispm_work_photons_end(ispm_state *s) { gk_counters_end(&s->photons_fetches); }

void ispm_photons_model(const unsigned *ph, int capacity, double out[4])
{
    double texels = (double)ISPM_RSM_RES * ISPM_RSM_RES, loads = 0.0, atomics = 0.0;
    for (int l = 1; l < ISPM_RSM_LEVELS; l++)
        loads += 4.0 * (double)(ISPM_RSM_RES >> l) * (ISPM_RSM_RES >> l);
    for (int l = 0; l < ISPM_RSM_LEVELS; l++)
        atomics += ph[ISPM_PH_NONZERO + l];
    unsigned level = ph[ISPM_PH_LEVEL], emitted = ph[ISPM_PH_COUNT];
    double side = (double)(ISPM_RSM_RES >> level), kept = emitted < (unsigned)capacity ? emitted : (unsigned)capacity;
    loads += side * side;
    texels += (double)emitted * (double)(1u << (2 * level)) + 3.0 * kept;
    atomics += (double)emitted + ph[ISPM_PH_OVERFLOW] + ph[ISPM_PH_REFLECTED];
    out[0] = texels, out[1] = kept, out[2] = loads, out[3] = atomics;
}

void ispm_work_photons(ispm_state *s, const unsigned *ph)
{
    if (!s->counting)
        return;
    ispm_photons_model(ph, s->capacity, s->photons_work);
    s->photons_modelled = true;
}

void ispm_work_counters(ispm_state *s, unsigned trace_loads, unsigned list_fragments, unsigned list_dropped)
{
    if (!s->counting)
        return;
    s->work_trace_loads = trace_loads;
    s->work_list_fragments = list_fragments;
    s->work_list_dropped = list_dropped;
    s->work_counted = true;
}

double ispm_list_atomics(unsigned fragments, unsigned dropped)
{
    unsigned kept = fragments > dropped ? fragments - dropped : 0u;
    return LIST_ATOMICS_KEPT * (double)kept + LIST_ATOMICS_DROPPED * (double)dropped;
}

int ispm_caustic_work(const ispm_state *s, gk_pass_work *out, int max)
{
    int n = 0;
    if (s->rsm_fragments.counted && s->rsm_fragments.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.ispm_photons", .kind = "raster_r16f_depth_fill",
                                  .fetches = s->rsm_fragments.value[0]};
    static const char *const photon_kinds[4] = {"tex2d_r32f_nearest", "tex2d_depth32f_nearest", "ssbo_rgba32f_load",
                                                "ssbo_r32ui_atomic"};
    for (int k = 0; k < 4 && s->photons_modelled; k++)
        if (s->photons_work[k] > 0.0 && n < max)
            out[n++] = (gk_pass_work){.pass = "gi.ispm_photons", .kind = photon_kinds[k], .fetches = s->photons_work[k]};
    if (!s->work_counted)
        return n;
    double atomics = ispm_list_atomics(s->work_list_fragments, s->work_list_dropped);
    if (s->tier == GK_ISPM_TIER_LISTS && atomics > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.ispm_lists", .kind = "ssbo_r32ui_atomic", .fetches = atomics};
    if (s->work_trace_loads > 0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.ispm_trace", .kind = "ssbo_rgba32f_load",
                                  .fetches = (double)s->work_trace_loads};
    if (s->splat_fragments.counted && s->splat_fragments.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.ispm_splat", .kind = "raster_r16f_depth_fill",
                                  .fetches = s->splat_fragments.value[0]};
    if (s->upsample_fetches.counted && s->upsample_fetches.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.ispm_upsample", .kind = "tex2d_rgba32f_nearest",
                                  .fetches = s->upsample_fetches.value[0]};
    return n;
}

void ispm_work_free(ispm_state *s)
{
    gk_counters_free(&s->splat_fragments);
    gk_counters_free(&s->upsample_fetches);
    gk_counters_free(&s->rsm_fragments);
    gk_counters_free(&s->photons_fetches);
}
