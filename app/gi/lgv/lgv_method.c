/* The `lgv` method behind gi.h: knobs, scene set-up, the per-frame passes (each timed under `gi`):
 *   lgv_maps    K distance cube-maps + refractor maps and their min mips (only when the scene changed)
 *   lgv_trace   photon emission and tracing, LGV injection, caustic list
 *   lgv_gather  eq. (6) iterations, the volume textures
 *   lgv_sslgv   caustic photons into the screen grid, its iterations
 *   lgv_lookup  eq. (7) + the SSLGV, added to the HDR image */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "lgv_internal.h"

/* Cost priors (relative, cheapest = 1). The seed gives frame rates only (Table 1, Fig. 9: 16^3 41 Hz,
 * 32^3 40 Hz, 48^3 33 Hz at 0.6M photons on a GTX 480, i.e. the grid's share grows from ~0 to ~20%);
 * tracing and injection are linear in the photons (research B.3), the maps' rendering linear in K
 * and the texels (rendered once for a static scene, so K and the resolution cost little per frame
 * beyond the lattice search in the tracer, linear in K), the SSLGV linear in its pixels.
 *   lgv_photons: 2 + N / 16384 (a fixed part of maps lookups and the grids)  -> 1, 2, 6, 22 (/3)
 *   lgv_maps:    nearest-map search per ray segment ~ K                       -> 1, 1.3, 1.8
 *   lgv_map_res: texture footprint only                                      -> 1, 1.05, 1.2
 *   lgv_size:    Fig. 9's frame times 24.4, 25, 30.3 ms                       -> 1, 1.03, 1.24
 *   lgv_iters:   linear in the iterations over the grid                      -> 1, 1.1, 1.2, 1.4, 1.6
 *                default 0: the least rel. RMSE of the indirect light summed over glass and
 *                caustic-ring at 32 cells (README lgv: 0 / 2 / 4 iterations 1.38 / 1.66 / 1.83;
 *                0 is glass's best, 2 caustic-ring's). It was 4 while the tracer lost ~40% of
 *                the photons at the walls, which the iterations' sum made up.
 *   lgv_sslgv:   12 iterations over w x h                                    -> 1, 1.5, 3 */
enum { K_PHOTONS, K_MAPS, K_MAP_RES, K_SIZE, K_ITERS, K_SSLGV, K_COUNT };
_Static_assert(K_COUNT == LGV_KNOBS, "lgv_internal.h's LGV_KNOBS counts the knobs");
static const gk_knob_def knobs[K_COUNT] = {
    {.name = "lgv_photons", .owner = "lgv", .n_values = 4, .values = {"16384", "65536", "262144", "1048576"},
     .cost = {1.0f, 2.0f, 6.0f, 22.0f}, .default_level = 1},
    {.name = "lgv_maps", .owner = "lgv", .n_values = 3, .values = {"8", "27", "64"}, .cost = {1.0f, 1.3f, 1.8f},
     .default_level = 1},
    {.name = "lgv_map_res", .owner = "lgv", .n_values = 3, .values = {"32", "64", "128"}, .cost = {1.0f, 1.05f, 1.2f},
     .default_level = 1},
    {.name = "lgv_size", .owner = "lgv", .n_values = 3, .values = {"16", "32", "48"}, .cost = {1.0f, 1.03f, 1.24f},
     .default_level = 1},
    {.name = "lgv_iters", .owner = "lgv", .n_values = 5, .values = {"0", "2", "4", "8", "12"},
     .cost = {1.0f, 1.1f, 1.2f, 1.4f, 1.6f}, .default_level = 0},
    {.name = "lgv_sslgv", .owner = "lgv", .n_values = 3, .values = {"128", "256", "512"}, .cost = {1.0f, 1.5f, 3.0f},
     .default_level = 1},
};

static void declare_knobs(gk_budget *b)
{
    gk_budget_add_all(b, knobs, K_COUNT);
}

