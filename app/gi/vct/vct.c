/* The vct GI method (gi.h): life cycle, knobs, and the per-frame decision of which passes run.
 * Model no more than the scene needs: the grid fits the scene's bounds at the budget's resolution;
 * static geometry is voxelized once, animated nodes are re-voxelized in their dirty region, and
 * a light that moves re-injects without re-voxelizing. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "vct_internal.h"

/* Cost priors (summary A.6.3): clear, inject and pre-integration grow with res^3, voxelization with
 * res^2 x area, tracing only with log(res) for wide cones; at CI sizes the res^3 passes dominate
 * from 128^3 (P.6), so the prior is between res^2 and res^3. Cones: linear. Step multiplier m:
 * steps ~ 1/ln(1 + m a) for a ~ 1.1 (1/ln 3.2 = 0.86, 1/ln 2.65 = 1.03, 1/ln 2.1 = 1.35,
 * 1/ln 1.55 = 2.28, normalised). Trace scale: traced pixels ~ s^2. Mips: six directions vs one
 * hardware mip chain. The cones, step and trace-scale priors are of the trace pass alone, which
 * each scales with the other two held (scales_pass): the scheduler predicts their steps from its
 * measured time; resolution and mips spread over voxelize/inject/mips/trace and are learnt. */
static const gk_knob_def knob_res = {"vct_res", "vct", 4, {"32", "64", "128", "256"}, {1, 4, 24, 160}, 1, 2, false, NULL}; /* 256^3 is past the 128 MiB SSBO limit on llvmpipe: a pinned value only */
static const gk_knob_def knob_cones = {"vct_cones", "vct", 3, {"4", "6", "9"}, {1, 1.5f, 2.25f}, 1, 0, false, .scales_pass = "gi.vct_trace"};
static const gk_knob_def knob_step = {"vct_step", "vct", 4, {"2", "1.5", "1", "0.5"}, {1, 1.2f, 1.57f, 2.65f}, 2, 0, false, .scales_pass = "gi.vct_trace"};
static const gk_knob_def knob_scale = {"vct_trace_scale", "vct", 3, {"0.25", "0.5", "1"}, {1, 4, 16}, 1, 0, false, .scales_pass = "gi.vct_trace"};
static const gk_knob_def knob_mips = {"vct_mips", "vct", 2, {"iso", "aniso"}, {1, 2}, 1, 0, false, NULL};
/* Level 0 of the anisotropic map (with vct_mips=aniso; ignored with iso): iso, the thesis's one
   isotropic texture (§4: an anisotropic level 0 rippled its surfaces, Fig. 16); aniso, six
   directional views from level 0 on, each voxel showing its light to a view by how its mean normal
   faces it (mip_aniso.comp), so a wall's lit voxel looks dark from the far side (not in the thesis;
   six times level 0's memory). A switch for measuring one against the other, never a scheduler
   pick: the calibration has no rows for it. */
static const gk_knob_def knob_level0 = {.name = "vct_level0", .owner = "vct", .n_values = 2, .values = {"iso", "aniso"},
                                        .cost = {1, 1}, .default_level = 0, .fixed = true};
/* Solid ("thick") voxelization of thin walls (vct/voxelize.comp thicken; not in the thesis): each
   fragment also marks the voxels behind it, up to this many voxels along -n, opaque without radiance,
   at level 0 only (mip_aniso.comp). A switch for measuring, never a scheduler pick: the calibration
   has no rows for it. Off by default: it cuts light-leak's leak (0.132% -> 0.077% / 0.050% of the
   lit wall at 64^3) but costs where thin shells are seen from both sides (caustic-ring 0.634 ->
   0.660 / 0.696, atrium 0.358 -> 0.370 / 0.464 against their references; README). Ignored with
   vct_variant=thesis (its CAS averages have no room for the mark). */
static const gk_knob_def knob_thick = {.name = "vct_thick", .owner = "vct", .n_values = 3,
                                       .values = {"0", "1.5", "3"}, .cost = {1, 1, 1},
                                       .default_level = 0, .fixed = true};
