/* The distance cube-maps of the lgv method (seed 002 §3; research B.1.2 pass 2, B.6).
 *
 * Placement (unspecified in the seed): a lattice of n^3 centres over the scene's bounds (n = 2, 3, 4
 * for K = 8, 27, 64; the seed's Fig. 4 uses 27), cell centres (i + 1/2) / n of each axis. A centre
 * inside a solid (most of the six axis rays from it meet a back face first) or closer than
 * LGV_CENTRE_CLEARANCE_REL of the spacing to a triangle is pushed out: the first free point of the
 * six axis directions at steps of 1/8 of the spacing (nearest first), else it stays. Glass needs one more map per transmissive mesh (up to
 * LGV_MAX_REFRACTORS): a refractor map centred in its bounds, where photons inside the glass find
 * their exit (Szirmay-Kalos et al. [32]). And one more at the same centre with the glass left out,
 * the exit map ([32]'s environment distance map): where a photon that has just left the glass
 * (refracted out of it or reflected off it) lands (gk_lgv_debug.exit_maps). No lattice map sees the
 * floor under a glass sphere, which the sphere hides from every centre outside it; photons focused
 * there by the sphere landed on whatever surface those maps see beside it (glass's indirect light,
 * test_lgv's fig9_regions: the floor around the sphere).
 *
 * Each map: 6 faces of res^2 in 2D array layers (lgv/common.glsl's face mapping), distance as R32UI
 * float bits with min-reduced mips (mip_min.comp), normal and base colour + material code in RGBA8.
 * Integer and RGBA8 colour targets are renderable in GLES 3.0, so no float-target extension is
 * needed. The maps are rendered when the scene changes or animates (f->scene_changed). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_target.h"
#include "lgv_internal.h"

typedef struct world_tris {
    vec3 *p;   /* 3 per triangle */
    int *mesh; /* owning mesh instance per triangle */
    long n;
} world_tris;

static int collect(const gk_scene *sc, world_tris *w)
{
    long n = 0;
    for (int i = 0; i < sc->n_nodes; i++)
        for (int k = sc->nodes[i].mesh_first; k < sc->nodes[i].mesh_first + sc->nodes[i].mesh_count; k++)
            if (k >= 0 && k < sc->n_meshes)
                n += sc->meshes[k].n_triangles;
    w->p = malloc(sizeof(vec3) * 3 * (size_t)(n ? n : 1));
    w->mesh = malloc(sizeof(int) * (size_t)(n ? n : 1));
    if (!w->p || !w->mesh)
        return -1;
    long t = 0;
    int inst = 0;
    for (int i = 0; i < sc->n_nodes; i++) {
        const gk_node *node = &sc->nodes[i];
        for (int k = node->mesh_first; k < node->mesh_first + node->mesh_count; k++, inst++) {
            if (k < 0 || k >= sc->n_meshes)
                continue;
            const gk_mesh *m = &sc->meshes[k];
            for (uint32_t j = 0; j < m->n_triangles; j++, t++) {
                for (int c = 0; c < 3; c++) {
                    const float *q = m->positions + 3 * (size_t)m->indices[3 * j + (uint32_t)c];
                    w->p[3 * t + c] = m4_point(node->world, v3(q[0], q[1], q[2]));
                }
                w->mesh[t] = inst;
            }
        }
    }
    w->n = t;
    return 0;
}

/* Distance from p to triangle abc (Ericson, Real-Time Collision Detection §5.1.5). */
static float tri_dist(vec3 p, vec3 a, vec3 b, vec3 c)
{
    vec3 ab = v3_sub(b, a), ac = v3_sub(c, a), ap = v3_sub(p, a);
    float d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return v3_len(ap);
    vec3 bp = v3_sub(p, b);
    float d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return v3_len(bp);
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return v3_len(v3_sub(p, v3_add(a, v3_scale(ab, d1 / (d1 - d3)))));
    vec3 cp = v3_sub(p, c);
    float d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return v3_len(cp);
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return v3_len(v3_sub(p, v3_add(a, v3_scale(ac, d2 / (d2 - d6)))));
    float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return v3_len(v3_sub(p, v3_add(b, v3_scale(v3_sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))))));
    float den = 1.0f / (va + vb + vc);
    vec3 q = v3_add(a, v3_add(v3_scale(ab, vb * den), v3_scale(ac, vc * den)));
    return v3_len(v3_sub(p, q));
}

