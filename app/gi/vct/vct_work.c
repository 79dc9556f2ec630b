/* The cone-trace pass's work (#21, app/gl/pass_work.h): how many voxel fetches vct_trace needs.
 * A cone sample reads the pre-integrated map once with isotropic mips; with anisotropic ones it
 * reads the three directional views its direction sees, and below lod 1 also the isotropic
 * level 0 it blends with them (vct/cone_lib.glsl): 4 fetches, 3 from lod 1 on. How many samples a
 * cone takes depends on the voxels (it stops at opacity 0.99 and at the volume's border), so the
 * pass counts them (vct/trace.comp Counters) and the bench reads the count; the model below, a
 * replay of the step loop in open space, is what a cone costs when only its length stops it --
 * the bound the count is checked against (tests/gpu/test_vct.c).
 * The injection (vct_inject, frames that re-light the voxels) reads the light's 32-bit depth map 9
 * times (3x3 PCF) per occupied voxel and shadowed light whose lookup lands in the map: which voxels
 * are occupied and where they project is data, so inject.comp counts them (INJECT_COUNT_FETCHES)
 * in the bench's untimed counting frame; its scratch-buffer reads and image stores have no
 * roofline kind and are not counted (tests/gpu/test_vct_inject.c: 9 per occupied voxel when the
 * light's map covers the scene).
 * The voxelizer (vct_voxelize, frames that voxelize) is bound by its atomics into the scratch
 * buffer: per voxel a triangle writes, one per channel (the count and three components each of
 * albedo, normal and position, + emission: 10 or 13; the thesis's compare-and-swap averages 3 or
 * 4), at the roofline's atomic kind. Which voxels a triangle overlaps is geometry, so
 * voxelize.comp counts them (VOXELIZE_COUNT_ATOMICS) in the counting frame; the clear pass and the
 * triangles' reads are not counted (tests/gpu/test_vct_inject.c: 10 x the scratch's count channel).
 * The compose (vct_compose) upsamples the traced light: per pixel a G-buffer depth read for its
 * background test, then at trace_scale 1 its own diffuse and specular texels, below 1 for each of
 * its 3x3 low-resolution taps a depth read of the tap's traced pixel and, where that is a surface,
 * the tap's 2 texels. Which taps are surfaces is data, so compose.frag counts them
 * (VCT_COMPOSE_COUNT_FETCHES) in the counting frame: the texels as the unfiltered kind (RGBA16F,
 * half its texels' bytes), the depth reads as the depth kind; the normal and position
 * reconstruction's reads and the material's are not counted (tests/gpu/test_vct_inject.c: a view
 * filled by the floor, 2 + 1 a pixel at scale 1, 18 + 10 at 0.5).
 * The second bounce (vct_bounce, vct_bounces=2, frames that re-light the voxels) gathers the trace's
 * cone set from every voxel with a normal: its samples, counted by bounce.comp (BOUNCE_COUNT_STEPS)
 * as the trace's are, become fetches by the trace's rule; the anisotropic mips it rebuilds after are
 * the vct_mips model's loads (tests/gpu/test_vct.c: exactly voxels x gk_vct_trace_model on a lone
 * floor where nothing stops a cone, bounded by it where the volume's border does). The voxels'
 * level-0 and scratch reads are not counted. */
#include <math.h>

#include "vct_internal.h"

double gk_vct_trace_fetches(bool aniso, bool aniso_level0, double fine, double coarse)
{
    if (!aniso)
        return fine + coarse;
    return (aniso_level0 ? 3.0 : 4.0) * fine + 3.0 * coarse;
}

/* vct/cone_lib.glsl trace_cone without the opacity and border tests, in float as the shader: the
 * receiver's tangent plane is the cone's only geometry, the apex u_apex_offset voxels above it. */
void gk_vct_cone_samples(const gk_vct_cone_model *m, bool aniso, int *fine, int *coarse)
{
    float res = (float)m->res, vs = 1.0f / res, dst = 0.0f, diam = 0.0f;
    float h0 = m->apex_offset / res;
    *fine = *coarse = 0;
    for (int it = 0; it < 8192; it++) {
        if (dst > m->max_dist)
            break;
        float ds = diam;
        if (m->footprint_clamp > 0.0f)
            ds = fminf(ds, m->footprint_clamp * fmaxf(h0 + dst * m->cos_n, 0.0f));
        float lod = fmaxf(log2f(ds * res), 0.0f);
        float step_len = fmaxf(ds * m->step_mul, vs);
        /* aniso: the first loop ends at lod 1 and the second goes on from the same place */
        if (aniso && lod >= 1.0f)
            ++*coarse;
        else
            ++*fine;
        dst += step_len;
        diam = dst * m->aperture;
    }
}

void gk_vct_trace_model(int cones, int res, float step_mul, bool aniso, const gk_vct_options *o, double *fine,
                        double *coarse)
{
    float dir[VCT_MAX_CONES][3], ap[VCT_MAX_CONES], w[VCT_MAX_CONES];
    int n = vct_cone_set(cones, o->faithful_weights, dir, ap, w);
    *fine = *coarse = 0.0;
    for (int k = 0; k < n; k++) {
        gk_vct_cone_model m = {.res = res, .aperture = ap[k], .step_mul = step_mul, .apex_offset = o->apex_offset,
                               .max_dist = o->max_dist, .footprint_clamp = o->footprint_clamp, .cos_n = dir[k][1]};
        int f, c;
        gk_vct_cone_samples(&m, aniso, &f, &c);
        *fine += f;
        *coarse += c;
    }
}

