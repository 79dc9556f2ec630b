/* Reflective shadow maps and VPL generation (thesis §6.5 steps 2–3). Every light with an RSM gets
 * an atlas of perspective faces: 1 for a spot (fov = 2·outer cone), 6 for a point light (the cube,
 * faces side by side), 5 for a rectangular area light (the hemicube around its emission axis: our
 * "hemispherical map from the centre", free of the paraboloid's straight-edge error on coarse
 * meshes), and 1 orthographic face for a directional light (the sun of 000 §3.2 and 001 ch. 6: the
 * view's region, the camera frustum's bounds clipped to the scene's, seen along the light). The N
 * VPLs are shared evenly between the lights; VPL i of a light samples its atlas at Halton point i. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vpl_internal.h"

typedef struct face { vec3 dir, up; } face;

static const face cube_faces[6] = {
    {{0, 0, -1}, {0, 1, 0}}, /* the emission axis first for hemicubes (replaced below) */
    {{1, 0, 0}, {0, 1, 0}},  {{-1, 0, 0}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, 1}},
    {{0, -1, 0}, {0, 0, 1}}, {{0, 0, 1}, {0, 1, 0}},
};

static const char *fmt_name(const vpl_state *s) { return s->tgt_half ? "RGBA16F" : "RGBA32F"; }

static int ensure_rsm(vpl_state *s, int w, int h, gk_err *e)
{
    if (s->rsm_fbo && s->rsm_w == w && s->rsm_h == h)
        return 0;
    if (s->rsm_fbo) {
        glDeleteFramebuffers(1, &s->rsm_fbo);
        glDeleteTextures(3, s->rsm_tex);
        glDeleteRenderbuffers(1, &s->rsm_depth);
    }
    glGenFramebuffers(1, &s->rsm_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->rsm_fbo);
    glGenTextures(3, s->rsm_tex);
    for (int i = 0; i < 3; i++) {
        glBindTexture(GL_TEXTURE_2D, s->rsm_tex[i]);
        glTexStorage2D(GL_TEXTURE_2D, 1, s->tgt_fmt, w, h);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, s->rsm_tex[i], 0);
    }
    glGenRenderbuffers(1, &s->rsm_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, s->rsm_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s->rsm_depth);
    s->rsm_w = w, s->rsm_h = h;
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "vpl: RSM framebuffer (3x %s %dx%d) incomplete", fmt_name(s), w, h);
    return 0;
}

static int ensure_gen(vpl_state *s, int n, gk_err *e)
{
    if (s->gen_fbo && s->gen_n == n)
        return 0;
    if (s->gen_fbo) {
        glDeleteFramebuffers(1, &s->gen_fbo);
        glDeleteTextures(3, s->gen_tex);
    }
    glGenFramebuffers(1, &s->gen_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->gen_fbo);
    glGenTextures(3, s->gen_tex);
    for (int i = 0; i < 3; i++) {
        glBindTexture(GL_TEXTURE_2D, s->gen_tex[i]);
        glTexStorage2D(GL_TEXTURE_2D, 1, s->tgt_fmt, n, 1);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, s->gen_tex[i], 0);
    }
    s->gen_n = n;
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "vpl: VPL framebuffer (3x %s %dx1) incomplete", fmt_name(s), n);
    return 0;
}

static vec3 any_up(vec3 d) { return fabsf(d.y) < 0.99f ? v3(0, 1, 0) : v3(1, 0, 0); }

/* Faces of one light: count, their view directions/ups, the tangent of the half field of view, and
 * the intensity kind used by rsm.frag. */
static int light_faces(const gk_gi_light *L, const gk_light *sl, face *out, float *tan_half, int *kind)
{
    vec3 d = v3_norm(L->direction);
    if (sl->type == GK_LIGHT_DIRECTIONAL) { /* one orthographic face; tan_half: set by ortho_region */
        out[0].dir = d, out[0].up = any_up(d);
        *tan_half = 1.0f, *kind = 3;
        return 1;
    }
    if (sl->shape == GK_SHAPE_RECT) { /* hemicube around the axis; the back face sees nothing */
        vec3 u = v3_norm(L->axis_u), v = v3_norm(L->axis_v);
        vec3 dirs[5] = {d, u, v3_scale(u, -1), v, v3_scale(v, -1)};
        for (int i = 0; i < 5; i++)
            out[i].dir = dirs[i], out[i].up = i == 0 ? v : (i < 3 ? v : u);
        *tan_half = 1.0f, *kind = 2;
        return 5;
    }
    if (sl->type == GK_LIGHT_SPOT && sl->outer_cone < 1.3f) { /* up to ~75°: one face */
        out[0].dir = d, out[0].up = any_up(d);
        *tan_half = tanf(fmaxf(sl->outer_cone, 0.05f) * 1.02f);
        *kind = 0;
        return 1;
    }
    for (int i = 0; i < 6; i++)
        out[i] = cube_faces[i];
    out[0].dir = v3(0, 0, -1);
    *tan_half = 1.0f;
    *kind = sl->type == GK_LIGHT_SPOT ? 0 : 1;
    return 6;
}

