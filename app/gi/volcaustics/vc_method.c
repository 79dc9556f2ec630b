/* The `volcaustics` method behind gi.h (volcaustics.h): knobs, per-frame orchestration of the
 * passes (nested under `gi` as vc_light, vc_lines, vc_airlight, vc_composite), statistics. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "vc_internal.h"

/* Knobs and cost priors (relative cost, cheapest = 1):
 *   vc_buffer: the caustic buffer's resolution (= the number of lines, res^2). The seed's Table 8.2
 *     (the volume-caustics step alone, Buddha, 256^2 screen): 5.18, 6.13, 10.75 ms at 256^2, 512^2,
 *     1024^2; 128^2 is ours (taken as 4.9 ms, the fixed share dominating) -> 1, 1.06, 1.25, 2.19.
 *   vc_step: the regular step Delta x (m) the line samples are spread onto; the seed's 0.2 is for
 *     its scene's units, ours is a 1 m ring: 0.05 by default. The points per fragment are
 *     2 r_f / Delta x whatever Delta x is, so the cost does not change -> 1, 1, 1, 1 (a quality knob:
 *     the scheduler never moves it).
 *   vc_filter: r_f / Delta x; the seed uses 1, and shows 0.1 as noisy (Fig. 8.9c/d). Points per
 *     fragment ~ 2 r_f / Delta x + 1: 1.2, 2, 3, 5 -> cost of the lines pass 1, 1.1, 1.2, 1.5.
 *   vc_march: (A)'s resolution relative to the screen; its cost ~ pixels -> 1, 4, 16 (of a pass
 *     that is a small share at 1/4: taken as 1, 1.5, 3 of the method).
 *   vc_output: which terms are shown (all = D; airlight, vcaustics, surfaces: one term, for
 *     measuring each against its reference term); a switch, never moved by the scheduler.
 *   vc_lights: the caustic lights at most (the scene's first point/spot lights that frame its
 *     specular objects; research §6.6 "# lights", 1-4). Each repeats passes 1-5 at the same
 *     resolution, so ours grows linearly -> 1, 2, 3, 4 of the light and lines passes (the seed's
 *     27, 46.5, 108, 345 ms are super-linear, unexplained there); in a scene with fewer lights
 *     the measured cost stops growing and the online model learns it. Default: all four.
 *   vc_surface: the surface caustics under (C), the caustic-buffer rays' ends splatted as photons
 *     (vc_surface.c): off (C = the renderer's surfaces alone, as before) or splat (the seed's C);
 *     a switch, so both can be measured. */
enum { K_BUFFER, K_STEP, K_FILTER, K_MARCH, K_OUTPUT, K_LIGHTS, K_SURFACE, K_COUNT };
_Static_assert(K_COUNT == VC_KNOBS, "vc_internal.h's VC_KNOBS counts the knobs");
static const gk_knob_def knobs[K_COUNT] = {
    {.name = "vc_buffer", .owner = "volcaustics", .n_values = 4, .values = {"128", "256", "512", "1024"},
     .cost = {1.0f, 1.06f, 1.25f, 2.19f}, .default_level = 1, .scales_pass = "gi.vc_lines"},
    {.name = "vc_step", .owner = "volcaustics", .n_values = 4, .values = {"0.2", "0.1", "0.05", "0.025"},
     .cost = {1.0f, 1.0f, 1.0f, 1.0f}, .default_level = 2, .fixed = true},
    {.name = "vc_filter", .owner = "volcaustics", .n_values = 4, .values = {"0.1", "0.5", "1", "2"},
     .cost = {1.0f, 1.1f, 1.2f, 1.5f}, .default_level = 2, .fixed = true},
    {.name = "vc_march", .owner = "volcaustics", .n_values = 3, .values = {"0.25", "0.5", "1"},
     .cost = {1.0f, 1.5f, 3.0f}, .default_level = 1, .scales_pass = "gi.vc_airlight"},
    {.name = "vc_output", .owner = "volcaustics", .n_values = 4, .values = {"all", "airlight", "vcaustics", "surfaces"},
     .cost = {1.0f, 1.0f, 1.0f, 1.0f}, .default_level = 0, .fixed = true},
    {.name = "vc_lights", .owner = "volcaustics", .n_values = 4, .values = {"1", "2", "3", "4"},
     .cost = {1.0f, 2.0f, 3.0f, 4.0f}, .default_level = 3, .scales_pass = "gi.vc_lines"},
    {.name = "vc_surface", .owner = "volcaustics", .n_values = 2, .values = {"off", "splat"},
     .cost = {1.0f, 1.1f}, .default_level = 1, .fixed = true},
};

