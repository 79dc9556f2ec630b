/* Seed 000 passes 2, 8 and 9: the light's RSM, the specular mask's count pyramid, and the reflected
 * photons (shaders_gles/ispm/rsm.*, mask.comp, emit.comp). */
#include <math.h>
#include <string.h>

#include "gl/gl_target.h"
#include "ispm_internal.h"

/* The seed handles one spot light. A point light has no frustum of its own, and the photons only
 * start on specular texels, so the RSM is one perspective frustum from the light around the
 * bounding sphere of the specular geometry: every specular surface the light sees is in it at the
 * full resolution. The first point or spot light of the frame is the one (the seed's single light). */
static bool frame_light(ispm_state *s, const gk_gi_frame *f)
{
    ispm_light *L = &s->light;
    memset(L, 0, sizeof *L);
    const gk_scene *sc = f->scene;
    const gk_gi_light *gl = NULL;
    for (int i = 0; i < f->n_lights && !gl; i++) {
        int li = f->lights[i].scene_light;
        if (li >= 0 && li < sc->n_lights && sc->lights[li].type != GK_LIGHT_DIRECTIONAL)
            gl = &f->lights[i];
    }
    if (!gl)
        return false;
    const gk_light *sl = &sc->lights[gl->scene_light];
    vec3 bmin = v3(1e30f, 1e30f, 1e30f), bmax = v3(-1e30f, -1e30f, -1e30f);
    bool any = false;
    for (int n = 0; n < sc->n_nodes; n++) {
        const gk_node *nd = &sc->nodes[n];
        for (int k = 0; k < nd->mesh_count; k++) {
            const gk_mesh *m = &sc->meshes[nd->mesh_first + k];
            const gk_material *mat = &sc->materials[m->material];
            if (mat->light_proxy || !(mat->roughness < 0.2f && mat->metallic > 0.5f))
                continue;
            for (int c = 0; c < 8; c++) {
                vec3 p = v3(c & 1 ? m->bmax.x : m->bmin.x, c & 2 ? m->bmax.y : m->bmin.y, c & 4 ? m->bmax.z : m->bmin.z);
                p = m4_point(nd->world, p);
                bmin = v3_min(bmin, p), bmax = v3_max(bmax, p);
                any = true;
            }
        }
    }
    if (!any)
        return false;
    vec3 c = v3_scale(v3_add(bmin, bmax), 0.5f);
    float r = 0.5f * v3_len(v3_sub(bmax, bmin));
    vec3 to = v3_sub(c, gl->position);
    float dist = v3_len(to);
    /* A light inside the bounding sphere gets a 150° frustum: what lies outside it emits no
       photons (logged by nothing: no shipped scene has it; the tests do not cover it). */
    float half = dist > r * 1.0001f ? asinf(fminf(r / dist, 1.0f)) * 1.02f : 75.0f * (float)M_PI / 180.0f;
    half = fminf(half, 75.0f * (float)M_PI / 180.0f);
    vec3 dir = dist > 0.0f ? v3_scale(to, 1.0f / dist) : v3(0, -1, 0);
    vec3 up = fabsf(dir.y) > 0.99f ? v3(1, 0, 0) : v3(0, 1, 0);
    float near = fmaxf(1e-3f * s->diam, 1e-4f), far = dist + r * 1.05f + near;
    L->pos = gl->position;
    L->axis = gl->direction;
    L->radiant = gl->radiant;
    L->spot = sl->type == GK_LIGHT_SPOT;
    L->cos_outer = cosf(sl->outer_cone), L->cos_inner = cosf(sl->inner_cone);
    L->view = m4_look_at(gl->position, c, up);
    L->proj = m4_perspective(2.0f * half, 1.0f, near, far);
    L->vp = m4_mul(L->proj, L->view);
    L->inv_vp = m4_inverse(L->vp);
    L->tan_half = tanf(half);
    float t2 = L->tan_half * L->tan_half;
    L->omega_texel = 4.0f * asinf(t2 / (1.0f + t2)) / (float)(ISPM_RSM_RES * ISPM_RSM_RES);
    L->ok = true;
    return true;
}

typedef struct rsm_uniforms { GLint u_light_vp, u_light_pos; } rsm_uniforms;
static const gk_uniform_field rsm_fields[] = {GK_UNIFORM(rsm_uniforms, u_light_vp), GK_UNIFORM(rsm_uniforms, u_light_pos)};

