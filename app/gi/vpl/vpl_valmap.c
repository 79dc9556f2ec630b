/* One paraboloid shadow map per VAL (thesis §6.3.2, §6.5 steps 7–8): linear radial depth into a
 * texture array layer (GLES 3.1 has no geometry shader, so one draw per layer), then the CSSM basis
 * (4 Fourier terms: cos/sin in RGBA8, z·cos/z·sin in RGBA16F, plus z itself) or the two moments,
 * and mipmaps for the prefiltered lookups; with vpl_umbra on, plane or horizon also the chain of
 * maxima (depth, gap) the deep-umbra test reads, and with plane or horizon the surface's plane per
 * texel. The exact-visibility reference uses the same pass with one hard map per VPL. Also the
 * tables the gather reads (VPLs with labels, emitters). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vpl_internal.h"

static void free_maps(vpl_state *s)
{
    GLuint tex[8] = {s->z_arr, s->bcos, s->bsin, s->bzcos, s->bzsin, s->bmom, s->zmax, s->zplane};
    for (int i = 0; i < 8; i++)
        if (tex[i])
            glDeleteTextures(1, &tex[i]);
    s->z_arr = s->bcos = s->bsin = s->bzcos = s->bzsin = s->bmom = s->zmax = s->zplane = 0;
    if (s->map_depth)
        glDeleteRenderbuffers(1, &s->map_depth);
    s->map_depth = 0;
    s->map_layers = 0;
}

static GLuint array_tex(GLenum fmt, int res, int layers, bool mips)
{
    GLuint t;
    int levels = 1;
    if (mips)
        while ((1 << (levels - 1)) < res)
            levels++;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, levels, fmt, res, res, layers);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, mips ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, mips ? GL_LINEAR : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

static void ensure_maps(vpl_state *s, int res, int layers, int vis, int umbra)
{
    if (s->map_layers >= layers && s->map_res == res && s->map_vis == vis && s->map_umbra == umbra)
        return;
    free_maps(s);
    if (umbra) {
        /* Read by texelFetch only (a maximum is not a filtered value): nearest everywhere. */
        s->zmax = array_tex(GL_RG16F, res, layers, true);
        glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
        glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    /* Unit normal and distance: fp32 where float targets render, else fp16 (gather.frag's
       tolerance covers its rounding). Read by texelFetch only. */
    if (umbra >= VPL_UMBRA_PLANE)
        s->zplane = array_tex(s->tgt_fmt, res, layers, false);
    s->z_arr = array_tex(GL_R16F, res, layers, vis == GK_VPL_VIS_CSSM);
    if (vis == GK_VPL_VIS_CSSM) {
        s->bcos = array_tex(GL_RGBA8, res, layers, true);
        s->bsin = array_tex(GL_RGBA8, res, layers, true);
        s->bzcos = array_tex(GL_RGBA16F, res, layers, true);
        s->bzsin = array_tex(GL_RGBA16F, res, layers, true);
    } else if (vis == GK_VPL_VIS_VSM) {
        /* (z, z²) cancels catastrophically in fp16 (dong-001.md §7.4): 32-bit where filterable
           and renderable (RG32F needs EXT_color_buffer_float, absent on the RGBA16F path). */
        bool f32 = !s->tgt_half && gk_gl_has_extension("GL_OES_texture_float_linear");
        s->bmom = array_tex(f32 ? GL_RG32F : GL_RG16F, res, layers, true);
    }
    glGenRenderbuffers(1, &s->map_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, s->map_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, res, res);
    if (!s->map_fbo)
        glGenFramebuffers(1, &s->map_fbo);
    if (!s->basis_fbo)
        glGenFramebuffers(1, &s->basis_fbo);
    s->map_res = res, s->map_layers = layers, s->map_vis = vis, s->map_umbra = umbra;
}