double gk_vct_mip_fetches(int res, int levels, bool aniso_level0)
{
    double texels = 0.0;
    for (int l = 1; l < levels; l++)
        texels += (double)(res >> l) * (res >> l) * (res >> l);
    return 6.0 * 8.0 * texels + (aniso_level0 ? 6.0 * res * res * res : 0.0);
}

const char *vct_work_inject_begin(gk_vct *v, bool count_work)
{
    v->inject_fetches.n = 1;
    v->inject_fetches.binding = 2; /* vct/inject.comp InjectFetches */
    return gk_counters_begin(&v->inject_fetches, count_work) ? "#define INJECT_COUNT_FETCHES 1\n" : "";
}

void vct_work_inject_end(gk_vct *v) { gk_counters_end(&v->inject_fetches); }

const char *vct_work_compose_begin(gk_vct *v, bool count_work)
{
    const char *d = gk_counters_variant(&v->compose_fetches, count_work, 2, 6, "#define VCT_COMPOSE_COUNT_FETCHES 1\n");
    return d ? d : "";
}

void vct_work_compose_end(gk_vct *v) { gk_counters_end(&v->compose_fetches); }

const char *vct_work_bounce_begin(gk_vct *v)
{
    v->bounce_ran = true;
    const char *d = gk_counters_variant(&v->bounce_steps, v->count_work, 3, 2, "#define BOUNCE_COUNT_STEPS 1\n");
    return d ? d : "";
}

void vct_work_bounce_end(gk_vct *v) { gk_counters_end(&v->bounce_steps); }

const char *vct_work_voxelize_begin(gk_vct *v)
{
    v->voxelize_atomics.n = 1;
    v->voxelize_atomics.binding = 2; /* vct/voxelize.comp VoxelizeAtomics */
    return gk_counters_begin(&v->voxelize_atomics, v->count_work) ? "#define VOXELIZE_COUNT_ATOMICS 1\n" : "";
}

void vct_work_voxelize_end(gk_vct *v) { gk_counters_end(&v->voxelize_atomics); }

void vct_work_free(gk_vct *v)
{
    gk_counters_free(&v->inject_fetches);
    gk_counters_free(&v->voxelize_atomics);
    gk_counters_free(&v->compose_fetches);
    gk_counters_free(&v->bounce_steps);
}

/* gk_gi_method.pass_work: the trace's counted samples as fetches of the RGBA16F voxel textures, and
   in a frame that rebuilt them, the voxelizer's counted atomics, the injection's counted shadow
   fetches and the anisotropic mips' image loads (the isotropic chain is the
   driver's glGenerateMipmap: no model). */
int vct_pass_work(void *self, gk_pass_work *out, int max)
{
    const gk_vct *v = self;
    gk_vct_stats s;
    gk_vct_get_stats(self, &s);
    int n = 0;
    if (s.trace_runs > 0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vct_trace", .kind = "tex3d_rgba16f_trilinear",
                                  .fetches = gk_vct_trace_fetches(s.aniso, s.aniso_level0, (double)s.last_trace_fine_steps,
                                                                  (double)(s.last_trace_steps - s.last_trace_fine_steps))};
    if (v->voxelize_ran && v->voxelize_atomics.counted && v->voxelize_atomics.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vct_voxelize", .kind = "ssbo_r32ui_atomic",
                                  .fetches = v->voxelize_atomics.value[0]};
    if (v->inject_ran && v->inject_fetches.counted && v->inject_fetches.value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vct_inject", .kind = "tex2d_depth32f_nearest",
                                  .fetches = v->inject_fetches.value[0]};
    if (v->mips_ran && v->cur.aniso && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vct_mips", .kind = "image3d_rgba16f_load",
                                  .fetches = gk_vct_mip_fetches(v->res, v->levels, v->cur.aniso_level0)};
    /* the second bounce: its cones' samples as the trace's fetches, then the mips it rebuilds */
    const gk_counters *bs = &v->bounce_steps;
    if (v->bounce_ran && bs->counted && bs->value[2] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vct_bounce", .kind = "tex3d_rgba16f_trilinear",
                                  .fetches = gk_vct_trace_fetches(v->cur.aniso, v->cur.aniso_level0, bs->value[0], bs->value[1])};
    if (v->bounce_ran && bs->counted && v->cur.aniso && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vct_bounce", .kind = "image3d_rgba16f_load",
                                  .fetches = gk_vct_mip_fetches(v->res, v->levels, v->cur.aniso_level0)};
    /* the compose's low-resolution texels (RGBA16F, unfiltered) and its background tests' depth reads */
    const gk_counters *c = &v->compose_fetches;
    if (c->counted && c->value[0] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vct_compose", .kind = "tex2d_rgba32f_nearest", .fetches = c->value[0]};
    if (c->counted && c->value[1] > 0.0 && n < max)
        out[n++] = (gk_pass_work){.pass = "gi.vct_compose", .kind = "tex2d_depth32f_nearest", .fetches = c->value[1]};
    return n;
}