typedef struct mask_uniforms { GLint u_rsm_nrm, u_level, u_size, u_off, u_off_prev, u_top; } mask_uniforms;
static const gk_uniform_field mask_fields[] = {
    GK_UNIFORM(mask_uniforms, u_rsm_nrm), GK_UNIFORM(mask_uniforms, u_level), GK_UNIFORM(mask_uniforms, u_size),
    GK_UNIFORM(mask_uniforms, u_off),     GK_UNIFORM(mask_uniforms, u_off_prev), GK_UNIFORM(mask_uniforms, u_top)};

typedef struct emit_uniforms {
    GLint u_rsm_depth, u_rsm_nrm, u_rsm_spec, u_rsm_diff, u_res, u_top, u_budget, u_capacity, u_faithful, u_rng_by_slot;
    GLint u_shuffle_mul, u_shuffle_add, u_light_inv_vp, u_light_rot, u_light_pos, u_light_axis, u_radiant, u_spot, u_cone,
        u_tan_half;
} emit_uniforms;
static const gk_uniform_field emit_fields[] = {
    GK_UNIFORM(emit_uniforms, u_rsm_depth),   GK_UNIFORM(emit_uniforms, u_rsm_nrm),     GK_UNIFORM(emit_uniforms, u_rsm_spec),
    GK_UNIFORM(emit_uniforms, u_rsm_diff),    GK_UNIFORM(emit_uniforms, u_res),         GK_UNIFORM(emit_uniforms, u_top),
    GK_UNIFORM(emit_uniforms, u_budget),      GK_UNIFORM(emit_uniforms, u_capacity),    GK_UNIFORM(emit_uniforms, u_faithful),
    GK_UNIFORM(emit_uniforms, u_rng_by_slot), GK_UNIFORM(emit_uniforms, u_shuffle_mul), GK_UNIFORM(emit_uniforms, u_shuffle_add),
    GK_UNIFORM(emit_uniforms, u_light_inv_vp), GK_UNIFORM(emit_uniforms, u_light_rot),  GK_UNIFORM(emit_uniforms, u_light_pos),
    GK_UNIFORM(emit_uniforms, u_light_axis),  GK_UNIFORM(emit_uniforms, u_radiant),     GK_UNIFORM(emit_uniforms, u_spot),
    GK_UNIFORM(emit_uniforms, u_cone),        GK_UNIFORM(emit_uniforms, u_tan_half)};

static int ensure_rsm(ispm_state *s, gk_err *e)
{
    if (s->rsm_fbo)
        return 0;
    gk_target t;
    const GLenum fmts[3] = {GL_RGB10_A2, GL_RGBA8, GL_RGBA8};
    if (gk_target_create(&t, "ispm rsm", ISPM_RSM_RES, ISPM_RSM_RES, 3, fmts, GL_NEAREST, true, e))
        return -1;
    s->rsm_fbo = t.fbo, s->rsm_depth = t.depth;
    for (int i = 0; i < 3; i++)
        s->rsm_tex[i] = t.color[i];
    long levels_total = 0;
    for (int l = 0; l < ISPM_RSM_LEVELS; l++)
        levels_total += (long)(ISPM_RSM_RES >> l) * (ISPM_RSM_RES >> l);
    glGenBuffers(1, &s->counts_ssbo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counts_ssbo);
    glBufferData(GL_SHADER_STORAGE_BUFFER, levels_total * 4, NULL, GL_DYNAMIC_COPY);
    return 0;
}

static int ensure_photons(ispm_state *s)
{
    if (s->photon_ssbo && s->capacity == s->photons)
        return 0;
    s->capacity = s->photons;
    if (!s->photon_ssbo)
        glGenBuffers(1, &s->photon_ssbo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->photon_ssbo);
    glBufferData(GL_SHADER_STORAGE_BUFFER, ISPM_PH_HEADER_BYTES + (long)s->capacity * ISPM_PHOTON_BYTES, NULL,
                 GL_DYNAMIC_COPY);
    if (!s->hit_buf)
        glGenBuffers(1, &s->hit_buf);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->hit_buf);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (long)s->capacity * ISPM_HIT_BYTES, NULL, GL_DYNAMIC_COPY);
    return 0;
}

static int render_rsm(ispm_state *s, const gk_gi_frame *f, gk_err *e)
{
    GLuint prog = gk_program_get(s->ctx.programs, "ispm/rsm.vert", "ispm/rsm.frag", ispm_work_rsm_begin(s), e);
    const rsm_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(rsm_fields), sizeof *u, e) : NULL;
    if (!u) {
        ispm_work_rsm_end(s);
        return -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, s->rsm_fbo);
    const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDrawBuffers(3, bufs);
    glViewport(0, 0, ISPM_RSM_RES, ISPM_RSM_RES);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(0, 0, 0, 0);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(prog);
    glUniformMatrix4fv(u->u_light_vp, 1, GL_FALSE, s->light.vp.m);
    glUniform3f(u->u_light_pos, s->light.pos.x, s->light.pos.y, s->light.pos.z);
    int rc = f->draw_scene(f->draw_ctx, prog, e);
    ispm_work_rsm_end(s);
    glDisable(GL_DEPTH_TEST);
    return rc;
}

