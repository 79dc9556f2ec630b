/* The volcaustics passes' work (#21, app/gl/pass_work.h), by the roofline's kinds:
 *   vc_light's ray generation (raygen.comp, per caustic light one invocation per light-view texel)
 *     reads the light views' depth: its own texel's, the march of the reflected or refracted ray
 *     through the depth without the specular objects (up to VC_P2_STEPS), and for glass the march
 *     and bisection through the back faces' depth. How far a ray marches is data, so the variant
 *     counts the reads (RAYGEN_COUNT_FETCHES) in the bench's untimed counting frame, as depth
 *     texels; its normal and colour reads (RGBA8) and the light views' rasterization are not counted.
 *   vc_lines is rasterized: its work is the lines' fragments (each filters its line's samples
 *     onto the view ray), at the fill rate, counted by lines.frag's variant (LINES_COUNT_FRAGMENTS);
 *     so is vc_surface, the rays' ends splatted as point sprites (SURFACE_COUNT_FRAGMENTS).
 *   vc_airlight reads the G-buffer's depth once per march pixel and, per step and light whose cone
 *     holds the step's point, that light's shadow map where the point projects into it: counted by
 *     airlight.frag's variant (AIRLIGHT_COUNT_FETCHES), as depth texels.
 * vc_composite is not modelled. tests/e2e/efficiency.sh checks the
 * counts against each other (each pass's count unchanged by another pass's knob) and against their
 * ceilings from the parameters. */
#include "vc_internal.h"

static const char *begin(gk_counters *c, bool on, const char *define)
{
    c->n = 1;
    c->binding = 6; /* the shaders' counting blocks */
    return gk_counters_begin(c, on) ? define : "";
}

void vc_work_frame(vc_state *s, const gk_gi_frame *f)
{
    s->count_work = f->count_work;
    /* a pass that does not run this frame (no caustic light, no lines) reports no earlier count */
    s->raygen_fetches.counted = s->line_fragments.counted = s->surface_fragments.counted = false;
    s->air_fetches.counted = false;
}

const char *vc_work_raygen_begin(vc_state *s)
{
    return begin(&s->raygen_fetches, s->count_work, "#define RAYGEN_COUNT_FETCHES 1\n");
}

void vc_work_raygen_end(vc_state *s) { gk_counters_end(&s->raygen_fetches); }

const char *vc_work_lines_begin(vc_state *s)
{
    return begin(&s->line_fragments, s->count_work, "#define LINES_COUNT_FRAGMENTS 1\n");
}

void vc_work_lines_end(vc_state *s) { gk_counters_end(&s->line_fragments); }

const char *vc_work_surface_begin(vc_state *s)
{
    return begin(&s->surface_fragments, s->count_work, "#define SURFACE_COUNT_FRAGMENTS 1\n");
}

void vc_work_surface_end(vc_state *s) { gk_counters_end(&s->surface_fragments); }

const char *vc_work_airlight_begin(vc_state *s)
{
    return begin(&s->air_fetches, s->count_work, "#define AIRLIGHT_COUNT_FETCHES 1\n");
}

void vc_work_airlight_end(vc_state *s) { gk_counters_end(&s->air_fetches); }

int vc_pass_work(void *self, gk_pass_work *out, int max)
{
    const vc_state *s = self;
    const struct {
        const gk_counters *c;
        const char *pass, *kind;
    } rows[4] = {
        {&s->raygen_fetches, "gi.vc_light", "tex2d_depth32f_nearest"},
        {&s->line_fragments, "gi.vc_lines", "raster_r16f_depth_fill"},
        {&s->surface_fragments, "gi.vc_surface", "raster_r16f_depth_fill"},
        {&s->air_fetches, "gi.vc_airlight", "tex2d_depth32f_nearest"},
    };
    int n = 0;
    for (int i = 0; i < 4; i++)
        if (rows[i].c->counted && rows[i].c->value[0] > 0.0 && n < max)
            out[n++] = (gk_pass_work){.pass = rows[i].pass, .kind = rows[i].kind, .fetches = rows[i].c->value[0]};
    return n;
}

void vc_work_free(vc_state *s)
{
    gk_counters_free(&s->raygen_fetches);
    gk_counters_free(&s->line_fragments);
    gk_counters_free(&s->surface_fragments);
    gk_counters_free(&s->air_fetches);
}