/* The axis clamp (vct/cone_lib.glsl axis_clamp, vct/axis_dist.comp; not in the thesis): a cone
   sample is read at a level no coarser than the largest whose trilinear footprint stays on its side
   of the first occupied voxel along each axis (first), or short of the second (second), so no
   coarse sample near a wall blends in the texels beyond it. A switch, never a scheduler pick.
   thin (the default since issue 11): `first`, stopped only at thin walls' voxels (a surface with
   another facing away from it within two voxels behind, vct/thin_flag.comp) and at the voxels up to
   VCT_THIN_DEPTH behind those (limits only, not opaque), so a scene without thin walls is traced as
   with off, bit for bit; light-leak renders black (README "The axis clamp at thin walls"). Not with
   vct_variant=thesis (the thesis as published has no clamp): there thin is off. */
static const gk_knob_def knob_axis_clamp = {.name = "vct_axis_clamp", .owner = "vct", .n_values = 4,
                                            .values = {"off", "first", "second", "thin"}, .cost = {1, 1, 1, 1},
                                            .default_level = 3, .fixed = true};
/* default: gk_vct_default_options (conservative voxelization, fixed-point averaging, footprint
   clamp, ...); thesis: gk_vct_thesis_options, the thesis as published. A switch for measuring one
   against the other, never a scheduler pick. */
/* Bounces: 1, the thesis; 2, the first gather injected back into the voxels (vct/bounce.comp), not in
   the thesis. The bounce pass runs with the injection only (static lights: once), but per voxel it
   traces the pixel's cone set, so its prior is the injection's order plus one mip rebuild. */
static const gk_knob_def knob_bounces = {.name = "vct_bounces", .owner = "vct", .n_values = 2, .values = {"1", "2"},
                                         .cost = {1, 1.3f}, .default_level = 0};
static const gk_knob_def knob_variant = {"vct_variant", "vct", 2, {"default", "thesis"}, {1, 1}, 0, 0, .fixed = true};
/* Shadows of direct light (thesis §3.3, Fig. 17; vct_shadow.c): map, the renderer's `shadow` knob;
   cone9 .. cone0, one cone toward the light per pixel through the voxel map at the thesis's fixed
   apertures (9, 6, 3, 0 degrees full apex angle); cone, its aperture the light's angular diameter
   from the receiver (not in the thesis). A switch, not a scheduler pick: the calibration has no rows
   for it, and on llvmpipe it measured slower than PCSS for a larger error (README "vct: the
   soft-shadow cone and empty-space skipping"). */
static const gk_knob_def knob_shadow = {.name = "vct_shadow", .owner = "vct", .n_values = 6,
                                        .values = {"map", "cone9", "cone6", "cone3", "cone0", "cone"},
                                        .cost = {1, 1, 1, 1, 1, 1}, .default_level = 0, .fixed = true};
/* Algorithm 1's empty-space skipping (vct/empty_skip.glsl) for the cones narrower than 0.3: the
   specular cone and the shadow cone. Off: the samples of every step, as the published code (whose
   skipping branch is disabled); on: the thesis's text. A switch for measuring one against the other. */
static const gk_knob_def knob_skip = {.name = "vct_skip", .owner = "vct", .n_values = 2, .values = {"off", "on"},
                                      .cost = {1, 1}, .default_level = 0, .fixed = true};

/* Levels of the variant knobs, in the order of their values above. */
enum { MIPS_ISO, MIPS_ANISO };
enum { LEVEL0_ISO, LEVEL0_ANISO };
enum { VARIANT_DEFAULT, VARIANT_THESIS };

void gk_vct_default_options(gk_vct_options *o)
{
    memset(o, 0, sizeof *o);
    o->conservative = true;
    o->average_cas = false;
    o->faithful_weights = false;
    o->axis_weight_sq = false;
    o->opacity_correction = false;
    o->directional_injection = true;
    o->clip_cones = true;
    o->projected_coverage = false;
    o->footprint_clamp = 1.0f / 3.0f;
    o->specular = -1;
    o->apex_offset = 2.5f;
    o->max_dist = 1.7320508f;
    o->ao_lambda = 725.0f;
    o->spec_aperture = 0.158f;
    o->shadow_ambient = 0.0f;
}

void gk_vct_thesis_options(gk_vct_options *o)
{
    gk_vct_default_options(o);
    o->conservative = false;
    o->average_cas = true;
    o->faithful_weights = true;
    o->directional_injection = false;
    o->clip_cones = false;
    o->projected_coverage = false;
    o->footprint_clamp = 0.0f;
    o->shadow_ambient = 0.07f;
}

static bool vct_applies(const gk_scene *s)
{
    return s && s->n_triangles > 0 && (s->n_lights > 0 || s->features.has_emissive);
}

