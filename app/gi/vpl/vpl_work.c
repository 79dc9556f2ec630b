/* The gather's work (#21, app/gl/pass_work.h): how many fetches vpl_gather needs. Per pixel of the
 * indirect buffer its VPL subset (n / block² VPLs) is read from the VPL table (2 fetches, a third
 * for a VPL that can light it), and each VPL that faces the pixel asks its VAL's visibility: 4
 * table fetches, then by the visibility in use 1 R16F depth texel (exact), 2 RGBA8 + 3 16-bit lookups
 * plus 2 more RGBA8 where the search kernel found blockers (CSSM), 2 moment lookups (VSM), none
 * (vpl_vis=none). That depends on the data (which VPLs face which pixels, where blockers are), so
 * the gather counts it in the bench's counting frame (vpl/gather.frag GATHER_COUNT_FETCHES) and the
 * bench reads the count. The multi-resolution gather (vpl_gather=multires) runs the same loop over
 * all n VPLs once per region it shades, at every level: its levels count into the same counters
 * (tests/gpu/test_vpl_work.c: regions x the per-pixel count of the dense interleaved gather); its
 * min-max mips, region tests and interpolation are not counted.
 * The VAL maps (vpl_valsm) are rasterized, not fetched: their work is fragments, at the roofline's
 * fill rate. How many the depth draws make depends on where the proxy geometry projects in each
 * paraboloid (and what the negative half-space discards costs as much), so val_depth.frag counts
 * them (VAL_COUNT_FRAGMENTS, one atomic add per fragment in the same untimed frame); the CSSM/VSM
 * basis pass is one full-screen triangle per map, res² fragments each, added from the parameters.
 * The mips (glGenerateMipmap of the basis or moment chains, and CSSM's depth) are modelled from the
 * parameters as one bilinear lookup of level l - 1 per texel of level l >= 1 of each map in use
 * (vpl_work_maps_mips), by the chain's format: RGBA8 (CSSM's cos/sin bases), 16-bit (its z bases,
 * depth, and VSM's moments, RG32F ones included). The driver mips every allocated layer
 * (GK_VPL_MAX_M), so the efficiency shows that waste. tests/gpu/test_vpl_work.c replays the depth
 * draws' rasterization on the CPU and hand-counts the mips.
 * With vpl_umbra on or plane the same pass reduces the chain of maxima the deep-umbra test reads
 * (val_zmax.frag; its level 0 and the plane target are written by the depth draws' fragments,
 * counted above): each texel of level 1 reads the 4x4 level-0 texels around its children, but those
 * on the paraboloid disc's rim, which it takes as left out without a fetch; each texel of a coarser
 * level its 4 children. RG16F texelFetches, the roofline's 16-bit unfiltered kind (as the gather's
 * reads of the same chain). Which texels the rim leaves out depends on the map's size alone, so the
 * reads are modelled from it (vpl_zmax_reads); tests/gpu/test_vpl_work.c checks them against the
 * shader's counting variant (ZMAX_COUNT_FETCHES).
 * The geometry-aware blur (vpl_blur) and the compose (vpl_compose) read the indirect-resolution
 * targets (RGBA32F, or RGBA16F without float render targets), unfiltered: the blur per pixel its
 * position (and normal where it is a surface), per tap inside the image its position, then its
 * normal where it is a surface, then its irradiance where the normals agree (and last frame's
 * result where the cross-fade mixes it in); the compose per shaded pixel its 2x2 upsample taps'
 * positions, and their normals and irradiance where they are surfaces. Which taps pass the tests
 * depends on the data, so blur.frag and compose.frag count them (BLUR_COUNT_FETCHES,
 * VPL_COMPOSE_COUNT_FETCHES) in the same untimed frame; the compose's G-buffer reads are not
 * counted. tests/gpu/test_vpl_work.c replays the blur's taps over the targets read back and
 * hand-counts the compose's 12 a pixel inside the box.
 * The RSMs (vpl_rsm) are rasterized: rsm.frag counts its fragments (RSM_COUNT_FRAGMENTS, every face
 * of every light, hidden and discarded ones included), at the roofline's fill rate; the VPL
 * generation then reads 3 RSM texels a VPL (vpl_gen.frag, from the parameters), unfiltered. The
 * VPLs' read-back to the CPU in the same pass is not counted. tests/gpu/test_vpl_work.c hand-counts
 * both on the harness's box (one face filled by its walls: 128² fragments, 3 n texels). */