static void declare_knobs(gk_budget *b)
{
    gk_budget_add_all(b, knobs, K_COUNT);
}

/* A scene with a participating medium (gi_catalogue.c: with caustics too, GK_GI_NEEDS_MEDIA |
   GK_GI_NEEDS_CAUSTICS; the airlight alone would apply to any medium, but then the method is the
   seed's terms A + C without its subject). */
static bool applies(const gk_scene *s)
{
    return s->medium.present;
}

static void *create(const gk_gi_context *ctx, gk_err *e)
{
    vc_state *s = calloc(1, sizeof *s);
    if (!s) {
        gk_fail(e, GK_ERUNTIME, "volcaustics: out of memory");
        return NULL;
    }
    s->ctx = *ctx;
    gk_knob_handles(s->knob, knobs, K_COUNT);
    s->own_cache = gk_gi_context_own_programs(&s->ctx);
    gk_gl_caps caps;
    gk_gl_caps_query(&caps, s->ctx.gles_version ? s->ctx.gles_version : 31);
    if (!caps.color_buffer_half) {
        gk_fail(e, GK_ERUNTIME, "volcaustics: needs RGBA16F render targets for its additive images (GLES 3.2 or "
                                "EXT_color_buffer_half_float); none is available");
        if (s->own_cache)
            gk_program_cache_destroy(s->own_cache);
        free(s);
        return NULL;
    }
    /* The lines add thousands of small radiances per pixel, each ~1/R^2 of the caustic: in RGBA16F
       the increments below half an ulp of the running sum vanish. Measured on caustic-ring-fog at
       160x120 (vcaustics term inside its mask, mean against the reference): RGBA16F 0.91 / 0.79 / 0.50
       at vc_buffer 256 / 512 / 1024, RGBA32F 0.955 / 0.953 / 0.954. So RGBA32F where it can be
       blended (EXT_color_buffer_float + EXT_float_blend), as ispm does. */
    s->caustic_fmt = caps.color_buffer_float && gk_gl_has_extension("GL_EXT_float_blend") ? GL_RGBA32F : GL_RGBA16F;
    if (s->caustic_fmt == GL_RGBA16F)
        gk_log("volcaustics: no blendable RGBA32F target: the lines add in RGBA16F, which loses energy at large "
               "caustic buffers (vc_buffer > 256)");
    glGenVertexArrays(1, &s->empty_vao);
    return s;
}

static int set_scene(void *self, const gk_scene *sc, gk_err *e)
{
    (void)e;
    vc_specular_bounds(self, sc);
    return 0;
}

static void read_budget(vc_state *s, const gk_budget *b)
{
    s->buffer_res = (int)gk_knob_number(b, &s->knob[K_BUFFER], 256.0f);
    s->buffer_res = s->buffer_res < 16 ? 16 : s->buffer_res;
    s->dx = gk_knob_number(b, &s->knob[K_STEP], 0.05f);
    s->rf = s->dx * gk_knob_number(b, &s->knob[K_FILTER], 1.0f);
    s->march_scale = gk_knob_number(b, &s->knob[K_MARCH], 0.5f);
    static const unsigned shown[4] = {GK_VC_TERM_ALL, GK_VC_TERM_AIRLIGHT, GK_VC_TERM_VCAUSTICS, GK_VC_TERM_SURFACES};
    int out = gk_knob_level(b, &s->knob[K_OUTPUT], 0);
    s->terms = shown[out >= 0 && out < 4 ? out : 0];
    s->max_lights = (int)gk_knob_number(b, &s->knob[K_LIGHTS], (float)VC_MAX_LIGHTS);
    s->surface_on = gk_knob_level(b, &s->knob[K_SURFACE], 1) == 1;
    s->max_lights = s->max_lights < 1 ? 1 : s->max_lights > VC_MAX_LIGHTS ? VC_MAX_LIGHTS : s->max_lights;
    s->st.buffer_res = s->buffer_res;
}