/* How rsm.frag encodes a texel so that it survives RGBA16F targets (fp16: 11-bit mantissa, normal
 * range 6.1e-5 .. 65504), used on both paths so they differ only in precision:
 *   position  (p − bounds centre) / (½ scene diameter)  -> |·| ≤ 1 (ulp ≤ 2^-11 of the half-diameter)
 *   area      area / (diam² · texel²)                     -> (d/diam)²·(1+u²+v²)^-1.5 / cosθ, O(1)
 *   flux      flux / (max radiant · texel²)               -> ρ·I·(1+u²+v²)^-1.5 ≤ 1
 * texel = 2·tanΘ/R is the face's texel width on the unit plane; a narrow spot's ΔΩ (~1e-6 sr at
 * Θ = 3°) would otherwise fall into fp16's subnormals. vpl_gen.frag scales area and flux linearly,
 * so the VPL row keeps the same code and vpl_generate decodes it per light. */
typedef struct rsm_code { float pos_scale, area_scale, flux_scale; } rsm_code;

static rsm_code light_code(const vpl_state *s, const gk_gi_light *L, float tan_half, bool ortho)
{
    float texel = 2.0f * tan_half / (float)VPL_RSM_RES;
    float rmax = fmaxf(L->radiant.x, fmaxf(L->radiant.y, L->radiant.z));
    rsm_code c = {2.0f / s->diam, 1.0f / (s->diam * s->diam * texel * texel),
                  1.0f / (fmaxf(rmax, 1e-20f) * texel * texel)};
    if (ortho) /* texel in metres: area = texel^2 / cos, flux = rho E texel^2 */
        c.area_scale = 1.0f / (texel * texel);
    return c;
}

/* The orthographic face of a directional light: the view's region (the bounds of the camera
   frustum's corners, its far plane clipped to the scene's bounds) seen along the light, centred on
   it, as wide as its bounding sphere; the depth range covers the whole scene in front of it, so
   what shades the region from outside it is in the map. Returns the half width (metres). */
static float ortho_face(const vpl_state *s, const gk_gi_frame *f, vec3 d, vec3 up, mat4 *vp)
{
    const gk_scene *sc = f->scene;
    vec3 lo = v3(1e30f, 1e30f, 1e30f), hi = v3(-1e30f, -1e30f, -1e30f);
    for (int k = 0; k < 8; k++) {
        vec4 c = m4_vec4(f->inv_view_proj, (vec4){(k & 1) ? 1.0f : -1.0f, (k & 2) ? 1.0f : -1.0f,
                                                   (k & 4) ? 1.0f : -1.0f, 1.0f});
        vec3 p = fabsf(c.w) > 1e-12f ? v3(c.x / c.w, c.y / c.w, c.z / c.w) : v3(s->origin[0], s->origin[1], s->origin[2]);
        lo = v3_min(lo, p), hi = v3_max(hi, p);
    }
    lo = v3_max(lo, sc->bmin), hi = v3_min(hi, sc->bmax);
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) /* camera outside the scene's bounds: all of it */
        lo = sc->bmin, hi = sc->bmax;
    vec3 centre = v3_scale(v3_add(lo, hi), 0.5f);
    float r = fmaxf(0.5f * v3_len(v3_sub(hi, lo)), 1e-3f * s->diam);
    vec3 eye = v3_sub(centre, v3_scale(d, s->diam));
    mat4 view = m4_look_at(eye, centre, up);
    *vp = m4_mul(m4_ortho(-r, r, -r, r, 0.0f, 2.0f * s->diam), view);
    return r;
}