#include <math.h>

#include "vpl_internal.h"

const char *vpl_work_begin(vpl_state *s, const gk_gi_frame *f)
{
    s->gather_fetches.n = 4;
    s->gather_fetches.binding = 6; /* vpl/gather.frag GatherFetches */
    return gk_counters_begin(&s->gather_fetches, f->count_work) ? "#define GATHER_COUNT_FETCHES 1\n" : "";
}

void vpl_work_end(vpl_state *s) { gk_counters_end(&s->gather_fetches); }

const char *vpl_work_maps_begin(vpl_state *s, const gk_gi_frame *f)
{
    s->map_mip_lookups[0] = s->map_mip_lookups[1] = 0.0;
    s->map_zmax_reads = 0.0;
    s->zmax_fetches.counted = false; /* a frame without the chain counts none */
    s->map_fragments.n = 1;
    s->map_fragments.binding = 6; /* vpl/val_depth.frag ValFragments (the gather's comes later) */
    return gk_counters_begin(&s->map_fragments, f->count_work) ? "#define VAL_COUNT_FRAGMENTS 1\n" : "";
}

void vpl_work_maps_end(vpl_state *s, long basis_fragments)
{
    gk_counters_end(&s->map_fragments);
    s->map_basis_fragments = basis_fragments;
}

void vpl_work_maps_mips(vpl_state *s, int res, int layers, int rgba8, int f16)
{
    double texels = 0.0;
    for (int r = res / 2; r >= 1; r /= 2)
        texels += (double)r * r;
    s->map_mip_lookups[0] = texels * layers * rgba8;
    s->map_mip_lookups[1] = texels * layers * f16;
}

/* val_zmax.frag's on_rim, in float as the shader computes it: texel p of a size² level 0 (clamped
   to the map, as its at()) holds no direction the map can be trusted in */
static bool zmax_on_rim(int px, int py, int size)
{
    px = px < 0 ? 0 : px >= size ? size - 1 : px;
    py = py < 0 ? 0 : py >= size ? size - 1 : py;
    float sx = ((float)px + 0.5f) / (float)size * 2.0f - 1.0f;
    float sy = ((float)py + 0.5f) / (float)size * 2.0f - 1.0f;
    return sqrtf(sx * sx + sy * sy) + sqrtf(2.0f) / (float)size > 1.0f;
}

double vpl_zmax_reads(int res)
{
    double reads = 0.0;
    for (int y = 0; y < res / 2; y++)
        for (int x = 0; x < res / 2; x++)
            for (int j = -1; j < 3; j++)
                for (int i = -1; i < 3; i++)
                    reads += zmax_on_rim(2 * x + i, 2 * y + j, res) ? 0.0 : 1.0;
    for (int r = res / 4; r >= 1; r /= 2)
        reads += 4.0 * r * r;
    return reads;
}

/* One counter at binding 6 (val_zmax.frag's ZmaxFetches) */
const char *vpl_work_zmax_begin(vpl_state *s, bool counting)
{
    return gk_counters_variant(&s->zmax_fetches, counting, 1, 6, "#define ZMAX_COUNT_FETCHES 1\n");
}

void vpl_work_zmax_end(vpl_state *s, int res, int layers)
{
    gk_counters_end(&s->zmax_fetches);
    if (s->map_fragments.counting)
        s->map_zmax_reads = vpl_zmax_reads(res) * layers;
}

/* One counter at binding 6 (blur.frag's and compose.frag's block) each. */
const char *vpl_work_blur_begin(vpl_state *s, const gk_gi_frame *f)
{
    return gk_counters_variant(&s->blur_fetches, f->count_work, 1, 6, "#define BLUR_COUNT_FETCHES 1\n");
}

void vpl_work_blur_end(vpl_state *s) { gk_counters_end(&s->blur_fetches); }