static bool vct_wants_shadow_mask(const gk_budget *b)
{
    gk_knob k = gk_budget_knob(b, &knob_shadow);
    return gk_knob_level(b, &k, 0) != VCT_SHADOW_MAP;
}

static void vct_declare_knobs(gk_budget *b)
{
    gk_budget_add(b, &knob_res);
    gk_budget_add(b, &knob_cones);
    gk_budget_add(b, &knob_step);
    gk_budget_add(b, &knob_scale);
    gk_budget_add(b, &knob_mips);
    gk_budget_add(b, &knob_variant);
    gk_budget_add(b, &knob_bounces);
    gk_budget_add(b, &knob_shadow);
    gk_budget_add(b, &knob_skip);
    gk_budget_add(b, &knob_level0);
    gk_budget_add(b, &knob_thick);
    gk_budget_add(b, &knob_axis_clamp);
}

static void *vct_create(const gk_gi_context *ctx, gk_err *e)
{
    gk_vct *v = calloc(1, sizeof *v);
    if (!v) {
        gk_fail(e, GK_ERUNTIME, "vct: out of memory");
        return NULL;
    }
    v->k_res = (gk_knob){&knob_res, -1};
    v->k_cones = (gk_knob){&knob_cones, -1};
    v->k_step = (gk_knob){&knob_step, -1};
    v->k_scale = (gk_knob){&knob_scale, -1};
    v->k_mips = (gk_knob){&knob_mips, -1};
    v->k_variant = (gk_knob){&knob_variant, -1};
    v->k_bounces = (gk_knob){&knob_bounces, -1};
    v->k_shadow = (gk_knob){&knob_shadow, -1};
    v->k_skip = (gk_knob){&knob_skip, -1};
    v->k_level0 = (gk_knob){&knob_level0, -1};
    v->k_thick = (gk_knob){&knob_thick, -1};
    v->k_axis_clamp = (gk_knob){&knob_axis_clamp, -1};
    v->ctx = *ctx;
    gk_vct_default_options(&v->opt);
    v->user_opt = v->opt;
    glGenBuffers(1, &v->tri_ssbo);
    glGenBuffers(1, &v->counter_ssbo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->counter_ssbo);
    glBufferData(GL_SHADER_STORAGE_BUFFER, 16, NULL, GL_DYNAMIC_READ);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    glGenSamplers(1, &v->nearest_sampler);
    glSamplerParameteri(v->nearest_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(v->nearest_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(v->nearest_sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(v->nearest_sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(v->nearest_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    /* the packed directional chains' level 0 alone, for the trace's samples below lod 1: a sampler
       without mip filtering lets llvmpipe read one level (8 texels) instead of two at weight 0 */
    glGenSamplers(1, &v->level0_sampler);
    glSamplerParameteri(v->level0_sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(v->level0_sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(v->level0_sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(v->level0_sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(v->level0_sampler, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glGenVertexArrays(1, &v->vao);
    if (glGetError() != GL_NO_ERROR) {
        gk_fail(e, GK_ERUNTIME, "vct: creating GL objects failed (is a GLES 3.1 context current?)");
        free(v);
        return NULL;
    }
    return v;
}

static int vct_set_scene(void *self, const gk_scene *s, gk_err *e)
{
    (void)e;
    gk_vct *v = self;
    v->scene = s;
    v->allocated = false;     /* grid refits and re-voxelizes on the next frame */
    v->need_voxelize = v->need_inject = true;
    vct_tris_free(&v->tris);
    return 0;
}

/* The options in use: the caller's, or the thesis's under vct_variant=thesis; the next render
   re-voxelizes with them. */
static void apply_options(gk_vct *v)
{
    if (v->thesis)
        gk_vct_thesis_options(&v->opt);
    else
        v->opt = v->user_opt;
    v->allocated = false;
    v->need_voxelize = v->need_inject = true;
}

void gk_vct_set_options(void *self, const gk_vct_options *o)
{
    gk_vct *v = self;
    v->user_opt = *o;
    apply_options(v);
}

void vct_read_budget(gk_vct *v, const gk_budget *b, vct_budget *out)
{
    out->res = (int)gk_knob_number(b, &v->k_res, 64);
    out->cones = (int)gk_knob_number(b, &v->k_cones, 6);
    out->step = gk_knob_number(b, &v->k_step, 1.0f);
    out->trace_scale = gk_knob_number(b, &v->k_scale, 0.5f);
    out->aniso = gk_knob_level(b, &v->k_mips, MIPS_ANISO) == MIPS_ANISO;
    out->thesis = gk_knob_level(b, &v->k_variant, VARIANT_DEFAULT) == VARIANT_THESIS;
    out->bounces = (int)gk_knob_number(b, &v->k_bounces, 1) == 2 ? 2 : 1;
    out->shadow = gk_knob_level(b, &v->k_shadow, 0);
    out->skip = gk_knob_level(b, &v->k_skip, 0) == 1;
    out->aniso_level0 = out->aniso && gk_knob_level(b, &v->k_level0, LEVEL0_ISO) == LEVEL0_ANISO;
    out->thick = gk_knob_number(b, &v->k_thick, 0.0f);
    if (!(out->thick >= 0.0f))
        out->thick = 0.0f;
    out->axis_clamp = gk_knob_level(b, &v->k_axis_clamp, 0);
    if (out->thesis && out->axis_clamp == VCT_AXIS_THIN)
        out->axis_clamp = 0;
    if (out->res < 8)
        out->res = 64;
    if (out->cones != 4 && out->cones != 9)
        out->cones = 6;
    if (!(out->trace_scale > 0.0f) || out->trace_scale > 1.0f)
        out->trace_scale = 0.5f;
    if (!(out->step > 0.0f))
        out->step = 1.0f;
}

/* Changes of anything injection depends on: light frames, power, shadow maps. */
static unsigned long light_hash(const gk_gi_frame *f)
{
    unsigned long h = 1469598103934665603UL;
    const unsigned char *p = (const unsigned char *)f->lights;
    size_t n = (size_t)f->n_lights * sizeof *f->lights;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211UL;
    return h ^ (unsigned long)f->n_lights;
}

static void to_voxels(const gk_vct *v, vec3 lo, vec3 hi, int rlo[3], int rhi[3])
{
    const float *o = v->origin;
    float l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
    for (int k = 0; k < 3; k++) {
        int a = (int)floorf((l[k] - o[k]) / v->voxel) - 1, b = (int)floorf((h[k] - o[k]) / v->voxel) + 1;
        rlo[k] = a < 0 ? 0 : (a >= v->res ? v->res - 1 : a);
        rhi[k] = b < 0 ? 0 : (b >= v->res ? v->res - 1 : b);
    }
}

static int upload_tris(gk_vct *v, int first, int count)
{
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->tri_ssbo);
    if (first == 0 && count == v->tris.n)
        glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)((v->tris.n ? v->tris.n : 1) * VCT_TRI_FLOATS * 4),
                     v->tris.data, GL_DYNAMIC_DRAW);
    else
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, (GLintptr)first * VCT_TRI_FLOATS * 4,
                        (GLsizeiptr)count * VCT_TRI_FLOATS * 4, v->tris.data + (size_t)first * VCT_TRI_FLOATS);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    return 0;
}

int vct_update(gk_vct *v, const gk_gi_frame *f, vct_budget *bp, gk_err *e)
{
    vct_budget b = *bp;
    const gk_scene *s = f->scene ? f->scene : v->scene;
    if (!s)
        return gk_fail(e, GK_ERUNTIME, "vct: render without a scene");
    if (b.thesis != v->thesis) {   /* variant switched: rebuild everything */
        v->thesis = b.thesis;
        apply_options(v);
    }

    if (!v->tris.data || s != v->scene) {           /* first frame of a scene: node matrices are valid now */
        v->scene = s;
        if (vct_tris_build(&v->tris, s, e) != 0 || vct_alpha_upload(v, s, e) != 0)
            return -1;
        v->emissive = v->tris.max_emission > 0.0f;
        v->allocated = false;
    }
    v->specular = v->opt.specular < 0 ? s->features.has_specular : v->opt.specular != 0;
    int max_res = vct_max_res_allowed(gk_vct_channels(v->emissive));
    if (b.res > max_res) {
        if (!v->allocated || v->cur.res != max_res)
            gk_log("vct: vct_res=%d does not fit this GPU's storage-buffer limit, using %d", b.res, max_res);
        b.res = max_res;
        gk_knob_note_ran(f->pass ? f->pass->ran : NULL, &v->k_res, (float)max_res);
    }
    if (!v->allocated || b.res != v->cur.res || b.aniso != v->cur.aniso || b.aniso_level0 != v->cur.aniso_level0) {
        vct_grid_fit(v, s, b.res);
        if (vct_alloc(v, &b, e) != 0)
            return -1;
        upload_tris(v, 0, v->tris.n);
    }
    if (b.thick != v->cur.thick || (b.axis_clamp == VCT_AXIS_THIN) != (v->cur.axis_clamp == VCT_AXIS_THIN))
        v->need_voxelize = true;   /* thin: its flags and limits are made with the voxels (vct_pass_voxelize) */
    v->cur.thick = b.thick;
    v->cur.axis_clamp = b.axis_clamp;
    v->cur.cones = b.cones;
    v->cur.step = b.step;
    v->cur.trace_scale = b.trace_scale;
    if (vct_ensure_trace_targets(v, f->width, f->height, b.trace_scale, e) != 0)
        return -1;
    v->stats.n_triangles = v->tris.n;
    v->stats.n_dynamic_triangles = v->tris.n - v->tris.n_static;

    int lo[3] = {0, 0, 0}, hi[3] = {v->res - 1, v->res - 1, v->res - 1};
    v->mips_ran = v->inject_ran = v->voxelize_ran = v->bounce_ran = false;
    v->count_work = f->count_work;
    /* Each pass of the thesis is a pass of the renderer's clock (nested under `gi`); a pass that
       has nothing to do this frame (static voxels, unchanged light) is not begun, so its column
       is empty rather than a measured zero. */
    if (v->need_voxelize) {
        gk_pass_begin(f->pass, "vct_voxelize");
        int rc = vct_pass_voxelize(v, lo, hi, e);
        gk_pass_end(f->pass);
        if (rc != 0)
            return -1;
        v->need_voxelize = false;
        v->need_inject = true;
        v->axis_valid = false;
        vct_tris_update(&v->tris, s, &(vec3){0}, &(vec3){0}); /* sync the remembered node matrices */
    } else if (v->tris.n > v->tris.n_static) {
        vec3 dlo, dhi;
        if (vct_tris_update(&v->tris, s, &dlo, &dhi)) {
            gk_pass_begin(f->pass, "vct_voxelize");
            upload_tris(v, v->tris.n_static, v->tris.n - v->tris.n_static);
            to_voxels(v, dlo, dhi, lo, hi);
            /* vct_thick: the moved surfaces' solid marks reach that far behind them, old and new */
            int reach = (int)ceilf(v->cur.thick);
            for (int k = 0; k < 3; k++) {
                lo[k] = lo[k] - reach < 0 ? 0 : lo[k] - reach;
                hi[k] = hi[k] + reach > v->res - 1 ? v->res - 1 : hi[k] + reach;
            }
            int rc = vct_pass_voxelize(v, lo, hi, e);
            gk_pass_end(f->pass);
            if (rc != 0)
                return -1;
            v->need_inject = true;   /* the moved object's shadows change everywhere */
            v->axis_valid = false;
        }
    }

    if (vct_axis_clamp_in_use(v, b.axis_clamp) && (!v->axis_valid || v->axis_nth != b.axis_clamp)) {   /* part of the voxels: timed with them */
        gk_pass_begin(f->pass, "vct_voxelize");
        int rc = vct_pass_axis_dist(v, b.axis_clamp, e);
        gk_pass_end(f->pass);
        if (rc != 0)
            return -1;
    }

    unsigned long lh = light_hash(f);
    if (lh != v->light_hash || b.bounces != v->cur.bounces)
        v->need_inject = true;
    v->cur.bounces = b.bounces;
    if (v->need_inject) {
        gk_pass_begin(f->pass, "vct_inject");
        int rc = vct_pass_inject(v, f, e);
        gk_pass_end(f->pass);
        if (rc != 0)
            return -1;
        v->inject_ran = true;
        gk_pass_begin(f->pass, "vct_mips");
        /* Directional views (gk_vct_options.directional_injection, mip_aniso.comp) with one bounce
           only: they keep a bright patch from lighting what sees it edge-on or from behind
           (cornell-spot vs its one-bounce reference 0.486 -> 0.355), but a cone crossing a surface
           obliquely then sees part of its lit face dark, and the loss compounds over bounces:
           cornell vs the full reference with vct_bounces=2 0.082 with isotropic views, 0.154 with
           directional ones. */
        bool directional = v->opt.directional_injection && b.bounces == 1;
        rc = vct_pass_mips(v, directional, e);
        gk_pass_end(f->pass);
        if (rc != 0)
            return -1;
        v->mips_ran = true;
        if (b.bounces == 2) {
            gk_pass_begin(f->pass, "vct_bounce");
            rc = vct_pass_bounce(v, &b, e);
            if (rc == 0)
                rc = vct_pass_mips(v, directional, e);
            gk_pass_end(f->pass);
            if (rc != 0)
                return -1;
        }
        v->need_inject = false;
        v->light_hash = lh;
    }
    v->cur.skip = b.skip;
    *bp = b;
    return 0;
}

static int vct_render(void *self, const gk_gi_frame *f, gk_err *e)
{
    gk_vct *v = self;
    vct_budget b;
    vct_read_budget(v, f->budget, &b);
    if (vct_update(v, f, &b, e) != 0)
        return -1;
    gk_pass_begin(f->pass, "vct_trace");
    int rc = vct_pass_trace(v, f, &b, e);
    gk_pass_end(f->pass);
    if (rc != 0)
        return -1;
    gk_pass_begin(f->pass, "vct_compose");
    rc = vct_pass_compose(v, f, e);
    gk_pass_end(f->pass);
    if (rc != 0)
        return -1;
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "vct: GL error 0x%x during the frame", err);
    return 0;
}

static void vct_invalidate(void *self)
{
    gk_vct *v = self;
    v->need_voxelize = v->need_inject = true;
}

static long vct_memory_bytes(const void *self)
{
    const gk_vct *v = self;
    if (!v->allocated)
        return 0;
    return gk_vct_memory_formula(v->cur.res, v->cur.aniso, v->cur.aniso_level0, gk_vct_channels(v->emissive),
                                 v->trace_w, v->trace_h, v->tris.n) +
           (v->vox_bounce ? gk_vct_bounce_memory(v->cur.res, v->cur.aniso) : 0) +
           (v->axis_ssbo ? gk_vct_axis_clamp_memory(v->cur.res) : 0) +
           (v->thin_ssbo ? gk_vct_thin_flag_memory(v->cur.res) : 0);
}

static void vct_destroy(void *self)
{
    gk_vct *v = self;
    if (!v)
        return;
    vct_free_gpu(v);
    glDeleteBuffers(1, &v->tri_ssbo);
    glDeleteBuffers(1, &v->counter_ssbo);
    vct_work_free(v);
    if (v->alpha_tex)
        glDeleteTextures(1, &v->alpha_tex);
    if (v->trace_diffuse)
        glDeleteTextures(1, &v->trace_diffuse);
    if (v->trace_spec)
        glDeleteTextures(1, &v->trace_spec);
    vct_shadow_free(v);
    glDeleteSamplers(1, &v->nearest_sampler);
    glDeleteSamplers(1, &v->level0_sampler);
    glDeleteVertexArrays(1, &v->vao);
    vct_tris_free(&v->tris);
    free(v);
}

void gk_vct_get_stats(const void *self, gk_vct_stats *out)
{
    const gk_vct *v = self;
    *out = v->stats;
    /* vct/trace.comp's and vct/shadow_cone.comp's Counters: all trace samples, those below lod 1,
       traced pixels, the shadow cones' samples */
    GLuint counted[4] = {0, 0, 0, 0};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->counter_ssbo);
    const GLuint *p = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, sizeof counted, GL_MAP_READ_BIT);
    if (p) {
        memcpy(counted, p, sizeof counted);
        glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    out->last_trace_steps = counted[0];
    out->last_trace_fine_steps = counted[1];
    out->last_trace_pixels = counted[2];
    out->last_shadow_steps = counted[3];
    out->aniso = v->cur.aniso;
    out->aniso_level0 = v->cur.aniso_level0;
}

unsigned gk_vct_scratch_buffer(const void *self) { return ((const gk_vct *)self)->scratch_ssbo; }
unsigned gk_vct_radiance_texture(const void *self) { return ((const gk_vct *)self)->vox0; }
unsigned gk_vct_axis_buffer(const void *self) { return ((const gk_vct *)self)->axis_ssbo; }
unsigned gk_vct_thin_buffer(const void *self) { return ((const gk_vct *)self)->thin_ssbo; }

const gk_gi_method gk_gi_vct = {
    .name = "vct",
    .applies = vct_applies,
    .declare_knobs = vct_declare_knobs,
    .create = vct_create,
    .set_scene = vct_set_scene,
    .render = vct_render,
    .memory_bytes = vct_memory_bytes,
    .shadow_mask = vct_shadow_mask,
    .wants_shadow_mask = vct_wants_shadow_mask,
    .invalidate = vct_invalidate,
    .pass_work = vct_pass_work,
    .destroy = vct_destroy,
};
