/* Convolution soft shadow maps, CSSM (Annen et al. 2008; dong-001.md §3, checklist §11.2), over the
 * shared depth maps. Per light and frame: depth map -> normalised linear depth (compute) -> the
 * K = 4 Fourier bases cos/sin(c_k z), z cos/sin(c_k z) and z, prefiltered either as
 *   mipmaps:  RGBA16F arrays written by compute (cssm_basis.comp) + glGenerateMipmap, or
 *   SATs:     exact modular fixed-point RGBA32UI / R32UI summed-area tables (vssm_sat.comp)
 * (the depth first renormalised per layer to the range it holds, cssm_range.comp: #11)
 * -> the lighting pass (shaders_gles/shadow/cssm.glsl): 6 basis lookups + 1 depth per pixel.
 * Methods registered here:
 *   cssm       mipmap prefilter (the thesis's fast path: ">3x faster", 8/16-bit storage)
 *   cssm_sat   SAT prefilter (the thesis's quality path for single lights)
 *   cssm_raw   SAT, no ringing suppression (alpha = 1) and no sharpening (A = 0): the baseline
 *              of failure tests F2 (ringing) and F3 (contact leak)
 *   cssm_thesis  as cssm without the two additions of #11: the depth normalised over [near, far]
 *              (no per-layer range) and no slope-scaled receiver shift (CSSM_SLOPE 0): the
 *              baseline of test_shadow_cssm.c
 *   cssm_env   as cssm with the slope-scaled shift capped at 5 cm (CSSM_SLOPE_MAX): the
 *              environment's area lights (render_env.c). Their kernels are wide (a sky patch tens
 *              of degrees across: up to a quarter map), and the uncapped shift, growing with kernel
 *              width x receiver slope, passed the height of the objects' contact shadows; without
 *              any shift a lone quad shadows itself under grazing sky lights. env-studio, method
 *              none against env-studio-direct.exr (160x120, llvmpipe): cssm 0.104 rel. RMSE / mean
 *              ratio 1.049, cssm_thesis 0.099 / 1.031, cssm_env 0.076 / 1.022 (the trade-off
 *              curve of the cap is in shaders_gles/shadow/cssm.glsl). Kept for comparison.
 *   cssm_plane as cssm with stage 3 tested against the receiver's tangent plane in sub-kernels
 *              (CSSM_PLANE) and stage 1 as the thesis's (no slope-scaled shift): scale-free, no
 *              length in metres; the environment's lights since #11 (render_env.c). Against the
 *              same reference 0.070 / 1.020 at 16 lights (the cap 0.076 / 1.022), and sampler-
 *              wrap.glb's lone quad against the tracer 0.049 (the cap 0.057); every env_lights
 *              level better than the cap on both (shaders_gles/shadow/cssm.glsl).
 * Texture units: the method's unit (depth map), +1..+4 the bases, +5 z (+6 z^2 SAT, unused sums),
 * +7 the per-layer depth range (2 x 1 texels per layer: min, max of the normalised depth). */
#include <math.h>
#include <stdlib.h>

#include "shadow_prefilter.h"
#include "shadow_prefilter_work.h"

#include "gl/gl_target.h"

/* Depth scale of the Fourier series (z_c = CSSM_RANGE z), and the receiver shift where the scaled,
   clamped K = 4 test saturates (dong-001.md §3.3: alpha >= 1.12 -> 0.064). */
#define CSSM_RANGE 0.85f
#define CSSM_SHIFT 0.064f

enum { B_COS, B_SIN, B_ZCOS, B_ZSIN, B_Z, B_Z2, B_TMP0, B_TMP1, B_N };

typedef struct cssm_slot {
    GLuint zlin, range;
    GLuint basis[B_N];
    int size, layers;
} cssm_slot;

typedef struct cssm_state {
    bool sat;
    bool full_range;        /* cssm_thesis: no per-layer range (the range texture holds (0, 1)) */
    gk_shadow_maps maps;
    cssm_slot slot[GK_SHADOW_MAX_LIGHTS];
} cssm_state;

static void slot_free(cssm_slot *s)
{
    if (s->zlin)
        glDeleteTextures(1, &s->zlin);
    if (s->range)
        glDeleteTextures(1, &s->range);
    for (int i = 0; i < B_N; i++)
        if (s->basis[i])
            glDeleteTextures(1, &s->basis[i]);
    *s = (cssm_slot){0};
}