static int ensure_images(vc_state *s, const gk_gi_frame *f, gk_err *e)
{
    int aw = (int)lroundf((float)f->width * s->march_scale), ah = (int)lroundf((float)f->height * s->march_scale);
    aw = aw < 1 ? 1 : aw, ah = ah < 1 ? 1 : ah;
    const GLenum half = GL_RGBA16F;
    if (!s->air.fbo || s->air.width != aw || s->air.height != ah) {
        gk_target_destroy(&s->air);
        if (gk_target_create(&s->air, "volcaustics airlight", aw, ah, 1, &half, GL_LINEAR, false, e))
            return -1;
    }
    if (!s->caustic.fbo || s->caustic.width != f->width || s->caustic.height != f->height) {
        gk_target_destroy(&s->caustic);
        if (gk_target_create(&s->caustic, "volcaustics lines", f->width, f->height, 1, &s->caustic_fmt, GL_NEAREST,
                             false, e))
            return -1;
    }
    if (s->surface_on && (!s->surface.fbo || s->surface.width != f->width || s->surface.height != f->height)) {
        gk_target_destroy(&s->surface);
        if (gk_target_create(&s->surface, "volcaustics surface caustics", f->width, f->height, 1, &s->caustic_fmt,
                             GL_NEAREST, false, e))
            return -1;
    }
    s->st.march_w = aw, s->st.march_h = ah;
    return 0;
}

static int render(void *self, const gk_gi_frame *f, gk_err *e)
{
    vc_state *s = self;
    if (!f->scene->medium.present)
        return 0;   /* nothing to scatter: the renderer's image stands */
    read_budget(s, f->budget);
    vc_work_frame(s, f);
    if (ensure_images(s, f, e))
        return -1;
    int n_lines = 0;
    gk_pass_begin(f->pass, "vc_light");
    bool want_surface = s->surface_on && (s->terms & GK_VC_TERM_SURFACES);
    int rc = (s->terms & GK_VC_TERM_VCAUSTICS) || want_surface ? vc_light_rays(s, f, &n_lines, e) : 0;
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    bool any = n_lines > 0 && (s->terms & GK_VC_TERM_VCAUSTICS);
    if (any) {
        gk_pass_begin(f->pass, "vc_lines");
        rc = vc_lines(s, f, n_lines, e);
        gk_pass_end(f->pass);
        if (rc)
            return -1;
    }
    bool surface = n_lines > 0 && want_surface;
    if (surface) {
        gk_pass_begin(f->pass, "vc_surface");
        rc = vc_surface_caustics(s, f, n_lines, e);
        gk_pass_end(f->pass);
        if (rc)
            return -1;
    }
    gk_pass_begin(f->pass, "vc_airlight");
    rc = (s->terms & GK_VC_TERM_AIRLIGHT) ? vc_airlight(s, f, e) : 0;
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    gk_pass_begin(f->pass, "vc_composite");
    rc = vc_composite(s, f, any, surface, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "volcaustics: GL error 0x%04x during the frame", err);
    return 0;
}

static long memory_bytes(const void *self)
{
    const vc_state *s = self;
    long r2 = (long)s->cb_res * s->cb_res;
    long b = r2 * (4 + 4 + 4) + 2 * r2 * (4 + 4); /* light views: 2 RGBA8 + depth, 2x (RGBA8 + depth) */
    b += s->n_cb * r2 * 16 * 3;                   /* caustic buffers: p1, p2, flux (RGBA32F) per light */
    b += (long)s->air.width * s->air.height * 8 +
         ((long)s->caustic.width * s->caustic.height + (long)s->surface.width * s->surface.height) *
             (s->caustic_fmt == GL_RGBA32F ? 16 : 8);
    return b;
}

void vc_free_gpu(vc_state *s)
{
    vc_free_light_buffers(s);
    gk_target_destroy(&s->air);
    gk_target_destroy(&s->caustic);
    glDeleteVertexArrays(1, &s->empty_vao);
    s->empty_vao = 0;
}

static void destroy(void *self)
{
    vc_state *s = self;
    if (!s)
        return;
    vc_free_gpu(s);
    vc_work_free(s);
    if (s->own_cache)
        gk_program_cache_destroy(s->own_cache);
    free(s);
}

const gk_volcaustics_stats *gk_volcaustics_get_stats(const void *self) { return &((const vc_state *)self)->st; }

const gk_gi_method gk_gi_volcaustics = {
    .name = "volcaustics",
    .applies = applies,
    .declare_knobs = declare_knobs,
    .create = create,
    .set_scene = set_scene,
    .render = render,
    .memory_bytes = memory_bytes,
    .destroy = destroy,
    .pass_work = vc_pass_work,
};