/* vpl/rsm.{vert,frag} (u_model and the material uniforms are gk_gi_frame.draw_scene's) */
typedef struct rsm_uniforms {
    GLint u_light_pos, u_light_dir, u_radiant, u_light_kind, u_cos_inner, u_cos_outer, u_face_res, u_tan_half,
        u_origin, u_code, u_light_vp, u_face_origin;
} rsm_uniforms;
static const gk_uniform_field rsm_fields[] = {
    GK_UNIFORM(rsm_uniforms, u_light_pos), GK_UNIFORM(rsm_uniforms, u_light_dir),
    GK_UNIFORM(rsm_uniforms, u_radiant),   GK_UNIFORM(rsm_uniforms, u_light_kind),
    GK_UNIFORM(rsm_uniforms, u_cos_inner), GK_UNIFORM(rsm_uniforms, u_cos_outer),
    GK_UNIFORM(rsm_uniforms, u_face_res),  GK_UNIFORM(rsm_uniforms, u_tan_half),
    GK_UNIFORM(rsm_uniforms, u_origin),    GK_UNIFORM(rsm_uniforms, u_code),
    GK_UNIFORM(rsm_uniforms, u_light_vp),  GK_UNIFORM(rsm_uniforms, u_face_origin),
};

/* vpl/vpl_gen.frag */
typedef struct gen_uniforms {
    GLint u_rsm_pos, u_rsm_nrm, u_rsm_flux, u_atlas_size, u_first, u_weight, u_rotation;
} gen_uniforms;
static const gk_uniform_field gen_fields[] = {
    GK_UNIFORM(gen_uniforms, u_rsm_pos),    GK_UNIFORM(gen_uniforms, u_rsm_nrm), GK_UNIFORM(gen_uniforms, u_rsm_flux),
    GK_UNIFORM(gen_uniforms, u_atlas_size), GK_UNIFORM(gen_uniforms, u_first),   GK_UNIFORM(gen_uniforms, u_weight),
    GK_UNIFORM(gen_uniforms, u_rotation),
};

/* count_define: rsm.frag's counting variant (vpl_work_rsm_begin), NULL without. */
static int render_light_rsm(vpl_state *s, const gk_gi_frame *f, const gk_gi_light *L, const gk_light *sl,
                            int first, int count, rsm_code *code, const char *count_define, gk_err *e)
{
    face faces[6];
    float tan_half;
    int kind;
    int nf = light_faces(L, sl, faces, &tan_half, &kind);
    if (nf == 0 || count <= 0)
        return 0;
    int R = VPL_RSM_RES;
    if (ensure_rsm(s, nf * R, R, e))
        return -1;
    GLuint prog = gk_program_get(s->ctx.programs, "vpl/rsm.vert", "vpl/rsm.frag", count_define, e);
    const rsm_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(rsm_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->rsm_fbo);
    const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDrawBuffers(3, bufs);
    glViewport(0, 0, s->rsm_w, s->rsm_h);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearColor(0, 0, 0, 0);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(prog);
    float near = 0.002f * s->diam, far = 2.5f * s->diam;
    float c_in = cosf(sl->inner_cone), c_out = cosf(sl->outer_cone);
    glUniform3f(u->u_light_pos, L->position.x, L->position.y, L->position.z);
    vec3 d = v3_norm(L->direction);
    glUniform3f(u->u_light_dir, d.x, d.y, d.z);
    glUniform3f(u->u_radiant, L->radiant.x, L->radiant.y, L->radiant.z);
    glUniform1i(u->u_light_kind, kind);
    glUniform1f(u->u_cos_inner, c_in);
    glUniform1f(u->u_cos_outer, c_out);
    glUniform1f(u->u_face_res, (float)R);
    mat4 ortho_vp;
    if (kind == 3)
        tan_half = ortho_face(s, f, faces[0].dir, faces[0].up, &ortho_vp);
    glUniform1f(u->u_tan_half, tan_half);
    *code = light_code(s, L, tan_half, kind == 3);
    glUniform3f(u->u_origin, s->origin[0], s->origin[1], s->origin[2]);
    glUniform3f(u->u_code, code->pos_scale, code->area_scale, code->flux_scale);
    for (int i = 0; i < nf; i++) {
        glViewport(i * R, 0, R, R);
        mat4 view = m4_look_at(L->position, v3_add(L->position, faces[i].dir), faces[i].up);
        mat4 proj = m4_perspective(2.0f * atanf(tan_half), 1.0f, near, far);
        mat4 vp = kind == 3 ? ortho_vp : m4_mul(proj, view);
        glUniformMatrix4fv(u->u_light_vp, 1, GL_FALSE, vp.m);
        glUniform2f(u->u_face_origin, (float)(i * R), 0.0f);
        if (f->draw_scene(f->draw_ctx, prog, e) != 0)
            return -1;
    }
    /* VPL generation over [first, first + count) of the VPL row. */
    GLuint gen = gk_program_get(s->ctx.programs, "common/fullscreen.vert", "vpl/vpl_gen.frag", NULL, e);
    const gen_uniforms *g = gen ? gk_program_uniforms(s->ctx.programs, gen, GK_FIELDS(gen_fields), sizeof *g, e) : NULL;
    if (!g)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->gen_fbo);
    glDrawBuffers(3, bufs);
    glDisable(GL_DEPTH_TEST);
    glViewport(first, 0, count, 1);
    glUseProgram(gen);
    for (int i = 0; i < 3; i++) {
        glActiveTexture(GL_TEXTURE0 + i);
        glBindTexture(GL_TEXTURE_2D, s->rsm_tex[i]);
    }
    glUniform1i(g->u_rsm_pos, 0);
    glUniform1i(g->u_rsm_nrm, 1);
    glUniform1i(g->u_rsm_flux, 2);
    glUniform2i(g->u_atlas_size, s->rsm_w, s->rsm_h);
    glUniform1i(g->u_first, first);
    glUniform1f(g->u_weight, (float)(s->rsm_w * s->rsm_h) / (float)count);
    float rot[2] = {0, 0};
    if (s->dbg.random_pattern) { /* per-frame Cranley–Patterson rotation (F8 oracle) */
        unsigned h = s->frame_index * 2654435761u + 12345u;
        rot[0] = (float)((h >> 8) & 0xffff) / 65536.0f;
        h = h * 1103515245u + 12345u;
        rot[1] = (float)((h >> 8) & 0xffff) / 65536.0f;
    }
    glUniform2f(g->u_rotation, rot[0], rot[1]);
    glBindVertexArray(s->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    vpl_work_rsm_gen(s, count);
    return 0;
}