/* The catalogue's GK_GI_NEEDS_CAUSTICS: a drawn mirror or glass lit by a point or spot lamp (area
   lamps are point/spot lights with a size), as the scene derived it at load (features.c). */
static bool applies(const gk_scene *s) { return s->features.has_caustics; }

void gk_lgv_default_debug(gk_lgv_debug *d)
{
    memset(d, 0, sizeof *d);
    d->parts = GK_LGV_PART_ALL;
    d->itp_mode = GK_LGV_ITP_ANGLE;
    d->snap_hits = true;
    d->plane_hits = true;
    d->bounds_hits = true;
    d->refractor_surface = true;
    d->exit_maps = true;
    d->refractor_entry = true;
    d->occlusion = true;
    d->lookup_offset = 0.5f;
    d->lookup_own_cell = true;
    d->inject_lobe = true;
    d->c0 = LGV_C0;
}

static void *create(const gk_gi_context *ctx, gk_err *e)
{
    lgv_state *s = calloc(1, sizeof *s);
    if (!s) {
        gk_fail(e, GK_ERUNTIME, "lgv: out of memory");
        return NULL;
    }
    s->ctx = *ctx;
    gk_knob_handles(s->knob, knobs, K_COUNT);
    s->own_cache = gk_gi_context_own_programs(&s->ctx);
    gk_lgv_default_debug(&s->dbg);
    return s;
}

static int set_scene(void *self, const gk_scene *sc, gk_err *e)
{
    lgv_state *s = self;
    s->scene = sc;
    vec3 pad = v3_scale(v3_sub(sc->bmax, sc->bmin), 1e-3f);
    s->bmin = v3_sub(sc->bmin, pad);
    s->bmax = v3_add(sc->bmax, pad);
    s->diag = v3_len(v3_sub(s->bmax, s->bmin));
    s->area = 0;
    for (int i = 0; i < sc->n_nodes; i++) {
        const gk_node *node = &sc->nodes[i];
        for (int k = node->mesh_first; k < node->mesh_first + node->mesh_count; k++) {
            if (k < 0 || k >= sc->n_meshes)
                continue;
            const gk_mesh *m = &sc->meshes[k];
            for (uint32_t t = 0; t < m->n_triangles; t++) {
                vec3 p[3];
                for (int c = 0; c < 3; c++) {
                    const float *q = m->positions + 3 * (size_t)m->indices[3 * t + (uint32_t)c];
                    p[c] = m4_point(node->world, v3(q[0], q[1], q[2]));
                }
                s->area += 0.5f * v3_len(v3_cross(v3_sub(p[1], p[0]), v3_sub(p[2], p[0])));
            }
        }
    }
    s->lattice = 0; /* placed at the first render, with the frame's K */
    s->maps_valid = false;
    (void)e;
    return 0;
}

static void read_budget(lgv_state *s, const gk_budget *b)
{
    s->photons = (int)gk_knob_number(b, &s->knob[K_PHOTONS], 65536.0f);
    s->photons = s->photons < 64 ? 64 : s->photons;
    s->n_maps_wanted = (int)gk_knob_number(b, &s->knob[K_MAPS], 27.0f);
    s->map_res = (int)gk_knob_number(b, &s->knob[K_MAP_RES], 64.0f);
    s->lgv_size = (int)gk_knob_number(b, &s->knob[K_SIZE], 32.0f);
    s->iters = (int)gk_knob_number(b, &s->knob[K_ITERS], 0.0f);
    s->ss_width = (int)gk_knob_number(b, &s->knob[K_SSLGV], 256.0f);
}