/* Distance along p + t d to triangle abc (Moller-Trumbore), or -1. */
static float ray_tri(vec3 p, vec3 d, vec3 a, vec3 b, vec3 c)
{
    vec3 e1 = v3_sub(b, a), e2 = v3_sub(c, a);
    vec3 h = v3_cross(d, e2);
    float det = v3_dot(e1, h);
    if (fabsf(det) < 1e-12f)
        return -1;
    float inv = 1.0f / det;
    vec3 s = v3_sub(p, a);
    float u = v3_dot(s, h) * inv;
    if (u < 0 || u > 1)
        return -1;
    vec3 q = v3_cross(s, e1);
    float v = v3_dot(d, q) * inv;
    if (v < 0 || u + v > 1)
        return -1;
    float t = v3_dot(e2, q) * inv;
    return t > 0 ? t : -1;
}

/* Free: at least `clear` from every triangle and not inside a solid: of the six axis rays from p,
   those that meet a surface mostly meet its back face first (faces wound outwards, as the builders'
   are: a room's walls face into it, a sphere's face out of it). */
static bool free_point(const world_tris *w, vec3 p, float clear)
{
    static const vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    float best[6] = {1e30f, 1e30f, 1e30f, 1e30f, 1e30f, 1e30f};
    bool back[6] = {false};
    for (long t = 0; t < w->n; t++) {
        const vec3 *q = &w->p[3 * t];
        if (tri_dist(p, q[0], q[1], q[2]) < clear)
            return false;
        vec3 ng = v3_cross(v3_sub(q[1], q[0]), v3_sub(q[2], q[0]));
        for (int k = 0; k < 6; k++) {
            float d = ray_tri(p, dirs[k], q[0], q[1], q[2]);
            if (d > 0 && d < best[k])
                best[k] = d, back[k] = v3_dot(ng, dirs[k]) > 0;
        }
    }
    int hits = 0, backs = 0;
    for (int k = 0; k < 6; k++)
        if (best[k] < 1e30f)
            hits++, backs += back[k];
    return !(hits > 0 && 2 * backs > hits);
}