static int build_mask(ispm_state *s, const char *count_define, gk_err *e)
{
    GLuint prog = gk_program_get_compute(s->ctx.programs, "ispm/mask.comp", count_define, e);
    const mask_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(mask_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, s->rsm_tex[0]);
    glUniform1i(u->u_rsm_nrm, 0);
    glUniform1i(u->u_top, ISPM_RSM_LEVELS - 1);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s->counts_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s->photon_ssbo);
    int off = 0, off_prev = 0;
    for (int l = 0; l < ISPM_RSM_LEVELS; l++) {
        int size = ISPM_RSM_RES >> l;
        glUniform1i(u->u_level, l);
        glUniform1i(u->u_size, size);
        glUniform1i(u->u_off, off);
        glUniform1i(u->u_off_prev, off_prev);
        glDispatchCompute((GLuint)(size + 7) / 8, (GLuint)(size + 7) / 8, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        off_prev = off;
        off += size * size;
    }
    return 0;
}

static int emit(ispm_state *s, const char *count_define, gk_err *e)
{
    GLuint prog = gk_program_get_compute(s->ctx.programs, "ispm/emit.comp", count_define, e);
    const emit_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(emit_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    const ispm_light *L = &s->light;
    glUseProgram(prog);
    for (int i = 0; i < 4; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, i == 0 ? s->rsm_depth : s->rsm_tex[i - 1]);
    }
    glUniform1i(u->u_rsm_depth, 0);
    glUniform1i(u->u_rsm_nrm, 1);
    glUniform1i(u->u_rsm_spec, 2);
    glUniform1i(u->u_rsm_diff, 3);
    glUniform1i(u->u_res, ISPM_RSM_RES);
    glUniform1i(u->u_top, ISPM_RSM_LEVELS - 1);
    glUniform1i(u->u_budget, s->photons);
    glUniform1i(u->u_capacity, s->capacity);
    glUniform1i(u->u_faithful, s->dbg.faithful_blocks);
    glUniform1i(u->u_rng_by_slot, s->dbg.rng_by_slot);
    /* An odd multiplier and an offset permute 4^k blocks; both change every frame when shuffling. */
    unsigned mul = 1, add = 0;
    if (s->dbg.shuffle) {
        unsigned h = s->dbg.shuffle * 2654435761u ^ (s->frame_index + 1) * 2246822519u;
        mul = (h | 1u) & 0xffffu, add = h >> 7;
    }
    glUniform1ui(u->u_shuffle_mul, mul);
    glUniform1ui(u->u_shuffle_add, add);
    glUniformMatrix4fv(u->u_light_inv_vp, 1, GL_FALSE, L->inv_vp.m);
    /* view -> world rotation: the transpose of the view matrix's upper 3x3 */
    float rot[9];
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            rot[c * 3 + r] = L->view.m[r * 4 + c];
    glUniformMatrix3fv(u->u_light_rot, 1, GL_FALSE, rot);
    glUniform3f(u->u_light_pos, L->pos.x, L->pos.y, L->pos.z);
    glUniform3f(u->u_light_axis, L->axis.x, L->axis.y, L->axis.z);
    glUniform3f(u->u_radiant, L->radiant.x, L->radiant.y, L->radiant.z);
    glUniform1i(u->u_spot, L->spot);
    glUniform2f(u->u_cone, L->cos_outer, L->cos_inner);
    glUniform1f(u->u_tan_half, L->tan_half);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s->counts_ssbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s->photon_ssbo);
    glDispatchCompute((GLuint)(ISPM_RSM_RES * ISPM_RSM_RES + 63) / 64, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return 0;
}

int ispm_emit_photons(ispm_state *s, const gk_gi_frame *f, bool *any, gk_err *e)
{
    *any = frame_light(s, f);
    s->st.has_specular = *any;
    if (!*any)
        return 0;
    if (ensure_rsm(s, e) || ensure_photons(s))
        return -1;
    static const unsigned zero[ISPM_PH_HEADER_UINTS];
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->photon_ssbo);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
    if (render_rsm(s, f, e))
        return -1;
    const char *count_define = ispm_work_photons_begin(s); /* the mask's and the emission's work */
    int rc = build_mask(s, count_define, e) || emit(s, count_define, e) ? -1 : 0;
    ispm_work_photons_end(s);
    return rc;
}