const char *vpl_work_compose_begin(vpl_state *s, const gk_gi_frame *f)
{
    return gk_counters_variant(&s->compose_fetches, f->count_work, 1, 6, "#define VPL_COMPOSE_COUNT_FETCHES 1\n");
}

void vpl_work_compose_end(vpl_state *s) { gk_counters_end(&s->compose_fetches); }

/* One counter at binding 6 (rsm.frag's block); the generation's reads from the parameters. */
const char *vpl_work_rsm_begin(vpl_state *s, const gk_gi_frame *f)
{
    s->rsm_gen_reads = 0.0;
    return gk_counters_variant(&s->rsm_fragments, f->count_work, 1, 6, "#define RSM_COUNT_FRAGMENTS 1\n");
}

void vpl_work_rsm_gen(vpl_state *s, int count)
{
    if (s->rsm_fragments.counting) /* vpl_gen.frag: position, normal, flux, one texel each a VPL */
        s->rsm_gen_reads += 3.0 * count;
}

void vpl_work_rsm_end(vpl_state *s) { gk_counters_end(&s->rsm_fragments); }

int vpl_pass_work(void *self, gk_pass_work *out, int max)
{
    const vpl_state *s = self;
    /* the VPL and VAL tables are RGBA32F, read unfiltered; CSSM's cos/sin bases RGBA8 and its z
       bases, depth and VSM's moments 16-bit float, all filtered between mips; exact visibility's
       paraboloid depths R16F, unfiltered */
    static const char *const kinds[4] = {"tex2d_rgba32f_nearest", "tex2d_rgba8_trilinear", "tex2d_rgba16f_trilinear",
                                         "tex2d_r16f_nearest"};
    int n = 0;
    /* the RSMs' fragments (every light's faces' draws, hidden and discarded ones included), then the
       generation's RSM texels (RGBA16F or RGBA32F targets, unfiltered) */
    if (s->rsm_fragments.counted && s->rsm_fragments.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vpl_rsm", .kind = "raster_r16f_depth_fill", .fetches = s->rsm_fragments.value[0]};
    if (s->rsm_fragments.counted && s->rsm_gen_reads > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vpl_rsm", .kind = "tex2d_rgba32f_nearest", .fetches = s->rsm_gen_reads};
    for (int k = 0; k < 4 && s->gather_fetches.counted; k++)
        if (s->gather_fetches.value[k] > 0.0 && n < max)
            out[n++] = (gk_pass_work){.pass = "gi.vpl_gather", .kind = kinds[k], .fetches = s->gather_fetches.value[k]};
    double fragments = s->map_fragments.value[0] + (double)s->map_basis_fragments;
    if (s->map_fragments.counted && fragments > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vpl_valsm", .kind = "raster_r16f_depth_fill", .fetches = fragments};
    static const char *const mip_kinds[2] = {"tex2d_rgba8_trilinear", "tex2d_rgba16f_trilinear"};
    for (int k = 0; k < 2 && s->map_fragments.counted; k++)
        if (s->map_mip_lookups[k] > 0.0 && n < max)
            out[n++] = (gk_pass_work){.pass = "gi.vpl_valsm", .kind = mip_kinds[k], .fetches = s->map_mip_lookups[k]};
    if (s->map_fragments.counted && s->map_zmax_reads > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vpl_valsm", .kind = "tex2d_r16f_nearest", .fetches = s->map_zmax_reads};
    if (s->blur_fetches.counted && s->blur_fetches.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vpl_blur", .kind = "tex2d_rgba32f_nearest", .fetches = s->blur_fetches.value[0]};
    if (s->compose_fetches.counted && s->compose_fetches.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vpl_compose", .kind = "tex2d_rgba32f_nearest",
                                  .fetches = s->compose_fetches.value[0]};
    return n;
}

void vpl_work_free(vpl_state *s)
{
    gk_counters_free(&s->gather_fetches);
    gk_counters_free(&s->map_fragments);
    gk_counters_free(&s->blur_fetches);
    gk_counters_free(&s->compose_fetches);
    gk_counters_free(&s->rsm_fragments);
    gk_counters_free(&s->zmax_fetches);
}