static int slot_ensure(cssm_slot *s, bool sat, int size, int layers, gk_err *e)
{
    if (s->zlin && s->size == size && s->layers == layers)
        return 0;
    slot_free(s);
    if (!(s->zlin = gk_pf_array_create(GL_R32F, size, layers, 1, false, e)))
        return -1;
    while (glGetError() != GL_NO_ERROR) {
    }
    glGenTextures(1, &s->range);
    glBindTexture(GL_TEXTURE_2D_ARRAY, s->range);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_R32F, 2, 1, layers);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        gk_fail(e, GK_ERUNTIME, "CSSM depth range texture (2x1x%d R32F): %s", layers, gk_gl_error_name(err));
        slot_free(s);
        return -1;
    }
    for (int i = 0; i < B_N; i++) {
        if (!sat && i > B_Z)
            break;
        GLenum fmt = !sat ? GL_RGBA16F : (i == B_Z || i == B_Z2) ? GL_R32UI : GL_RGBA32UI;
        s->basis[i] = sat ? gk_pf_array_create(fmt, size, layers, 1, false, e)
                          : gk_pf_array_create(fmt, size, layers, 0, true, e);
        if (!s->basis[i]) {
            slot_free(s);
            return -1;
        }
    }
    s->size = size;
    s->layers = layers;
    return 0;
}

static void *cssm_create_mm(void) { return calloc(1, sizeof(cssm_state)); }

static void *cssm_create_full(void)
{
    cssm_state *st = calloc(1, sizeof(cssm_state));
    if (st)
        st->full_range = true;
    return st;
}

static void *cssm_create_sat(void)
{
    cssm_state *st = calloc(1, sizeof(cssm_state));
    if (st)
        st->sat = true;
    return st;
}

static void cssm_destroy(void *self)
{
    cssm_state *st = self;
    if (!st)
        return;
    gk_shadow_maps_free(&st->maps);
    for (int i = 0; i < GK_SHADOW_MAX_LIGHTS; i++)
        slot_free(&st->slot[i]);
    free(st);
}

/* shadow/cssm_basis.comp, both passes */
typedef struct basis_uniforms {
    GLint u_z, u_size, u_range;
} basis_uniforms;
static const gk_uniform_field basis_fields[] = {GK_UNIFORM(basis_uniforms, u_z), GK_UNIFORM(basis_uniforms, u_size),
                                                GK_UNIFORM(basis_uniforms, u_range)};

/* shaders_gles/shadow/cssm.glsl, in the lighting program (mipmap and SAT variants) */
typedef struct cssm_uniforms {
    GLint u_cssm_basis[6]; /* cos, sin, zcos, zsin, z, z2 */
    GLint u_cssm, u_cssm_range;
} cssm_uniforms;
static const gk_uniform_field cssm_fields[] = {
    GK_UNIFORM_AS(cssm_uniforms, u_cssm_basis[0], "u_cssm_cos"),
    GK_UNIFORM_AS(cssm_uniforms, u_cssm_basis[1], "u_cssm_sin"),
    GK_UNIFORM_AS(cssm_uniforms, u_cssm_basis[2], "u_cssm_zcos"),
    GK_UNIFORM_AS(cssm_uniforms, u_cssm_basis[3], "u_cssm_zsin"),
    GK_UNIFORM_AS(cssm_uniforms, u_cssm_basis[4], "u_cssm_z"),
    GK_UNIFORM_AS(cssm_uniforms, u_cssm_basis[5], "u_cssm_z2"),
    GK_UNIFORM(cssm_uniforms, u_cssm),
    GK_UNIFORM(cssm_uniforms, u_cssm_range),
};