int vpl_generate(vpl_state *s, const gk_gi_frame *f, gk_err *e)
{
    int n = s->n;
    if (ensure_gen(s, n, e))
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->gen_fbo);
    const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDrawBuffers(3, bufs);
    glViewport(0, 0, n, 1);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    int lit[64], n_lit = 0;
    rsm_code code[64];
    for (int i = 0; i < f->n_lights && n_lit < 64; i++) {
        (void)f->scene->lights[f->lights[i].scene_light]; /* every light type has an RSM */
        lit[n_lit++] = i;
    }
    const char *count_define = vpl_work_rsm_begin(s, f);
    for (int j = 0; j < n_lit; j++) {
        int first = n * j / n_lit, count = n * (j + 1) / n_lit - first;
        const gk_gi_light *L = &f->lights[lit[j]];
        code[j] = (rsm_code){1, 1, 1};
        if (render_light_rsm(s, f, L, &f->scene->lights[L->scene_light], first, count, &code[j], count_define, e)) {
            vpl_work_rsm_end(s);
            return -1;
        }
    }
    vpl_work_rsm_end(s);
    float *buf = malloc((size_t)n * 4 * sizeof(float) * 3);
    if (!buf)
        return gk_fail(e, GK_ERUNTIME, "vpl: out of memory reading VPLs");
    glBindFramebuffer(GL_FRAMEBUFFER, s->gen_fbo);
    for (int i = 0; i < 3; i++) {
        glReadBuffer(GL_COLOR_ATTACHMENT0 + i);
        glReadPixels(0, 0, n, 1, GL_RGBA, GL_FLOAT, buf + (size_t)i * n * 4);
    }
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    int valid = 0;
    for (int j = 0, i = 0; j < (n_lit > 0 ? n_lit : 1); j++) {
        int end = n_lit > 0 ? n * (j + 1) / n_lit : n;
        rsm_code c = n_lit > 0 ? code[j] : (rsm_code){1, 1, 1};
        for (; i < end; i++) {
            const float *p = buf + i * 4, *nn = buf + n * 4 + i * 4, *fl = buf + 2 * n * 4 + i * 4;
            gk_vpl *v = &s->st.vpl[i];
            v->pos = v3(p[0] / c.pos_scale + s->origin[0], p[1] / c.pos_scale + s->origin[1],
                        p[2] / c.pos_scale + s->origin[2]);
            v->area = p[3] / c.area_scale;
            v->nrm = v3_norm(v3(nn[0], nn[1], nn[2]));
            v->flux = v3(fmaxf(fl[0], 0) / c.flux_scale, fmaxf(fl[1], 0) / c.flux_scale, fmaxf(fl[2], 0) / c.flux_scale);
            if (!(v->flux.x + v->flux.y + v->flux.z > 0.0f) || v3_len(v->nrm) < 0.5f)
                v->flux = v3(0, 0, 0);
            else
                valid++;
        }
    }
    free(buf);
    s->st.n = n;
    s->st.n_valid = valid;
    return n;
}