int lgv_place_maps(lgv_state *s, const gk_scene *sc, int per_axis, gk_err *e)
{
    world_tris w = {0};
    if (collect(sc, &w) != 0) {
        free(w.p), free(w.mesh);
        return gk_fail(e, GK_ERUNTIME, "lgv: out of memory placing the cube-maps");
    }
    vec3 ext = v3_sub(s->bmax, s->bmin);
    float spacing = fmaxf(ext.x, fmaxf(ext.y, ext.z)) / (float)per_axis;
    float clear = LGV_CENTRE_CLEARANCE_REL * spacing;
    static const vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    s->n_maps = 0;
    for (int z = 0; z < per_axis; z++)
        for (int y = 0; y < per_axis; y++)
            for (int x = 0; x < per_axis; x++) {
                vec3 c = v3(s->bmin.x + ext.x * ((float)x + 0.5f) / (float)per_axis,
                            s->bmin.y + ext.y * ((float)y + 0.5f) / (float)per_axis,
                            s->bmin.z + ext.z * ((float)z + 0.5f) / (float)per_axis);
                vec3 best = c;
                bool ok = free_point(&w, c, clear);
                for (int k = 1; k <= 8 && !ok; k++)
                    for (int d = 0; d < 6 && !ok; d++) {
                        vec3 p = v3_add(c, v3_scale(dirs[d], spacing * (float)k / 8.0f));
                        if (free_point(&w, p, clear))
                            best = p, ok = true;
                    }
                float *o = &s->centres[4 * s->n_maps++];
                o[0] = best.x, o[1] = best.y, o[2] = best.z, o[3] = 0;
            }
    /* refractor maps: one per transmissive mesh instance, centred in its world bounds */
    s->n_refractors = 0;
    int inst = 0;
    for (int i = 0; i < sc->n_nodes; i++) {
        const gk_node *node = &sc->nodes[i];
        for (int k = node->mesh_first; k < node->mesh_first + node->mesh_count; k++, inst++) {
            if (k < 0 || k >= sc->n_meshes || s->n_refractors >= LGV_MAX_REFRACTORS)
                continue;
            const gk_mesh *m = &sc->meshes[k];
            const gk_material *mat = &sc->materials[m->material];
            if (mat->transmission <= 0.0f)
                continue;
            vec3 lo = v3(1e30f, 1e30f, 1e30f), hi = v3(-1e30f, -1e30f, -1e30f);
            for (uint32_t j = 0; j < m->n_vertices; j++) {
                const float *q = m->positions + 3 * (size_t)j;
                vec3 p = m4_point(node->world, v3(q[0], q[1], q[2]));
                lo = v3(fminf(lo.x, p.x), fminf(lo.y, p.y), fminf(lo.z, p.z));
                hi = v3(fmaxf(hi.x, p.x), fmaxf(hi.y, p.y), fmaxf(hi.z, p.z));
            }
            vec3 c = v3_scale(v3_add(lo, hi), 0.5f);
            s->refractor_draw[2 * s->n_refractors] = i, s->refractor_draw[2 * s->n_refractors + 1] = k;
            float *o = &s->centres[4 * (s->n_maps + s->n_refractors++)];
            o[0] = c.x, o[1] = c.y, o[2] = c.z, o[3] = 0.5f * v3_len(v3_sub(hi, lo));
        }
    }
    /* the exit maps: the refractors' centres again, after them (lgv/common.glsl's layer order) */
    memcpy(&s->centres[4 * (s->n_maps + s->n_refractors)], &s->centres[4 * s->n_maps],
           sizeof(float) * 4 * (size_t)s->n_refractors);
    free(w.p), free(w.mesh);
    return 0;
}

/* lgv/cubemap.{vert,frag} */
typedef struct cubemap_uniforms {
    GLint u_centre, u_face, u_near_far, u_leave_glass, u_n_refractors, u_refractor_draws;
} cubemap_uniforms;
static const gk_uniform_field cubemap_fields[] = {
    GK_UNIFORM(cubemap_uniforms, u_centre),
    GK_UNIFORM(cubemap_uniforms, u_face),
    GK_UNIFORM(cubemap_uniforms, u_near_far),
    GK_UNIFORM(cubemap_uniforms, u_leave_glass),
    GK_UNIFORM(cubemap_uniforms, u_n_refractors),
    GK_UNIFORM(cubemap_uniforms, u_refractor_draws),
};

/* lgv/mip_min.comp */
typedef struct mip_uniforms {
    GLint u_dst_res;
} mip_uniforms;
static const gk_uniform_field mip_fields[] = {GK_UNIFORM(mip_uniforms, u_dst_res)};

static GLuint array_texture(GLenum fmt, int res, int layers, int levels)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, levels, fmt, res, res, layers);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

static int ensure_maps(lgv_state *s, gk_err *e)
{
    int count = s->n_maps + 2 * s->n_refractors;
    if (s->dist_tex && s->maps_res == s->map_res && s->maps_count == count)
        return 0;
    GLuint tex[3] = {s->dist_tex, s->nrm_tex, s->alb_tex};
    glDeleteTextures(3, tex);
    glDeleteRenderbuffers(1, &s->map_depth);
    if (!s->map_fbo)
        glGenFramebuffers(1, &s->map_fbo);
    s->levels = 3; /* the partition's three loops read levels 2, 1, 0 */
    int layers = 6 * count;
    s->dist_tex = array_texture(GL_R32UI, s->map_res, layers, s->levels);
    s->nrm_tex = array_texture(GL_RGBA8, s->map_res, layers, 1);
    s->alb_tex = array_texture(GL_RGBA8, s->map_res, layers, 1);
    glGenRenderbuffers(1, &s->map_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, s->map_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, s->map_res, s->map_res);
    s->maps_res = s->map_res;
    s->maps_count = count;
    s->maps_valid = false;
    s->centres_ssbo = lgv_buffer(s->centres_ssbo, (long)sizeof(float) * 4 * (count ? count : 1), false);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->centres_ssbo);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(sizeof(float) * 4 * (size_t)count), s->centres);
    if (glGetError() != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "lgv: cannot allocate %d cube-maps of %d^2", count, s->map_res);
    return 0;
}