/* vpl/val_zmax.frag */
typedef struct val_zmax_uniforms {
    GLint u_zmax, u_layer, u_level;
} val_zmax_uniforms;
static const gk_uniform_field val_zmax_fields[] = {GK_UNIFORM(val_zmax_uniforms, u_zmax),
                                                   GK_UNIFORM(val_zmax_uniforms, u_layer),
                                                   GK_UNIFORM(val_zmax_uniforms, u_level)};

/* The chain of maxima of the deep-umbra test: level 0 came from the depth pass; each coarser
   level is reduced from the one below, which is made the texture's only level meanwhile (reading
   one level of a texture while rendering into another is a feedback loop in GLES unless the
   written level lies outside [base, max]). */
static int build_zmax(vpl_state *s, int count, bool count_work, gk_err *e)
{
    const char *count_define = vpl_work_zmax_begin(s, count_work);
    GLuint prog = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/val_zmax.frag", count_define, e);
    const val_zmax_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(val_zmax_fields), sizeof *u, e) : NULL;
    if (!u) {
        gk_counters_end(&s->zmax_fetches);
        return -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, s->basis_fbo);
    const GLenum b1[1] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, b1);
    glUseProgram(prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, s->zmax);
    glUniform1i(u->u_zmax, 0);
    glBindVertexArray(s->empty_vao);
    int level = 1;
    for (int res = s->map_res / 2; res >= 1; res /= 2, level++) {
        glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, level - 1);
        glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, level - 1);
        glViewport(0, 0, res, res);
        glUniform1i(u->u_level, level);
        for (int k = 0; k < count; k++) {
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s->zmax, level, k);
            if (level == 1 && k == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
                gk_counters_end(&s->zmax_fetches);
                return gk_fail(e, GK_ERUNTIME, "vpl: chain of maxima framebuffer (RG16F) incomplete");
            }
            glUniform1i(u->u_layer, k);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 1000);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0, 0);
    glViewport(0, 0, s->map_res, s->map_res); /* the basis pass draws at the map's size */
    vpl_work_zmax_end(s, s->map_res, count);
    return 0;
}

float vpl_lift(const vpl_state *s) { return 0.005f * s->diam; }

void vpl_emitter_params(const vpl_state *s, const gk_val *v, bool exact, float out_c[3], float *rnear, float *far)
{
    /* The centre is lifted off its surface by 0.5% of the scene diameter so the surface the VPLs
       lie on falls in the negative half-space (no self-shadowing); geometry within r_near of the
       centre is ignored as the thesis says, with r_near = ¼ of the VAL size (thesis: unstated). */
    float lift = vpl_lift(s);
    vec3 base = exact || s->dbg.centroid_origin ? v->centre : v->origin;
    vec3 c = v3_add(base, v3_scale(v->normal, lift));
    out_c[0] = c.x, out_c[1] = c.y, out_c[2] = c.z;
    *rnear = exact ? 0.0f : 0.25f * v->size;
    *far = 1.1f * s->diam + lift; /* every receiver at d = r/far < 0.91: inside the Fourier period */
}

/* vpl/val_depth.{vert,frag} */
typedef struct val_depth_uniforms {
    GLint u_model, u_c, u_t, u_b, u_n, u_far, u_rnear;
} val_depth_uniforms;
static const gk_uniform_field val_depth_fields[] = {
    GK_UNIFORM(val_depth_uniforms, u_model), GK_UNIFORM(val_depth_uniforms, u_c),   GK_UNIFORM(val_depth_uniforms, u_t),
    GK_UNIFORM(val_depth_uniforms, u_b),     GK_UNIFORM(val_depth_uniforms, u_n),   GK_UNIFORM(val_depth_uniforms, u_far),
    GK_UNIFORM(val_depth_uniforms, u_rnear),
};

/* vpl/val_basis.frag (CSSM and VSM variants) */
typedef struct val_basis_uniforms {
    GLint u_z, u_layer;
} val_basis_uniforms;
static const gk_uniform_field val_basis_fields[] = {GK_UNIFORM(val_basis_uniforms, u_z),
                                                    GK_UNIFORM(val_basis_uniforms, u_layer)};