static int basis_mipmaps(gk_program_cache *progs, cssm_slot *s, gk_err *e)
{
    GLuint p0 = gk_program_get_compute(progs, "shadow/cssm_basis.comp", "#define CSSM_PASS 0\n", e);
    GLuint p1 = p0 ? gk_program_get_compute(progs, "shadow/cssm_basis.comp", "#define CSSM_PASS 1\n", e) : 0;
    const basis_uniforms *u0 = p1 ? gk_program_uniforms(progs, p0, GK_FIELDS(basis_fields), sizeof *u0, e) : NULL;
    const basis_uniforms *u1 = u0 ? gk_program_uniforms(progs, p1, GK_FIELDS(basis_fields), sizeof *u1, e) : NULL;
    if (!u1)
        return -1;
    GLuint groups = (GLuint)((s->size + 7) / 8);
    glUseProgram(p0);
    gk_pf_bind(u0->u_z, s->zlin, 0);
    glUniform1i(u0->u_size, s->size);
    glUniform1f(u0->u_range, CSSM_RANGE);
    for (int i = 0; i < 4; i++)
        glBindImageTexture((GLuint)i, s->basis[B_COS + i], 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(groups, groups, (GLuint)s->layers);
    glUseProgram(p1);
    gk_pf_bind(u1->u_z, s->zlin, 0);
    glUniform1i(u1->u_size, s->size);
    glUniform1f(u1->u_range, CSSM_RANGE);
    glBindImageTexture(0, s->basis[B_Z], 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(groups, groups, (GLuint)s->layers);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    for (int i = B_COS; i <= B_Z; i++) {
        glBindTexture(GL_TEXTURE_2D_ARRAY, s->basis[i]);
        glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    return 0;
}

/* shadow/cssm_range.comp: the layer's depth range, then the depth renormalised to it in place. With
   `full` only (0, 1) is written (the thesis's [near, far] normalisation). */
typedef struct range_uniforms {
    GLint u_size;
} range_uniforms;
static const gk_uniform_field range_fields[] = {GK_UNIFORM(range_uniforms, u_size)};

static int depth_range(gk_program_cache *progs, cssm_slot *s, bool full, gk_err *e)
{
    if (full) {
        float v[16];
        for (int l = 0; l < s->layers && l < 8; l++)
            v[2 * l] = 0.0f, v[2 * l + 1] = 1.0f;
        glBindTexture(GL_TEXTURE_2D_ARRAY, s->range);
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, 2, 1, s->layers, GL_RED, GL_FLOAT, v);
        glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
        return 0;
    }
    GLuint p0 = gk_program_get_compute(progs, "shadow/cssm_range.comp", "#define CSSM_RANGE_PASS 0\n", e);
    GLuint p1 = p0 ? gk_program_get_compute(progs, "shadow/cssm_range.comp", "#define CSSM_RANGE_PASS 1\n", e) : 0;
    const range_uniforms *u0 = p1 ? gk_program_uniforms(progs, p0, GK_FIELDS(range_fields), sizeof *u0, e) : NULL;
    const range_uniforms *u1 = u0 ? gk_program_uniforms(progs, p1, GK_FIELDS(range_fields), sizeof *u1, e) : NULL;
    if (!u1)
        return -1;
    glUseProgram(p0);
    glUniform1i(u0->u_size, s->size);
    glBindImageTexture(0, s->zlin, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32F);
    glBindImageTexture(1, s->range, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute(1, 1, (GLuint)s->layers);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(p1);
    glUniform1i(u1->u_size, s->size);
    glBindImageTexture(0, s->zlin, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32F);
    glBindImageTexture(1, s->range, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32F);
    GLuint groups = (GLuint)((s->size + 7) / 8);
    glDispatchCompute(groups, groups, (GLuint)s->layers);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    return 0;
}

static int basis_sats(gk_program_cache *progs, cssm_slot *s, gk_err *e)
{
    float q = (float)((1u << gk_sat_bits(s->size)) - 1u);
    GLuint *b = s->basis;
    if (gk_pf_sat(progs, 0, s->zlin, s->size, s->layers, q, CSSM_RANGE, b[B_Z], b[B_Z2], 0, 0, e) != 0 ||
        gk_pf_sat(progs, 1, s->zlin, s->size, s->layers, q, CSSM_RANGE, b[B_COS], b[B_SIN], b[B_TMP0], b[B_TMP1], e) != 0 ||
        gk_pf_sat(progs, 2, s->zlin, s->size, s->layers, q, CSSM_RANGE, b[B_ZCOS], b[B_ZSIN], b[B_TMP0], b[B_TMP1], e) != 0)
        return -1;
    return 0;
}

static int cssm_render(void *self, const gk_shadow_ctx *ctx, int slot, const gk_shadow_view *v, gk_err *e)
{
    cssm_state *st = self;
    if (gk_shadow_maps_render(&st->maps, ctx, slot, v, e) != 0)
        return -1;
    cssm_slot *s = &st->slot[slot];
    if (slot_ensure(s, st->sat, v->map_size, v->n_faces, e) != 0)
        return -1;
    gk_pass_begin(ctx->pass, "cssm_prefilter"); /* linearize, depth range, bases (mipmaps or SATs) */
    int rc = -1;
    if (gk_pf_linearize(ctx->progs, st->maps.tex[slot], v, s->zlin, 0, e) == 0 &&
        depth_range(ctx->progs, s, st->full_range, e) == 0)
        rc = st->sat ? basis_sats(ctx->progs, s, e) : basis_mipmaps(ctx->progs, s, e);
    gk_pass_end(ctx->pass);
    if (rc == 0 && ctx->prefilter_work) /* the bench's counting frame (#21) */
        gk_pf_work_cssm(&ctx->prefilter_work->cssm, s->size, s->layers, st->full_range, st->sat);
    glUseProgram(0);
    return rc;
}

static int cssm_bind(void *self, gk_program_cache *progs, int slot, const gk_shadow_view *v, GLuint prog, int unit,
                     gk_err *e)
{
    cssm_state *st = self;
    cssm_slot *s = &st->slot[slot];
    const cssm_uniforms *u = gk_program_uniforms(progs, prog, GK_FIELDS(cssm_fields), sizeof *u, e);
    if (!u || gk_shadow_maps_bind(&st->maps, progs, slot, v, prog, unit, e) != 0)
        return -1;
    int n = st->sat ? 6 : 5;
    for (int i = 0; i < n; i++)
        gk_pf_bind(u->u_cssm_basis[i], s->basis[i], unit + 1 + i);
    gk_pf_bind(u->u_cssm_range, s->range, unit + 7);
    float q = (float)((1u << gk_sat_bits(s->size)) - 1u);
    glUniform4f(u->u_cssm, CSSM_RANGE, CSSM_SHIFT, 1.0f / q, 0.0f);
    return 0;
}

const gk_shadow_method gk_shadow_cssm = {
    .name = "cssm",
    .glsl_define = "#define SHADOW_CSSM 1\n",
    .create = cssm_create_mm,
    .destroy = cssm_destroy,
    .render = cssm_render,
    .bind = cssm_bind,
};

const gk_shadow_method gk_shadow_cssm_sat = {
    .name = "cssm_sat",
    .glsl_define = "#define SHADOW_CSSM 1\n#define CSSM_SAT 1\n",
    .create = cssm_create_sat,
    .destroy = cssm_destroy,
    .render = cssm_render,
    .bind = cssm_bind,
};

const gk_shadow_method gk_shadow_cssm_raw = {
    .name = "cssm_raw",
    .glsl_define = "#define SHADOW_CSSM 1\n#define CSSM_SAT 1\n#define CSSM_ALPHA 1.0\n#define CSSM_SHARP_A 0.0\n",
    .create = cssm_create_sat,
    .destroy = cssm_destroy,
    .render = cssm_render,
    .bind = cssm_bind,
};

const gk_shadow_method gk_shadow_cssm_thesis = {
    .name = "cssm_thesis",
    .glsl_define = "#define SHADOW_CSSM 1\n#define CSSM_SLOPE 0\n",
    .create = cssm_create_full,
    .destroy = cssm_destroy,
    .render = cssm_render,
    .bind = cssm_bind,
};

const gk_shadow_method gk_shadow_cssm_env = {
    .name = "cssm_env",
    .glsl_define = "#define SHADOW_CSSM 1\n#define CSSM_SLOPE_MAX 0.05\n",
    .create = cssm_create_mm,
    .destroy = cssm_destroy,
    .render = cssm_render,
    .bind = cssm_bind,
};

const gk_shadow_method gk_shadow_cssm_plane = {
    .name = "cssm_plane",
    .glsl_define = "#define SHADOW_CSSM 1\n#define CSSM_PLANE 1\n",
    /* two draws (render_split.c): the first only adds and marks the pixels with no light (CSSM's
       shadow_settle settles none), so the second's early stencil test skips the SIMD blocks of sky
       and of surfaces facing away from the light, where llvmpipe ran the whole lookup masked */
    .split = true,
    .create = cssm_create_mm,
    .destroy = cssm_destroy,
    .render = cssm_render,
    .bind = cssm_bind,
};