int lgv_render_maps(lgv_state *s, const gk_gi_frame *f, gk_err *e)
{
    if (ensure_maps(s, e) != 0)
        return -1;
    if (s->maps_valid && !f->scene_changed)
        return 0;
    s->maps_ran = true;
    gk_program_cache *pc = s->ctx.programs;
    GLuint prog = gk_program_get(pc, "lgv/cubemap.vert", "lgv/cubemap.frag", lgv_work_begin(s, LGV_WORK_MAPS), e);
    const cubemap_uniforms *u = prog ? gk_program_uniforms(pc, prog, GK_FIELDS(cubemap_fields), sizeof *u, e) : NULL;
    GLuint mip = gk_program_get_compute(pc, "lgv/mip_min.comp", NULL, e);
    const mip_uniforms *mu = mip ? gk_program_uniforms(pc, mip, GK_FIELDS(mip_fields), sizeof *mu, e) : NULL;
    if (!u || !mu)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, s->map_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s->map_depth);
    const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDrawBuffers(3, bufs);
    glViewport(0, 0, s->map_res, s->map_res);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glUseProgram(prog);
    glUniform2f(u->u_near_far, 1e-3f * s->diag, 4.0f * s->diag);
    /* which draw is which refractor's glass: the material code names it (draw_scene sets
       u_node_mesh per draw) */
    glUniform1i(u->u_n_refractors, s->n_refractors);
    if (s->n_refractors > 0)
        glUniform2iv(u->u_refractor_draws, s->n_refractors, s->refractor_draw);
    const GLuint far_bits[4] = {LGV_FAR_BITS, 0, 0, 0};
    const float zero[4] = {0, 0, 0, 0};
    for (int m = 0; m < s->maps_count; m++) {
        glUniform3f(u->u_centre, s->centres[4 * m], s->centres[4 * m + 1], s->centres[4 * m + 2]);
        glUniform1i(u->u_leave_glass, m >= s->n_maps + s->n_refractors); /* the exit maps */
        for (int face = 0; face < 6; face++) {
            int layer = 6 * m + face;
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, s->dist_tex, 0, layer);
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, s->nrm_tex, 0, layer);
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, s->alb_tex, 0, layer);
            if (m == 0 && face == 0 && gk_fbo_check("lgv cube-map", e) != 0)
                return -1;
            glClearBufferuiv(GL_COLOR, 0, far_bits);
            glClearBufferfv(GL_COLOR, 1, zero);
            glClearBufferfv(GL_COLOR, 2, zero);
            glClear(GL_DEPTH_BUFFER_BIT);
            glUniform1i(u->u_face, face);
            if (f->draw_scene(f->draw_ctx, prog, e) != 0)
                return -1;
        }
    }
    lgv_work_end(s, LGV_WORK_MAPS);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, f->hdr_fbo);
    /* min-reduced mips, every layer in one dispatch per level */
    glUseProgram(mip);
    int layers = 6 * s->maps_count;
    for (int l = 0; l + 1 < s->levels; l++) {
        int dst = s->map_res >> (l + 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        glBindImageTexture(0, s->dist_tex, l, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(1, s->dist_tex, l + 1, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
        glUniform1i(mu->u_dst_res, dst);
        glDispatchCompute((GLuint)(dst + 7) / 8, (GLuint)(dst + 7) / 8, (GLuint)layers);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    s->maps_valid = true;
    s->maps_stamp++; /* the geometry volume follows the maps (lgv_geometry.c) */
    return 0;
}
