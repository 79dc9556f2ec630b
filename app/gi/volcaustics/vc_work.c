/* The volcaustics passes' work (#21, app/gl/pass_work.h), by the roofline's kinds:
 *   vc_light's ray generation (raygen.comp, per caustic light one invocation per light-view texel)
 *     reads the light views' depth: its own texel's, the march of the reflected or refracted ray
 *     through the depth without the specular objects (up to VC_P2_STEPS), and for glass the march
 *     and bisection through the back faces' depth. How far a ray marches is data, so the variant
 *     counts the reads (RAYGEN_COUNT_FETCHES) in the bench's untimed counting frame, as depth
 *     texels; its normal and colour reads (RGBA8) are not counted. The light views it starts from
 *     (per light the front view, the view without the specular objects and their back faces) are
 *     rasterized: their fragments, every surface in the light's frustum in each of the three views
 *     (the ones a view then discards included: the counter comes first), at the fill rate, counted
 *     by lightview.frag's variant (LIGHTVIEW_COUNT_FRAGMENTS, at binding 7: the ray generation's
 *     counter holds binding 6 across the same loop).
 *   vc_lines is rasterized: its work is the lines' fragments (each filters its line's samples
 *     onto the view ray), at the fill rate, counted by lines.frag's variant (LINES_COUNT_FRAGMENTS);
 *     so is vc_surface, the rays' ends splatted as point sprites (SURFACE_COUNT_FRAGMENTS).
 *   vc_airlight reads the G-buffer's depth once per march pixel and, per step and light whose cone
 *     holds the step's point, that light's shadow map where the point projects into it: counted by
 *     airlight.frag's variant (AIRLIGHT_COUNT_FETCHES), as depth texels.
 *   vc_composite's two full-screen draws read, per pixel, the G-buffer's depth for the attenuated
 *     surfaces (C) and again for the surface caustics, the airlight image (bilinear, RGBA16F) and
 *     the lines' image, and the surface caustics' irradiance where a surface is (unfiltered, RGBA32F
 *     or 16F), each as the terms shown (vc_output) ask: counted by composite.frag's variant
 *     (COMPOSITE_COUNT_FETCHES, three counters by kind); its G-buffer albedo reads are not counted.
 * tests/e2e/efficiency.sh checks the
 * counts against each other (each pass's count unchanged by another pass's knob) and against their
 * ceilings from the parameters; tests/gpu/test_vc_work.c the airlight's, the composite's and the
 * light views' against hand counts. */
#include "vc_internal.h"

/* Per VC_WORK_* pass: its shader variant, its counters' binding, its pass and each counter's kind. */
static const struct {
    const char *define, *pass;
    GLuint binding;
    int n;
    const char *kind[3];
} variants[VC_WORK_N] = {
    [VC_WORK_RAYGEN] = {"#define RAYGEN_COUNT_FETCHES 1\n", "gi.vc_light", 6, 1, {"tex2d_depth32f_nearest"}},
    [VC_WORK_LINES] = {"#define LINES_COUNT_FRAGMENTS 1\n", "gi.vc_lines", 6, 1, {"raster_r16f_depth_fill"}},
    [VC_WORK_SURFACE] = {"#define SURFACE_COUNT_FRAGMENTS 1\n", "gi.vc_surface", 6, 1, {"raster_r16f_depth_fill"}},
    [VC_WORK_AIRLIGHT] = {"#define AIRLIGHT_COUNT_FETCHES 1\n", "gi.vc_airlight", 6, 1, {"tex2d_depth32f_nearest"}},
    [VC_WORK_COMPOSITE] = {"#define COMPOSITE_COUNT_FETCHES 1\n", "gi.vc_composite", 6, 3,
                           {"tex2d_depth32f_nearest", "tex2d_rgba16f_trilinear", "tex2d_rgba32f_nearest"}},
    [VC_WORK_LIGHTVIEW] = {"#define LIGHTVIEW_COUNT_FRAGMENTS 1\n", "gi.vc_light", 7, 1, {"raster_r16f_depth_fill"}},
};

void vc_work_frame(vc_state *s, const gk_gi_frame *f)
{
    s->count_work = f->count_work;
    /* a pass that does not run this frame (no caustic light, no lines) reports no earlier count */
    for (int k = 0; k < VC_WORK_N; k++)
        s->work[k].counted = false;
}

const char *vc_work_begin(vc_state *s, int pass)
{
    gk_counters *c = &s->work[pass];
    c->n = variants[pass].n;
    c->binding = variants[pass].binding;
    return gk_counters_begin(c, s->count_work) ? variants[pass].define : "";
}

void vc_work_end(vc_state *s, int pass) { gk_counters_end(&s->work[pass]); }

int vc_pass_work(void *self, gk_pass_work *out, int max)
{
    const vc_state *s = self;
    int n = 0;
    for (int k = 0; k < VC_WORK_N; k++)
        for (int i = 0; i < variants[k].n; i++)
            if (s->work[k].counted && s->work[k].value[i] > 0.0 && n < max)
                out[n++] = (gk_pass_work){.pass = variants[k].pass, .kind = variants[k].kind[i],
                                          .fetches = s->work[k].value[i]};
    return n;
}

void vc_work_free(vc_state *s)
{
    for (int k = 0; k < VC_WORK_N; k++)
        gk_counters_free(&s->work[k]);
}