int vpl_build_maps(vpl_state *s, const gk_gi_frame *f, const gk_val *em, int count, gk_err *e)
{
    /* first: a counting frame without maps counts none */
    const char *count_define = vpl_work_maps_begin(s, f);
    if (s->vis == GK_VPL_VIS_NONE || count == 0) {
        vpl_work_maps_end(s, 0);
        return 0;
    }
    bool exact = s->vis == GK_VPL_VIS_EXACT;
    int res = exact ? VPL_EXACT_RES : s->val_res;
    int umbra = exact ? VPL_UMBRA_OFF : s->umbra;
    ensure_maps(s, res, exact ? s->n : GK_VPL_MAX_M, s->vis, umbra);
    GLuint prog = gk_program_get(s->ctx.programs, "vpl/val_depth.vert", "vpl/val_depth.frag", count_define, e);
    const val_depth_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(val_depth_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->map_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s->map_depth);
    const GLenum b3[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDrawBuffers(umbra >= VPL_UMBRA_PLANE ? 3 : umbra ? 2 : 1, b3);
    glViewport(0, 0, res, res);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(prog);
    for (int k = 0; k < count; k++) {
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s->z_arr, 0, k);
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, umbra ? s->zmax : 0, 0, k);
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, s->zplane, 0, k);
        if (k == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            vpl_work_maps_end(s, 0);
            return gk_fail(e, GK_ERUNTIME, "vpl: paraboloid map framebuffer (R16F %d²) incomplete", res);
        }
        const GLfloat far_z[4] = {1, 1, 1, 1};
        /* Nothing drawn (beyond far, the negative half-space, the near sphere): depth 1 with no
           slope, so its edge against anything drawn is a gap. */
        const GLfloat empty[4] = {1, 0, 0, 0};
        glClearBufferfv(GL_COLOR, 0, far_z);
        if (umbra)
            glClearBufferfv(GL_COLOR, 1, empty);
        const GLfloat no_plane[4] = {0, 0, 0, 0};
        if (umbra >= VPL_UMBRA_PLANE)
            glClearBufferfv(GL_COLOR, 2, no_plane);
        glClear(GL_DEPTH_BUFFER_BIT);
        float c[3], rnear, far;
        vpl_emitter_params(s, &em[k], exact, c, &rnear, &far);
        glUniform3f(u->u_c, c[0], c[1], c[2]);
        glUniform3f(u->u_t, em[k].t.x, em[k].t.y, em[k].t.z);
        glUniform3f(u->u_b, em[k].b.x, em[k].b.y, em[k].b.z);
        glUniform3f(u->u_n, em[k].normal.x, em[k].normal.y, em[k].normal.z);
        glUniform1f(u->u_far, far);
        glUniform1f(u->u_rnear, rnear);
        vpl_proxy_draw_all(&s->proxy, f->scene, u->u_model);
    }
    glDisable(GL_DEPTH_TEST);
    vpl_work_maps_end(s, exact ? 0 : (long)res * res * count);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, 0, 0, 0);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, 0, 0, 0);
    if (exact)
        return 0;
    if (umbra && build_zmax(s, count, f->count_work, e))
        return -1;
    bool vsm = s->vis == GK_VPL_VIS_VSM;
    GLuint bp = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/val_basis.frag",
                               vsm ? "#define VIS_VSM 1\n" : NULL, e);
    const val_basis_uniforms *ub = bp ? gk_program_uniforms(s->ctx.programs, bp, GK_FIELDS(val_basis_fields), sizeof *ub, e) : NULL;
    if (!ub)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->basis_fbo);
    const GLenum b4[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glDrawBuffers(vsm ? 1 : 4, b4);
    glUseProgram(bp);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, s->z_arr);
    glUniform1i(ub->u_z, 0);
    glBindVertexArray(s->empty_vao);
    for (int k = 0; k < count; k++) {
        if (vsm) {
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s->bmom, 0, k);
        } else {
            GLuint t[4] = {s->bcos, s->bsin, s->bzcos, s->bzsin};
            for (int i = 0; i < 4; i++)
                glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, t[i], 0, k);
        }
        if (k == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return gk_fail(e, GK_ERUNTIME, "vpl: %s basis framebuffer incomplete (needs RGBA16F/RG32F "
                                           "colour-renderable)", vsm ? "VSM" : "CSSM");
        glUniform1i(ub->u_layer, k);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    /* Mips over all layers: unused layers keep stale data but are never sampled. */
    GLuint mipped[5] = {s->z_arr, s->bcos, s->bsin, s->bzcos, s->bzsin};
    if (vsm)
        mipped[0] = s->bmom;
    for (int i = 0; i < (vsm ? 1 : 5); i++) {
        glBindTexture(GL_TEXTURE_2D_ARRAY, mipped[i]);
        glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
    }
    /* the maps in use; the chains by format: CSSM's cos/sin bases RGBA8 (2), its depth and z bases
       16-bit (3); VSM's moments alone (1, counted with the 16-bit ones) */
    vpl_work_maps_mips(s, res, count, vsm ? 0 : 2, vsm ? 1 : 3);
    return 0;
}