static void read_stats(lgv_state *s)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, s->stats_ssbo);
    const GLuint *p = glMapBufferRange(GL_COPY_READ_BUFFER, 0, LGV_ST_N * 4, GL_MAP_READ_BIT);
    if (p) {
        s->st.rays = p[LGV_ST_RAYS], s->st.injected = p[LGV_ST_INJECTED], s->st.caustic = p[LGV_ST_CAUSTIC];
        s->st.escaped = p[LGV_ST_ESCAPED], s->st.sslgv_accepted = p[LGV_ST_SSLGV];
        glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    s->st.n_maps = s->n_maps, s->st.n_refractors = s->n_refractors;
    memcpy(s->st.dims, s->dims, sizeof s->dims);
    s->st.cell = s->cell;
}

static int render(void *self, const gk_gi_frame *f, gk_err *e)
{
    lgv_state *s = self;
    if (!s->scene && set_scene(s, f->scene, e))
        return -1;
    read_budget(s, f->budget);
    s->count_work = f->count_work; /* a bench counting frame (lgv_work.c) */
    s->maps_ran = false;
    /* a pass that does not run this frame (no photons: no lamp) reports no count of an earlier one */
    for (int k = 0; k < LGV_WORK_N; k++)
        s->work[k].counted = false;
    int per_axis = s->n_maps_wanted >= 64 ? 4 : (s->n_maps_wanted >= 27 ? 3 : 2);
    int rc = 0;
    gk_pass_begin(f->pass, "lgv_maps");
    if (s->lattice != per_axis || f->scene_changed) {
        rc = lgv_place_maps(s, f->scene, per_axis, e);
        s->lattice = per_axis;
        s->maps_valid = false;
    }
    rc = rc ? rc : lgv_render_maps(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    gk_pass_begin(f->pass, "lgv_trace");
    rc = lgv_trace_photons(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    gk_pass_begin(f->pass, "lgv_gather");
    rc = lgv_gather(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    gk_pass_begin(f->pass, "lgv_sslgv");
    rc = lgv_sslgv(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    gk_pass_begin(f->pass, "lgv_lookup");
    rc = lgv_lookup(s, f, e);
    gk_pass_end(f->pass);
    if (rc)
        return -1;
    s->frame_index++;
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "lgv: GL error 0x%04x during the frame", err);
    return 0;
}

static long memory_bytes(const void *self)
{
    const lgv_state *s = self;
    long layers = 6L * s->maps_count, texels = (long)s->maps_res * s->maps_res;
    long b = layers * texels * (4 * 4 / 3 + 4 + 4);                 /* R32UI with mips, 2 x RGBA8 */
    b += s->lgv_cells * 48 * 4 + s->lgv_cells * 8 * 3;              /* ints, src, acc, dst; 3 RGBA16F volumes */
    b += 12L * (s->geo_dims[0] * s->geo_dims[1] * s->geo_dims[2]);  /* geometry volume (3 uints per corner) */
    b += LGV_CAUSTIC_HEADER + (long)s->caustic_cap * LGV_CAUSTIC_BYTES;
    b += (long)s->ss_w * s->ss_h * (48 * 3 + 8 * 3);
    return b;
}

void lgv_free_gpu(lgv_state *s)
{
    GLuint tex[3] = {s->dist_tex, s->nrm_tex, s->alb_tex};
    glDeleteTextures(3, tex);
    glDeleteTextures(3, s->vol);
    glDeleteTextures(3, s->ss_img);
    glDeleteRenderbuffers(1, &s->map_depth);
    glDeleteFramebuffers(1, &s->map_fbo);
    GLuint bufs[12] = {s->centres_ssbo, s->lgv_ssbo, s->caustic_ssbo, s->stats_ssbo, s->probe_ssbo, s->src_ssbo,
                       s->acc_ssbo, s->dst_ssbo, s->ss_grid, s->ss_a, s->ss_b, s->geo_ssbo};
    glDeleteBuffers(12, bufs);
    glDeleteVertexArrays(1, &s->empty_vao);
}

static void invalidate(void *self) { ((lgv_state *)self)->maps_valid = false; }

static void destroy(void *self)
{
    lgv_state *s = self;
    if (!s)
        return;
    lgv_free_gpu(s);
    lgv_work_free(s);
    if (s->own_cache)
        gk_program_cache_destroy(s->own_cache);
    free(s);
}

void gk_lgv_set_debug(void *self, const gk_lgv_debug *d) { ((lgv_state *)self)->dbg = *d; }

const gk_lgv_stats *gk_lgv_get_stats(void *self)
{
    lgv_state *s = self;
    if (s->stats_ssbo)
        read_stats(s);
    return &s->st;
}

int gk_lgv_centres(const void *self, float *out, int cap)
{
    const lgv_state *s = self;
    int n = s->n_maps + 2 * s->n_refractors;
    n = n < cap ? n : cap;
    memcpy(out, s->centres, sizeof(float) * 4 * (size_t)n);
    return n;
}

typedef struct probe_uniforms {
    GLint u_photons;
} probe_uniforms;
static const gk_uniform_field probe_fields[] = {GK_UNIFORM(probe_uniforms, u_photons)};

int gk_lgv_probe(void *self, const float *rays, int n, float *hits, double *fetches, gk_err *e)
{
    lgv_state *s = self;
    if (!s->maps_valid)
        return gk_fail(e, GK_ERUNTIME, "lgv probe: no maps yet (render a frame first)");
    s->count_work = fetches != NULL;
    char defines[256];
    lgv_trace_defines(s, true, defines, sizeof defines);
    if (fetches && !s->work[LGV_WORK_TRACE].counting)
        return gk_fail(e, GK_ERUNTIME, "lgv probe: cannot count fetches here (no storage buffers to count into)");
    GLuint prog = gk_program_get_compute(s->ctx.programs, "lgv/trace.comp", defines, e);
    const probe_uniforms *u = prog ? gk_program_uniforms(s->ctx.programs, prog, GK_FIELDS(probe_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    float *buf = malloc(sizeof(float) * 8 * (size_t)n);
    if (!buf)
        return gk_fail(e, GK_ERUNTIME, "lgv probe: out of memory");
    for (int i = 0; i < n; i++) {
        memcpy(&buf[8 * i], &rays[6 * i], 3 * sizeof(float));
        memcpy(&buf[8 * i + 4], &rays[6 * i + 3], 3 * sizeof(float));
        buf[8 * i + 3] = buf[8 * i + 7] = 0;
    }
    s->probe_ssbo = lgv_buffer(s->probe_ssbo, (long)sizeof(float) * 8 * n, false);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->probe_ssbo);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(sizeof(float) * 8 * (size_t)n), buf);
    glUseProgram(prog);
    if (lgv_bind_tracer(s, prog, e) != 0) {
        free(buf);
        return -1;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, s->probe_ssbo);
    glUniform1i(u->u_photons, n);
    glDispatchCompute((GLuint)(n + 63) / 64, 1, 1);
    lgv_work_end(s, LGV_WORK_TRACE);
    if (fetches)
        *fetches = s->work[LGV_WORK_TRACE].value[0];
    s->count_work = false;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, s->probe_ssbo);
    const float *p = glMapBufferRange(GL_COPY_READ_BUFFER, 0, (GLsizeiptr)(sizeof(float) * 8 * (size_t)n), GL_MAP_READ_BIT);
    if (p) {
        for (int i = 0; i < n; i++)
            memcpy(&hits[4 * i], &p[8 * i], 4 * sizeof(float));
        glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    free(buf);
    return p ? n : gk_fail(e, GK_ERUNTIME, "lgv probe: cannot read the hits back");
}

const gk_gi_method gk_gi_lgv = {
    .name = "lgv",
    .applies = applies,
    .declare_knobs = declare_knobs,
    .create = create,
    .set_scene = set_scene,
    .render = render,
    .memory_bytes = memory_bytes,
    .invalidate = invalidate,
    .destroy = destroy,
    .pass_work = lgv_pass_work,
};