void vpl_upload(vpl_state *s, const gk_val *em, int count)
{
    int n = s->n;
    float *buf = malloc((size_t)n * 3 * 4 * sizeof(float));
    if (!buf)
        return;
    for (int i = 0; i < n; i++) {
        const gk_vpl *v = &s->st.vpl[i];
        float *p = buf + i * 4, *q = buf + (n + i) * 4, *r = buf + (2 * n + i) * 4;
        p[0] = v->pos.x, p[1] = v->pos.y, p[2] = v->pos.z, p[3] = (float)s->st.labels[i];
        q[0] = v->nrm.x, q[1] = v->nrm.y, q[2] = v->nrm.z, q[3] = v->area;
        r[0] = v->flux.x, r[1] = v->flux.y, r[2] = v->flux.z, r[3] = 0.0f;
    }
    if (!s->vpl_tex)
        glGenTextures(1, &s->vpl_tex);
    glBindTexture(GL_TEXTURE_2D, s->vpl_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, n, 3, 0, GL_RGBA, GL_FLOAT, buf);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    free(buf);
    int w = count > 0 ? count : 1;
    float *vb = calloc((size_t)w * 4 * 4, sizeof(float));
    if (!vb)
        return;
    bool exact = s->vis == GK_VPL_VIS_EXACT;
    float res = (float)(exact ? VPL_EXACT_RES : s->val_res);
    for (int k = 0; k < count; k++) {
        float c[3], rnear, far;
        vpl_emitter_params(s, &em[k], exact, c, &rnear, &far);
        float *r0 = vb + k * 4, *r1 = vb + (w + k) * 4, *r2 = vb + (2 * w + k) * 4, *r3 = vb + (3 * w + k) * 4;
        r0[0] = c[0], r0[1] = c[1], r0[2] = c[2], r0[3] = far;
        r1[0] = em[k].normal.x, r1[1] = em[k].normal.y, r1[2] = em[k].normal.z, r1[3] = em[k].size;
        r2[0] = em[k].t.x, r2[1] = em[k].t.y, r2[2] = em[k].t.z, r2[3] = rnear;
        r3[0] = em[k].b.x, r3[1] = em[k].b.y, r3[2] = em[k].b.z, r3[3] = res;
    }
    if (!s->val_tex)
        glGenTextures(1, &s->val_tex);
    glBindTexture(GL_TEXTURE_2D, s->val_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, 4, 0, GL_RGBA, GL_FLOAT, vb);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    s->val_tex_w = w;
    free(vb);
}

void vpl_free_maps(vpl_state *s) { free_maps(s); }
