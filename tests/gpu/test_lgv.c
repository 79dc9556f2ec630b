/* The lgv method (seed 002) on llvmpipe, on the shipped scenes at the references' 160x120 and on a
 * lone lit plane (research B.5):
 *   item 1/2  the cube-map tracer against exact ray casting (the reference tracer's BVH) on the same
 *             rays, photon-like (from the lamp, and cosine bounces off the surfaces the lamp's rays
 *             meet): pass-through rate (the tracer's hit lies beyond the first true surface, or it
 *             finds none), for the seed's angle-partition ITP and for the planar ITP (Fig. 4);
 *   caustic   the SSLGV's caustic against glass-caustics.exr / caustic-ring-caustics.exr inside their
 *             masks (energy, rel. RMSE) and the share of caustic photons the SSLGV accepts;
 *   item 13   the energy (LGV and SSLGV) constant as the photon count N and C0 vary;
 *   Fig. 9    the indirect light's error against SCENE-indirect.exr per LGV size, the seed's injection
 *             and the cosine lobe, without and with the gathering iterations (eq. 6); by region (the
 *             sphere, the floor under it, the walls, the rest of the floor), with the photons leaving
 *             glass traced on its exit map and on the lattice maps, and with the lookup in the
 *             surface's own cell and half a cell along the normal; the injected flux by cell layer;
 *   item 6    the LGV's temporal noise with new photons every frame; the same photons twice: identical;
 *   G         eq. (6)'s fuzzy occlusion: on light-leak the gathering carries no flux through the wall;
 *   work      each pass's work for the bench's efficiency (lgv_work.c) against hand counts on the
 *             furnace box, and the injection's atomics against the injected photons on glass; the
 *             tracer's counted texels against a CPU replay of it (tests/common/lgv_replay.c);
 *   sweep     (GK_LGV_SWEEP=1, alone) iterations x LGV sizes against the indirect references (README);
 *   Fig. 9's cause (GK_LGV_FIG9=1, alone) the error per LGV size at 1M, 4M and 16M photons, and by
 *             region at 1M and 16M;
 *   Fig. 9's chart (GK_LGV_FIG9_OUT=DIR, alone; `make bench`, tools/fig9_chart.sh) per LGV size the
 *             indirect light's error, its noise-free error and the passes' times, as a CSV and EXRs;
 * GK_LGV_ONLY=NAME runs one test; GK_LGV_EVENTS, GK_LGV_OFFSET, GK_LGV_OWN, GK_LGV_SEEING,
 * GK_LGV_BOUNDS, GK_LGV_SPHERE, GK_LGV_EXIT, GK_LGV_LOBE, GK_LGV_SNAP, GK_LGV_PLANE set the debug switches
 * max_events, lookup_offset, lookup_own_cell, seeing_maps, bounds_hits, sphere_normals, exit_maps,
 * inject_lobe, snap_hits and plane_hits for the README's experiments.
 * (The other B.5 tests are not written yet: see the README's lgv section.)
 * Bounds come from the measurements printed with each test (see the comments there). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "common/lgv_replay.h"
#include "core/tonemap.h"
#include "io/image_io.h"
#include "metrics/metrics.h"
#include "gi/lgv/lgv.h"
#include "gl/gl_program.h"
#include "gl/gl_target.h"
#include "gl/gl_timing.h"
#include "ref/bvh.h"
#include "render/scene_gpu.h"

extern const gk_gi_method gk_gi_lgv;

#define W 160
#define HH 120

typedef struct harness {
    gkt_gl gl;
    gk_program_cache *programs;
    gk_scene *scene;
    gk_scene_gpu gpu;
    gk_target gbuf, hdr;
    mat4 view, proj, vp, inv_vp;
    vec3 eye;
    gk_gi_light lights[8];
    int n_lights;
    gk_budget budget;
    void *self;
    float img[W * HH * 4];
} harness;

static harness H;
static float C0 = 1.0f; /* the SSLGV's C0 of the next frames (item 13 varies it) */
static bool OCCLUSION = true; /* eq. (6)'s G of the next frames (the leak test turns it off) */
static bool REPLACE = false;  /* the lookup reads the last gathering iteration alone */
static bool REFRACTOR = true; /* glass hits placed and shaded on its refractor map (gk_lgv_debug.refractor_surface) */
static bool COUNT = false;    /* the next frames are the bench's counting frames (lgv_work.c) */
static bool LOBE = true;      /* the next frames inject cosine lobes (gk_lgv_debug.inject_lobe, the default) */
static bool OWN_CELL = true;  /* the lookup reads the surface's own cell (gk_lgv_debug.lookup_own_cell, the default) */
static bool EXIT_MAPS = true; /* photons leaving glass traced on its exit map (gk_lgv_debug.exit_maps) */
static bool ENTRY = true;     /* photons on a specular chain meet glass on its refractor map (gk_lgv_debug.refractor_entry) */
static int SSLGV_ITERS = 0;   /* the SSLGV's gathering iterations (gk_lgv_debug.sslgv_iters; 0: the default) */
static const gk_pass_ctx *PASS; /* the next frames' clock (fig9_chart; NULL: untimed) */
static gk_frame_report REPORT;  /* with PASS: the last frame's passes, the method's under "gi" as in the bench */

static int draw_scene(void *ctx, unsigned prog, gk_err *e)
{
    harness *h = ctx;
    (void)e;
    gk_draw_uniforms u;
    gk_draw_uniforms_lookup(prog, &u);
    gk_scene_gpu_draw(&h->gpu, h->scene, &u, GK_DRAW_MATERIALS | GK_DRAW_SKIP_PROXIES);
    return 0;
}

/* The renderer's G-buffer: glass left out (render_glass.c draws it later). */
static int gbuffer(harness *h)
{
    gk_err e = {0};
    GLuint gp = gk_program_get(h->programs, "gbuffer/gbuffer.vert", "gbuffer/gbuffer.frag", NULL, &e);
    if (!gp)
        return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, h->gbuf.fbo);
    const GLenum b4[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glDrawBuffers(4, b4);
    glViewport(0, 0, W, HH);
    glClearColor(0, 0, 0, 0);
    glClearDepthf(1);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(gp);
    gk_uniform_mat4(gp, "u_viewproj", h->vp.m);
    gk_uniform_3f(gp, "u_eye", h->eye.x, h->eye.y, h->eye.z);
    gk_draw_uniforms du;
    gk_draw_uniforms_lookup(gp, &du);
    gk_scene_gpu_draw(&h->gpu, h->scene, &du, GK_DRAW_MATERIALS | GK_DRAW_SKIP_GLASS);
    glDisable(GL_DEPTH_TEST);
    return 0;
}

static int open_scene(harness *h, gk_scene *s)
{
    gk_err e = {0};
    h->scene = s;
    gk_scene_evaluate(s, 0.0f);
    gk_scene_camera(s, (float)W / (float)HH, &h->view, &h->proj, &h->eye);
    h->vp = m4_mul(h->proj, h->view);
    h->inv_vp = m4_inverse(h->vp);
    h->n_lights = 0;
    for (int i = 0; i < s->n_nodes && h->n_lights < 8; i++)
        if (s->nodes[i].light >= 0) {
            gk_gi_light *L = &h->lights[h->n_lights++];
            memset(L, 0, sizeof *L);
            L->scene_light = s->nodes[i].light, L->node = i;
            gk_scene_light_frame(s, i, &L->position, &L->direction, &L->axis_u, &L->axis_v);
        }
    if (gk_scene_gpu_upload(&h->gpu, s, &e) || gbuffer(h))
        return -1;
    gk_gi_context ctx = {.programs = h->programs, .gles_version = h->gl.egl.gles_version};
    h->self = gk_gi_lgv.create(&ctx, &e);
    if (!h->self || gk_gi_lgv.set_scene(h->self, s, &e)) {
        fprintf(stderr, "lgv: %s\n", e.msg);
        return -1;
    }
    return 0;
}

static void close_scene(harness *h)
{
    gk_gi_lgv.destroy(h->self);
    h->self = NULL;
    gk_scene_gpu_free(&h->gpu);
    gk_scene_free(h->scene);
    h->scene = NULL;
}

/* One frame with the knobs of `list` and the lookup's parts; what lgv added lands in H.img. */
static void frame(const char *list, int parts, unsigned seed)
{
    gk_err e = {0};
    gk_budget_init(&H.budget);
    gk_gi_lgv.declare_knobs(&H.budget);
    if (list && gk_budget_pin_list(&H.budget, list, &e))
        fail_msg("budget: %s", e.msg);
    gk_lgv_debug d;
    gk_lgv_default_debug(&d);
    d.parts = parts, d.seed = seed, d.c0 = C0, d.occlusion = OCCLUSION, d.gather_replace = REPLACE;
    d.refractor_surface = REFRACTOR, d.exit_maps = EXIT_MAPS, d.refractor_entry = ENTRY, d.sslgv_iters = SSLGV_ITERS;
    d.max_events = getenv("GK_LGV_EVENTS") ? atoi(getenv("GK_LGV_EVENTS")) : 0;
    if (getenv("GK_LGV_OFFSET"))
        d.lookup_offset = (float)atof(getenv("GK_LGV_OFFSET"));
    d.lookup_own_cell = OWN_CELL;
    if (getenv("GK_LGV_SNAP"))
        d.snap_hits = atoi(getenv("GK_LGV_SNAP")) != 0;
    if (getenv("GK_LGV_PLANE"))
        d.plane_hits = atoi(getenv("GK_LGV_PLANE")) != 0;
    if (getenv("GK_LGV_OWN"))
        d.lookup_own_cell = atoi(getenv("GK_LGV_OWN")) != 0;
    if (getenv("GK_LGV_SEEING"))
        d.seeing_maps = atoi(getenv("GK_LGV_SEEING")) != 0;
    if (getenv("GK_LGV_SPHERE"))
        d.sphere_normals = atoi(getenv("GK_LGV_SPHERE")) != 0;
    if (getenv("GK_LGV_BOUNDS"))
        d.bounds_hits = atoi(getenv("GK_LGV_BOUNDS")) != 0;
    d.inject_lobe = LOBE;
    if (getenv("GK_LGV_LOBE"))
        d.inject_lobe = atoi(getenv("GK_LGV_LOBE")) != 0;
    if (getenv("GK_LGV_EXIT"))
        d.exit_maps = atoi(getenv("GK_LGV_EXIT")) != 0;
    if (getenv("GK_LGV_ENTRY"))
        d.refractor_entry = atoi(getenv("GK_LGV_ENTRY")) != 0;
    gk_lgv_set_debug(H.self, &d);
    gk_gi_frame f = {0};
    f.scene = H.scene, f.width = W, f.height = HH, f.scene_changed = false;
    f.view = H.view, f.proj = H.proj, f.view_proj = H.vp, f.inv_view_proj = H.inv_vp, f.eye = H.eye;
    f.gbuf_albedo = H.gbuf.color[0], f.gbuf_normal = H.gbuf.color[1], f.gbuf_emission = H.gbuf.color[2];
    f.gbuf_depth = H.gbuf.depth, f.gbuf_specular = H.gbuf.color[3];
    f.hdr_fbo = H.hdr.fbo;
    f.n_lights = H.n_lights, f.lights = H.lights, f.budget = &H.budget;
    f.draw_scene = draw_scene, f.draw_ctx = &H;
    f.count_work = COUNT;
    f.pass = PASS;
    glBindFramebuffer(GL_FRAMEBUFFER, H.hdr.fbo);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    if (PASS) /* the renderer's clock around the method, as the renderer nests it under `gi` */
        gk_timer_frame_begin(PASS->timer), gk_timer_pass_begin(PASS->timer, "gi");
    if (gk_gi_lgv.render(H.self, &f, &e))
        fail_msg("render: %s", e.msg);
    if (PASS)
        gk_timer_pass_end(PASS->timer), gk_timer_frame_end(PASS->timer, &REPORT);
    gkt_read_rgba(&H.hdr, 0, GL_FLOAT, H.img);
}


static int setup(void **state)
{
    (void)state;
    memset(&H, 0, sizeof H);
    if (gkt_gl_open(&H.gl) != 0)
        return -1;
    H.programs = gk_program_cache_create(NULL, H.gl.egl.gles_version);
    const GLenum gb[4] = {GL_RGBA8, GL_RGBA16F, GL_RGBA16F, GL_RGBA8};
    const GLenum hf[1] = {GL_RGBA32F};
    if (gkt_target(&H.gbuf, "test gbuffer", W, HH, 4, gb, true) || gkt_target(&H.hdr, "test hdr", W, HH, 1, hf, false))
        return -1;
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    gk_target_destroy(&H.gbuf);
    gk_target_destroy(&H.hdr);
    gk_program_cache_destroy(H.programs);
    gkt_gl_close(&H.gl);
    return 0;
}

static gk_scene *load(const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "config/scenes/%s.gltf", name);
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path, &e);
    if (!s)
        fail_msg("%s", e.msg);
    return s;
}

/* ---- item 1/2: the cube-map tracer against exact ray casting ---- */

static uint32_t pcg(uint32_t *s)
{
    *s = *s * 747796405u + 2891336453u;
    uint32_t w = ((*s >> ((*s >> 28u) + 4u)) ^ *s) * 277803737u;
    return (w >> 22u) ^ w;
}
static float unit(uint32_t *s) { return (float)(pcg(s) >> 8) * (1.0f / 16777216.0f); }

static vec3 sphere_dir(uint32_t *s)
{
    float z = 1 - 2 * unit(s), phi = 6.2831853f * unit(s), r = sqrtf(fmaxf(0, 1 - z * z));
    return v3(r * cosf(phi), r * sinf(phi), z);
}

typedef struct exact {
    vec3 *verts;
    uint32_t n;
    gk_bvh bvh;
} exact;

static void exact_build(exact *x, const gk_scene *s)
{
    uint32_t n = 0;
    for (int i = 0; i < s->n_nodes; i++)
        for (int k = s->nodes[i].mesh_first; k < s->nodes[i].mesh_first + s->nodes[i].mesh_count; k++)
            if (!s->materials[s->meshes[k].material].light_proxy)
                n += s->meshes[k].n_triangles;
    x->verts = malloc(sizeof(vec3) * 3 * n);
    x->n = 0;
    for (int i = 0; i < s->n_nodes; i++)
        for (int k = s->nodes[i].mesh_first; k < s->nodes[i].mesh_first + s->nodes[i].mesh_count; k++) {
            const gk_mesh *m = &s->meshes[k];
            if (s->materials[m->material].light_proxy)
                continue;
            for (uint32_t t = 0; t < m->n_triangles; t++, x->n++)
                for (int c = 0; c < 3; c++) {
                    const float *q = m->positions + 3 * (size_t)m->indices[3 * t + (uint32_t)c];
                    x->verts[3 * x->n + (uint32_t)c] = m4_point(s->nodes[i].world, v3(q[0], q[1], q[2]));
                }
        }
    gk_err e = {0};
    assert_int_equal(gk_bvh_build(&x->bvh, x->verts, x->n, &e), 0);
}

/* Photon-like rays: half from the lamp in uniform directions, half cosine bounces off the points
   where other lamp rays first meet the scene (exactly), offset 1 mm along the normal. */
static int make_rays(const exact *x, vec3 lamp, int n, float *rays)
{
    uint32_t seed = 12345u;
    int k = 0;
    while (k < n) {
        vec3 d = sphere_dir(&seed);
        if (k % 2 == 0) {
            memcpy(&rays[6 * k], &lamp, sizeof lamp), memcpy(&rays[6 * k + 3], &d, sizeof d);
            k++;
            continue;
        }
        gk_bvh_hit hit;
        if (!gk_bvh_intersect(&x->bvh, lamp, d, 1e-4f, 1e30f, &hit))
            continue;
        const vec3 *t = &x->verts[3 * hit.tri];
        vec3 ng = v3_norm(v3_cross(v3_sub(t[1], t[0]), v3_sub(t[2], t[0])));
        if (v3_dot(ng, d) > 0)
            ng = v3_scale(ng, -1);
        vec3 p = v3_add(v3_add(lamp, v3_scale(d, hit.t)), v3_scale(ng, 1e-3f));
        vec3 r = sphere_dir(&seed);
        if (v3_dot(r, ng) < 0)
            r = v3_scale(r, -1);
        memcpy(&rays[6 * k], &p, sizeof p), memcpy(&rays[6 * k + 3], &r, sizeof r);
        k++;
    }
    return n;
}

typedef struct pass_through {
    double rate;        /* beyond the first true surface (or no hit where there is one) */
    double early;       /* before it (a surface that is not there) */
    double lost;        /* no hit at all where there is one (the photon leaves the scene) */
    double lost_at_bounds; /* of them: the true surface lies within 1% of the diagonal of where the ray leaves the bounds */
    double median_err;  /* hit position error, m */
} pass_through;

static float axis_of(vec3 v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

/* tol: a hit counts as right within this distance along the ray of the exact one. */
static void compare_rays(const exact *x, const float *rays, const float *hits, int n, float tol, pass_through *out)
{
    int beyond = 0, early = 0, valid = 0, lost = 0, at_bounds = 0;
    vec3 pad = v3_scale(v3_sub(H.scene->bmax, H.scene->bmin), 1e-3f);
    vec3 bmin = v3_sub(H.scene->bmin, pad), bmax = v3_add(H.scene->bmax, pad);
    float *err = malloc(sizeof(float) * (size_t)n);
    for (int i = 0; i < n; i++) {
        vec3 o = v3(rays[6 * i], rays[6 * i + 1], rays[6 * i + 2]), d = v3(rays[6 * i + 3], rays[6 * i + 4], rays[6 * i + 5]);
        gk_bvh_hit hit;
        if (!gk_bvh_intersect(&x->bvh, o, d, 1e-4f, 1e30f, &hit))
            continue; /* leaves the scene: nothing to pass through */
        vec3 pe = v3_add(o, v3_scale(d, hit.t));
        if (hits[4 * i + 3] < 0.5f) {
            float exit_t = 1e30f;
            for (int a = 0; a < 3; a++) {
                float da = axis_of(d, a);
                if (fabsf(da) > 1e-12f)
                    exit_t = fminf(exit_t, ((da > 0 ? axis_of(bmax, a) : axis_of(bmin, a)) - axis_of(o, a)) / da);
            }
            at_bounds += exit_t - hit.t < tol;
            beyond++, lost++;
            err[valid++] = 1e9f;
            continue;
        }
        vec3 pl = v3(hits[4 * i], hits[4 * i + 1], hits[4 * i + 2]);
        float tl = v3_dot(v3_sub(pl, o), d);
        if (tl > hit.t + tol)
            beyond++;
        else if (tl < hit.t - tol)
            early++;
        err[valid++] = v3_len(v3_sub(pl, pe));
    }
    qsort(err, (size_t)valid, sizeof(float), cmp_float);
    out->rate = (double)beyond / valid;
    out->early = (double)early / valid;
    out->lost = (double)lost / valid;
    out->lost_at_bounds = lost ? (double)at_bounds / lost : 0;
    out->median_err = err[valid / 2];
    free(err);
}

/* bound_angle: the most pass-through of the angle partition; fig4: assert the seed's Fig. 4 order
   (the angle partition passes through less than the planar ITP). */
static void tracer_on(const char *name, double bound_angle, bool fig4)
{
    gk_scene *s = load(name);
    assert_int_equal(open_scene(&H, s), 0);
    frame("lgv_photons=16384", GK_LGV_PART_ALL, 0);
    exact x;
    exact_build(&x, s);
    const int n = 65536; /* the probe takes well under a second; 4096 left Fig. 4's order to ~30 rays */
    float *rays = malloc(sizeof(float) * 6 * n), *hits = malloc(sizeof(float) * 4 * n);
    make_rays(&x, H.lights[0].position, n, rays);
    vec3 ext = v3_sub(s->bmax, s->bmin);
    float tol = 0.01f * v3_len(ext);
    /* the seed's angle partition, the planar ITP (Fig. 4), the angle partition with rays reaching the
       bounds counted as leaving (the tracer before gk_lgv_debug.bounds_hits) */
    pass_through pt[3];
    for (int k = 0; k < 3; k++) {
        gk_lgv_debug d;
        gk_lgv_default_debug(&d);
        d.itp_mode = k == 1 ? GK_LGV_ITP_PLANAR : GK_LGV_ITP_ANGLE;
        d.bounds_hits = k != 2;
        gk_lgv_set_debug(H.self, &d);
        gk_err e = {0};
        assert_int_equal(gk_lgv_probe(H.self, rays, n, hits, NULL, &e), n);
        compare_rays(&x, rays, hits, n, tol, &pt[k]);
    }
    printf("# %s, 27 maps of 64^2, %d rays, tolerance %.3f m: pass-through %.4f angle partition / %.4f planar ITP; "
           "early hits %.4f / %.4f; no hit at all %.4f / %.4f; median hit error %.4f / %.4f m\n",
           name, n, tol, pt[0].rate, pt[1].rate, pt[0].early, pt[1].early, pt[0].lost, pt[1].lost, pt[0].median_err,
           pt[1].median_err);
    printf("# %s, angle partition, rays reaching the bounds left the scene (no bounds hits): pass-through %.4f, no hit "
           "at all %.4f, of them with the true surface at the bounds %.3f\n", name, pt[2].rate, pt[2].lost, pt[2].lost_at_bounds);
    assert_true(pt[0].rate <= bound_angle);
    if (fig4)
        assert_true(pt[0].rate < pt[1].rate);
    /* the bounds hits find what the error test missed: nearly every ray without a hit had its surface
       at the bounds (measured 0.997 and 0.996), and with them almost none is left (0.0002, 0.0006) */
    assert_true(pt[2].lost > 0.05 && pt[2].lost_at_bounds > 0.95);
    assert_true(pt[0].lost < 0.005);
    free(rays), free(hits);
    gk_bvh_free(&x.bvh);
    free(x.verts);
    close_scene(&H);
}

static void tracer_against_exact_rays(void **state)
{
    (void)state;
    /* Measured on llvmpipe (deterministic rays and maps, 65536 rays): pass-through glass 0.0104 angle
       partition / 0.0082 planar, caustic-ring 0.0058 / 0.0077; early hits 0.0068 / 0.0181 and 0.0322 /
       0.0257. Before the bounds hits (gk_lgv_debug.bounds_hits) 0.107 / 0.142 with the angle partition,
       nearly all of it rays with no hit (0.098, 0.137) whose true surface was a wall at the bounds;
       before the second march on the photon's own map (4096 rays) 0.1235 / 0.2155 and 0.2145 / 0.2904.
       Fig. 4's order (angle partition < planar) holds on caustic-ring, whose concave ring is Fig. 3a's
       case; on glass (a sphere in a box, nothing concave) the two are within 0.003 and the planar ITP
       is the lower since the bounds hits (its early hits are 2.7x the angle partition's). Bounds: the
       measurement + ~0.01. */
    tracer_on("glass", 0.02, false);
    tracer_on("caustic-ring", 0.015, true);
}

/* ---- the caustic against the path-traced reference (issue: energy in the mask within 15%) ---- */

/* Where Fig. 9's error lies: glass's pixels in regions, from the scene's "sphere" param, its bounds
   (the box) and the view rays through the pixels' centres (top row first, as the references): the
   sphere's own pixels, the floor within 2.5 radii of its contact point (where the sphere focuses the
   room's light: L D S+ D, in the LGV), and the rest by the surface the ray leaves the box through:
   the walls (left, right, back), the ceiling, the rest of the floor; and the walls' and the rest of
   the floor's pixels within one 16-cell LGV cell of the box's edge (the open front's included):
   where a coarse cell holds two surfaces' photons. */
enum { REGION_WALLS, REGION_SPHERE, REGION_FLOOR, REGION_CEILING, REGION_FLOOR_REST, REGION_EDGES, REGIONS };
static const char *const REGION_NAMES[REGIONS] = {"walls", "sphere", "floor under it", "ceiling", "rest of the floor",
                                                  "walls' and floor's edges"};

/* The box surface a ray from inside the box (or through its open front) leaves it through. */
static unsigned char box_surface(vec3 o, vec3 d, vec3 bmin, vec3 bmax)
{
    float t[3];
    for (int a = 0; a < 3; a++) {
        float da = a == 0 ? d.x : (a == 1 ? d.y : d.z), oa = a == 0 ? o.x : (a == 1 ? o.y : o.z);
        float lo = a == 0 ? bmin.x : (a == 1 ? bmin.y : bmin.z), hi = a == 0 ? bmax.x : (a == 1 ? bmax.y : bmax.z);
        t[a] = da == 0.0f ? INFINITY : ((da > 0 ? hi : lo) - oa) / da;
    }
    int a = (t[1] <= t[0] && t[1] <= t[2]) ? 1 : (t[0] <= t[2] ? 0 : 2);
    if (a == 1 && d.y > 0)
        return REGION_CEILING;
    vec3 p = v3_add(o, v3_scale(d, t[a])), ext = v3_sub(bmax, bmin);
    float edge = fmaxf(ext.x, fmaxf(ext.y, ext.z)) / 16.0f, near = INFINITY;
    const float lo[3] = {p.x - bmin.x, p.y - bmin.y, p.z - bmin.z}, hi[3] = {bmax.x - p.x, bmax.y - p.y, bmax.z - p.z};
    for (int b = 0; b < 3; b++)
        if (b != a)
            near = fminf(near, fminf(lo[b], hi[b]));
    if (near < edge)
        return REGION_EDGES;
    return a == 1 ? REGION_FLOOR_REST : REGION_WALLS;
}

static void glass_regions(unsigned char *region)
{
    gk_scene *s = load("glass");
    float sp[4];
    assert_int_equal(gk_scene_param(s, "sphere", sp, 4), 4);
    vec3 bmin = s->bmin, bmax = s->bmax;
    gk_scene_free(s);
    vec3 c = v3(sp[0], sp[1], sp[2]);
    float rad = sp[3], floor_y = sp[1] - sp[3];
    for (int y = 0; y < HH; y++)
        for (int x = 0; x < W; x++) {
            vec4 q = m4_vec4(H.inv_vp, (vec4){2.0f * ((float)x + 0.5f) / W - 1.0f, 1.0f - 2.0f * ((float)y + 0.5f) / HH, 1.0f, 1.0f});
            vec3 d = v3_norm(v3_sub(v3(q.x / q.w, q.y / q.w, q.z / q.w), H.eye)), oc = v3_sub(H.eye, c);
            float b = v3_dot(oc, d), disc = b * b - (v3_dot(oc, oc) - rad * rad);
            unsigned char k = box_surface(H.eye, d, bmin, bmax);
            if (disc > 0 && -b - sqrtf(disc) > 0)
                k = REGION_SPHERE;
            else if (d.y < 0) {
                vec3 p = v3_add(H.eye, v3_scale(d, (floor_y - H.eye.y) / d.y));
                if (hypotf(p.x - c.x, p.z - c.z) < 2.5f * rad)
                    k = REGION_FLOOR;
            }
            region[y * W + x] = k;
        }
}

typedef struct ruler {
    double energy;  /* sum of luminance inside the reference's mask, lgv / reference */
    double rel_in;  /* rel. RMSE inside the mask */
    double rel_all; /* rel. RMSE over the whole image */
    double energy_near[2]; /* with a mask: the energy inside it grown by 2 and by 4 pixels */
    double energy_total;   /* with a mask: the energy over the whole image */
    double hidden_share;   /* with HIDDEN: ours in those pixels over the reference's whole image */
    double energy_all;     /* ours over the reference's, every pixel (HIDDEN's too) */
    double noise, bias;    /* indirect_on: the average's photon noise and its error without it (noise_free_error) */
} ruler;

/* Pixels left out of the grown and whole-image energies (NULL: none): glass's sphere, where the
   reference shows the glass and the harness, which draws no glass pass, shows the floor behind it
   (the G-buffer leaves glass out), caustic and all. */
static const unsigned char *HIDDEN;

/* Luminance sums of ours and the reference over the mask grown by `grow` pixels (a square). */
static double grown_energy(const gk_image *ref, const gk_image *ours, const unsigned char *mask, int grow)
{
    double eo = 0, er = 0;
    for (int y = 0; y < HH; y++)
        for (int x = 0; x < W; x++) {
            if (HIDDEN && HIDDEN[y * W + x])
                continue;
            bool in = false;
            for (int dy = -grow; dy <= grow && !in; dy++)
                for (int dx = -grow; dx <= grow && !in; dx++) {
                    int u = x + dx, v = y + dy;
                    in = u >= 0 && v >= 0 && u < W && v < HH && mask[v * W + u];
                }
            if (!in)
                continue;
            const float *o = &ours->pixels[(y * W + x) * 3], *f = &ref->pixels[(y * W + x) * ref->channels];
            eo += gk_luminance(o[0], o[1], o[2]), er += gk_luminance(f[0], f[1], f[2]);
        }
    return eo / er;
}

/* H.img (bottom row first) as an image (top row first), like the references. */
static void as_image(gk_image *out)
{
    assert_int_equal(gk_image_alloc(out, W, HH, 3), 0);
    for (int y = 0; y < HH; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                out->pixels[((HH - 1 - y) * W + x) * 3 + c] = H.img[(y * W + x) * 4 + c];
}

/* Compares what the last frame added against ref_path inside mask_path (NULL: energy over the image). */
static void measure(const char *ref_path, const char *mask_path, ruler *r)
{
    gk_err e = {0};
    gk_image ref = {0}, mimg = {0}, ours = {0};
    assert_int_equal(gk_image_read(ref_path, &ref, &e), 0);
    assert_int_equal(ref.width, W);
    as_image(&ours);
    const char *dump = getenv("GK_LGV_DUMP"); /* a folder: what was measured, for looking at */
    if (dump) { /* numbered in the order measured, so a test's configurations do not overwrite each other */
        static int dumped;
        char path[512];
        const char *base = strrchr(ref_path, '/');
        snprintf(path, sizeof path, "%s/lgv-%02d-%s", dump, dumped++, base ? base + 1 : ref_path);
        gk_image_write_float(path, &ours, NULL, &e);
    }
    unsigned char *mask = NULL;
    if (mask_path) {
        assert_int_equal(gk_image_read(mask_path, &mimg, &e), 0);
        mask = gk_mask_from_image(&mimg);
        assert_non_null(mask);
    }
    double eo = 0, er = 0;
    for (int i = 0; i < W * HH; i++)
        if (!mask || mask[i]) {
            const float *o = &ours.pixels[i * 3], *f = &ref.pixels[i * ref.channels];
            eo += gk_luminance(o[0], o[1], o[2]), er += gk_luminance(f[0], f[1], f[2]);
        }
    r->energy = eo / er;
    gk_metrics m;
    double exposure = gk_metrics_auto_exposure(&ref);
    r->rel_in = 0;
    if (mask) {
        assert_int_equal(gk_metrics_compute_masked(&ref, &ours, exposure, mask, &m, &e), 0);
        r->rel_in = m.rel_rmse;
        r->energy_near[0] = grown_energy(&ref, &ours, mask, 2);
        r->energy_near[1] = grown_energy(&ref, &ours, mask, 4);
        r->energy_total = grown_energy(&ref, &ours, mask, W);
    }
    double hidden = 0, ref_all = 0, ours_all = 0;
    for (int i = 0; i < W * HH; i++) {
        const float *o = &ours.pixels[i * 3], *f = &ref.pixels[i * ref.channels];
        hidden += HIDDEN && HIDDEN[i] ? gk_luminance(o[0], o[1], o[2]) : 0.0;
        ours_all += gk_luminance(o[0], o[1], o[2]);
        ref_all += gk_luminance(f[0], f[1], f[2]);
    }
    r->hidden_share = hidden / ref_all;
    r->energy_all = ours_all / ref_all;
    assert_int_equal(gk_metrics_compute(&ref, &ours, exposure, &m, &e), 0);
    r->rel_all = m.rel_rmse;
    free(mask);
    gk_image_free(&ref);
    gk_image_free(&mimg);
    gk_image_free(&ours);
}

/* The light's photons that meet glass's sphere, from the scene's "sphere" and "light_position" params:
   N times the solid angle the sphere subtends at the point lamp over 4 pi. */
static double photons_at_the_sphere(const gk_scene *s, double n)
{
    float sp[4], lp[3];
    assert_int_equal(gk_scene_param(s, "sphere", sp, 4), 4);
    assert_int_equal(gk_scene_param(s, "light_position", lp, 3), 3);
    double d2 = (sp[0] - lp[0]) * (sp[0] - lp[0]) + (sp[1] - lp[1]) * (sp[1] - lp[1]) + (sp[2] - lp[2]) * (sp[2] - lp[2]);
    return n * 0.5 * (1.0 - sqrt(1.0 - (double)sp[3] * sp[3] / d2));
}

/* The SSLGV's caustic of `name` against its caustics reference and mask; on glass also the caustic
   photons over the light's photons that meet the sphere (*caught), and the grown and whole-image
   energies without the sphere's pixels (HIDDEN). */
static void caustic_on(const char *name, const char *budget, ruler *r, double *accepted, double *caught)
{
    char ref[128], mask[128];
    snprintf(ref, sizeof ref, "tests/references/%s-caustics.exr", name);
    snprintf(mask, sizeof mask, "tests/references/%s-caustics-mask.png", name);
    gk_scene *scene = load(name);
    bool glass = strcmp(name, "glass") == 0;
    double aimed = glass ? photons_at_the_sphere(scene, 262144.0) : 0.0;
    assert_int_equal(open_scene(&H, scene), 0);
    frame(budget, GK_LGV_PART_SSLGV, 0);
    static unsigned char region[W * HH], sphere[W * HH];
    if (glass) {
        glass_regions(region);
        for (int i = 0; i < W * HH; i++)
            sphere[i] = region[i] == REGION_SPHERE;
        HIDDEN = sphere;
    }
    measure(ref, mask, r);
    HIDDEN = NULL;
    const gk_lgv_stats *st = gk_lgv_get_stats(H.self);
    *accepted = (double)st->sslgv_accepted / (double)st->caustic;
    *caught = glass ? st->caustic / aimed : 0.0;
    printf("# %s caustic (SSLGV) [%s]: energy in the mask %.3f, rel. RMSE inside %.3f, whole image %.3f; "
           "%u caustic photons, %u accepted (%.3f); energy in the mask grown by 2 / 4 pixels %.3f / %.3f, "
           "over the image %.3f\n",
           name, budget, r->energy, r->rel_in, r->rel_all, st->caustic, st->sslgv_accepted, *accepted,
           r->energy_near[0], r->energy_near[1], r->energy_total);
    if (glass)
        printf("#   (grown and whole-image energies without the sphere's pixels; ours in them: %.3f of the "
               "reference's image); photons at the sphere %.0f, caustic photons over them %.3f\n",
               r->hidden_share, aimed, *caught);
    close_scene(&H);
}

static void caustic_against_reference(void **state)
{
    (void)state;
    ruler g, c, g0, g1, gi;
    double ga, ca, g0a, g1a, gc, cc, g0c, g1c, gia, gic;
    caustic_on("glass", "lgv_photons=262144", &g, &ga, &gc);
    SSLGV_ITERS = 1; /* the SSLGV's gathering: one iteration against the default 12, on the same photons */
    caustic_on("glass", "lgv_photons=262144", &gi, &gia, &gic);
    SSLGV_ITERS = 0;
    printf("# glass, SSLGV gathering 12 / 1 iterations: energy over every pixel %.4f / %.4f (ratio %.4f), "
           "in the mask %.3f / %.3f, rel. RMSE inside %.3f / %.3f\n",
           g.energy_all, gi.energy_all, g.energy_all / gi.energy_all, g.energy, gi.energy, g.rel_in, gi.rel_in);
    caustic_on("caustic-ring", "lgv_photons=262144", &c, &ca, &cc);
    ENTRY = false; /* photons meet glass where the lattice maps see it (before gk_lgv_debug.refractor_entry) */
    caustic_on("glass", "lgv_photons=262144", &g1, &g1a, &g1c);
    REFRACTOR = false; /* glass as the lattice maps see it: the place and normal of the hit map's texel */
    caustic_on("glass", "lgv_photons=262144", &g0, &g0a, &g0c);
    REFRACTOR = true, ENTRY = true;
    if (getenv("GK_LGV_EXPLORE")) { /* the richer maps, for the README's numbers */
        caustic_on("glass", "lgv_photons=262144,lgv_map_res=128", &g, &ga, &gc);
        caustic_on("caustic-ring", "lgv_photons=262144,lgv_map_res=128,lgv_maps=64", &c, &ca, &cc);
    }
    /* Measured (llvmpipe, 0.26M photons, 27 maps of 64^2, SSLGV 256 wide): glass 0.932 in the mask,
       rel. RMSE inside 0.183; without the sphere's pixels 0.980 over the image and 0.989 in the mask grown
       by 2 pixels; 3149 caustic photons, 0.959 of the 3283 the solid angle sends at the sphere.
       Where the energy had gone (gk_lgv_debug.refractor_entry off, as before it): the lattice maps see
       the sphere from afar, a few texels each, and of the 3,229 light photons whose first segment
       meets the sphere (counted in the tracer against the exact sphere) 886 passed through that coarse
       copy to a diffuse surface behind it, the rim's and part of the focus's: 2316 caustic photons
       (0.705 of 3283), 0.729 in the mask, rel. RMSE inside 0.314, 0.751 over the image without the
       sphere's pixels. The other candidates measured small: 26 of the photons on a specular chain
       escaped, 1 died at the 6-event cap, none was lost inside the glass; 0.963 of the caustic photons
       accepted by the SSLGV. Over the whole image that run read 0.849 because the harness adds the
       SSLGV on the floor behind the sphere, where the reference shows the glass: ours there is 0.114
       of the reference's image (0.181 now), so "over the image" now leaves those pixels out.
       Before the exit maps (gk_lgv_debug.exit_maps: the photons leaving the sphere traced on the
       lattice maps, which do not see the floor next to its contact point) 0.974 in the mask but rel.
       RMSE inside 0.993: a small bright triangle where the reference has an ellipse. With glass as
       the lattice maps see it (REFRACTOR and ENTRY false) 0.697 in the mask, rel. RMSE inside 0.362:
       a photon leaving the sphere met the lattice maps' coarse copy of it, up to a texel footprint
       outside, at once, and bounced in and out until the 6-event cap. Before the acceptance fixes
       0.189 with 524 accepted. caustic-ring 0.510 (most of its caustic photons land off screen at the
       references' view; 24 events instead of 6: 0.568, its ring needs several mirror bounces).
       Bounds: the issue's +-15% in the mask; glass's shape in it (rel. RMSE < 0.25: 0.31 without the
       refractor entry, 0.99 before the exit maps); caustic photons over those at the sphere 0.92-1.03
       (escapes, the cap and the rim's grazing rays lose ~4%, the hash's Poisson noise ~1.8%; 0.705
       without the entry); without the entry and lattice-only below 0.80 in the mask; caustic-ring the
       measurement +- 0.05.
       The SSLGV's gathering keeps its energy and does not carry the focus out of the mask: 12
       iterations against 1 on the same photons, energy over every pixel 1.1403 / 1.1404 (ratio
       0.9998: what one pixel gives its neighbour takes; the rest is float rounding), in the mask 0.932
       both, rel. RMSE inside 0.183 both (h = C0 sqrt(A/N), ~2.7 mm here, is below most neighbouring
       pixels' distance on the floor, so little is exchanged); asserted within 0.2%. */
    assert_true(fabs(g.energy_all / gi.energy_all - 1.0) < 0.002);
    assert_true(g.energy > 0.85 && g.energy < 1.15);
    assert_true(g.rel_in < 0.25);
    assert_true(g.energy_near[0] > 0.85 && g.energy_near[0] < 1.15);
    assert_true(g.energy_total > 0.85 && g.energy_total < 1.15);
    assert_true(gc > 0.92 && gc < 1.03);
    assert_true(ga > 0.92);
    assert_true(g1.energy < 0.80 && g1c < 0.80);
    assert_true(g0.energy < 0.80);
    assert_true(c.energy > 0.46 && c.energy < 0.56);
}

static double mean_luminance(void)
{
    double sum = 0;
    for (int i = 0; i < W * HH; i++)
        sum += gk_luminance(H.img[4 * i], H.img[4 * i + 1], H.img[4 * i + 2]);
    return sum / (W * HH);
}

/* Mean luminance of what lgv adds over `frames` frames of a fresh method on glass (frame 0's photon
   hash keys first: the same photons for the same N, whatever ran before). */
static double mean_over(const char *budget, int parts, int frames, unsigned *accepted)
{
    assert_int_equal(open_scene(&H, load("glass")), 0);
    double sum = 0;
    *accepted = 0;
    for (int f = 0; f < frames; f++) {
        frame(budget, parts, 0);
        sum += mean_luminance();
        *accepted += gk_lgv_get_stats(H.self)->sslgv_accepted;
    }
    close_scene(&H);
    return sum / frames;
}

/* B.5 item 13: the energy does not depend on N (eq. 4's errata fixed: k instead of A C0^2 / 4N)
   nor on C0 (it only sets the SSLGV's acceptance radius h and the reach of its diffusion). N is
   varied at the same total of 1M photons (16, 4, 1 frames), so each estimate has ~7,000 caustic
   photons (Poisson noise ~1.2%) and ~0.5M LGV injections; C0 on the same photons (1M). */
static void energy_constant_in_n_and_c0(void **state)
{
    (void)state;
    static const char *const counts[3] = {"lgv_photons=65536", "lgv_photons=262144", "lgv_photons=1048576"};
    static const int frames[3] = {16, 4, 1};
    static const float c0s[3] = {0.5f, 1.0f, 2.0f};
    double lgv[3], ssn[3], ssc[3];
    unsigned acc[3], dummy;
    for (int i = 0; i < 3; i++) {
        lgv[i] = mean_over(counts[i], GK_LGV_PART_LGV, frames[i], &dummy);
        ssn[i] = mean_over(counts[i], GK_LGV_PART_SSLGV, frames[i], &dummy);
    }
    for (int i = 0; i < 3; i++) {
        C0 = c0s[i];
        ssc[i] = mean_over("lgv_photons=1048576", GK_LGV_PART_SSLGV, 1, &acc[i]);
    }
    C0 = 1.0f;
    printf("# glass, mean indirect (LGV) at N = 65536 / 262144 / 1048576: %.5f / %.5f / %.5f (ratios %.4f %.4f)\n",
           lgv[0], lgv[1], lgv[2], lgv[0] / lgv[1], lgv[2] / lgv[1]);
    printf("# glass, mean caustic (SSLGV) at N = 65536 / 262144 / 1048576: %.5f / %.5f / %.5f (ratios %.4f %.4f)\n",
           ssn[0], ssn[1], ssn[2], ssn[0] / ssn[1], ssn[2] / ssn[1]);
    printf("# glass, mean caustic (SSLGV) at C0 = 0.5 / 1 / 2: %.5f / %.5f / %.5f (ratios %.4f %.4f); accepted %u / %u / %u\n",
           ssc[0], ssc[1], ssc[2], ssc[0] / ssc[1], ssc[2] / ssc[1], acc[0], acc[1], acc[2]);
    for (int i = 0; i < 3; i += 2) { /* the tolerance, against 262144 photons and C0 = 1 */
        assert_true(fabs(lgv[i] / lgv[1] - 1.0) <= 0.02);
        assert_true(fabs(ssn[i] / ssn[1] - 1.0) <= 0.02);
        assert_true(fabs(ssc[i] / ssc[1] - 1.0) <= 0.02);
    }
}

/* The error of the average of two independent halves a and b (images as the references: top row first,
   RGB) against ref, with the photon noise taken out: the halves' difference has twice the noise of
   one half, so rms(a - b) / 2 is the average's noise, and it adds to the bias in quadrature (the
   noise is independent of the bias): bias^2 = err^2 - noise^2. Rel. RMSE as gk_metrics and
   region_parts (sqrt(sum of squares / values) / the reference's mean). *err and *noise get the
   average's error and noise; returns the bias (0 when the noise exceeds the error). */
static double noise_free_error(const gk_image *ref, const float *a, const float *b, double *err, double *noise)
{
    double sq = 0, dq = 0, mean = 0, values = 3.0 * W * HH;
    for (int i = 0; i < W * HH; i++)
        for (int ch = 0; ch < 3; ch++) {
            double r = ref->pixels[i * ref->channels + ch], x = a[i * 3 + ch], y = b[i * 3 + ch];
            sq += (0.5 * (x + y) - r) * (0.5 * (x + y) - r);
            dq += (x - y) * (x - y);
            mean += r;
        }
    mean /= values;
    *err = sqrt(sq / values) / mean;
    *noise = 0.5 * sqrt(dq / values) / mean;
    return sqrt(fmax(*err * *err - *noise * *noise, 0.0));
}

/* The indirect light (LGV only) of `scene` at `budget`, 4 frames averaged, against its indirect reference. */
static void indirect_on(const char *scene, const char *budget, ruler *r)
{
    char ref[128];
    snprintf(ref, sizeof ref, "tests/references/%s-indirect.exr", scene);
    assert_int_equal(open_scene(&H, load(scene)), 0);
    static float sum[W * HH * 4], half[2][W * HH * 4];
    memset(sum, 0, sizeof sum);
    memset(half, 0, sizeof half);
    for (int f = 0; f < 4; f++) {
        frame(budget, GK_LGV_PART_LGV, 0);
        for (int k = 0; k < W * HH * 4; k++)
            sum[k] += 0.25f * H.img[k], half[f / 2][k] += 0.5f * H.img[k];
    }
    gk_image ref_img = {0}, ha = {0}, hb = {0};
    gk_err e = {0};
    assert_int_equal(gk_image_read(ref, &ref_img, &e), 0);
    memcpy(H.img, half[0], sizeof sum), as_image(&ha);
    memcpy(H.img, half[1], sizeof sum), as_image(&hb);
    double err;
    r->bias = noise_free_error(&ref_img, ha.pixels, hb.pixels, &err, &r->noise);
    gk_image_free(&ref_img), gk_image_free(&ha), gk_image_free(&hb);
    memcpy(H.img, sum, sizeof sum);
    measure(ref, NULL, r);
    const gk_lgv_stats *st = gk_lgv_get_stats(H.self);
    printf("# %s [%s]: dims %dx%dx%d, cell %.4f m; last frame: %u ray segments, %u injected, %u escaped; "
           "rel. RMSE %.3f, energy %.3f; noise %.4f, noise-free error %.4f\n", scene, budget, st->dims[0], st->dims[1],
           st->dims[2], st->cell, st->rays, st->injected, st->escaped, r->rel_all, r->energy, r->noise, r->bias);
    close_scene(&H);
}

/* Seed Fig. 9, the LGV-size trade-off: the indirect light (the LGV's eq. 7 lookup, no caustic) against
   SCENE-indirect.exr per lgv_size, at 1M photons (4 frames of 262144 averaged), with no gathering
   iterations (the density estimate alone, the default), on glass and caustic-ring, with the seed's
   injection (eq. 4-5 as written) and with the cosine lobe (gk_lgv_debug.inject_lobe, the default);
   and on glass with 2 iterations. The time side is the bench's (tools/bench.sh, sweep lgv);
   fig9_regions says where the error lies, the photon study (GK_LGV_FIG9) what more photons change. */
static void lgv_size_tradeoff(void **state)
{
    (void)state;
    static const char *const sizes[3] = {"16", "32", "48"};
    static const char *const scenes[2] = {"glass", "caustic-ring"};
    static const char *const injections[2] = {"seed's injection", "lobe injection"};
    double err[2][2][3], ratio[2][2][3], err2[3], ratio2[3], bias[3] = {0}, noise[3] = {0};
    bool lobe_default = LOBE;
    for (int k = 0; k < 2; k++)
        for (int sc = 0; sc < 2; sc++)
            for (int i = 0; i < 3; i++) {
                char budget[96];
                snprintf(budget, sizeof budget, "lgv_photons=262144,lgv_size=%s,lgv_iters=0", sizes[i]);
                LOBE = k == 1;
                ruler r;
                indirect_on(scenes[sc], budget, &r);
                err[k][sc][i] = r.rel_all, ratio[k][sc][i] = r.energy;
                if (k == 1 && sc == 0)
                    bias[i] = r.bias, noise[i] = r.noise;
            }
    LOBE = lobe_default;
    for (int i = 0; i < 3; i++) {
        char budget[96];
        snprintf(budget, sizeof budget, "lgv_photons=262144,lgv_size=%s,lgv_iters=2", sizes[i]);
        ruler r;
        indirect_on("glass", budget, &r);
        err2[i] = r.rel_all, ratio2[i] = r.energy;
    }
    for (int k = 0; k < 2; k++)
        for (int sc = 0; sc < 2; sc++)
            printf("# %s indirect (LGV, %s, no gathering) vs %s-indirect.exr: rel. RMSE %.3f / %.3f / %.3f at 16 / 32 / "
                   "48 cells; energy ratio %.3f / %.3f / %.3f\n", scenes[sc], injections[k], scenes[sc], err[k][sc][0],
                   err[k][sc][1], err[k][sc][2], ratio[k][sc][0], ratio[k][sc][1], ratio[k][sc][2]);
    printf("# glass indirect (LGV, the default injection, 2 gathering iterations): rel. RMSE %.3f / %.3f / %.3f; energy "
           "ratio %.3f / %.3f / %.3f\n", err2[0], err2[1], err2[2], ratio2[0], ratio2[1], ratio2[2]);
    printf("# Fig. 9, glass indirect (LGV, the lobe injection, no gathering, 1M photons): noise %.4f / %.4f / %.4f, the error "
           "without it %.4f / %.4f / %.4f at 16 / 32 / 48 cells\n", noise[0], noise[1], noise[2], bias[0], bias[1], bias[2]);
    fflush(stdout);
    /* Measured (llvmpipe, 4 x 262144 photons, deterministic; the own-cell lookup and the plane hits,
       the defaults): glass, the seed's injection 0.525 / 0.528 / 0.538, energy 0.963 / 0.938 / 0.929;
       the lobe 0.278 / 0.242 / 0.249, energy 1.017 / 0.993 / 0.985 (snapped: 0.282 / 0.253 / 0.266;
       fig9_regions: the walls, 0.69 / 0.68 / 0.68 of the reference's with the seed's, 0.99 / 0.98 /
       0.98 with the lobe). With the half-cell lookup the lobe's energy fell 1.002 / 0.963 / 0.940 with
       the size (4% from 16 to 32 cells): it read glass's faces, f = 0.016 / 0.032 / 0.048 of a cell
       inside their cells, at 1 - f (fig9_regions). Caustic-ring, seed's / lobe: 0.571 / 0.652 / 0.680
       and 0.574 / 0.649 / 0.673, energy ~0.53 / 0.47 / 0.45 either way (its indirect is mostly light
       after several mirror bounces on the ring: README lgv). 2 iterations with the lobe 0.831 / 0.796 /
       0.796, energy 1.573 / 1.547 / 1.539. The plain error rises from 32 to 48 cells at 1M photons: the
       noise at 48 cells outweighs the grid's gain (the photon study, README lgv; the trend below).
       Bounds: glass's lobe error the measurement + 0.03 and at most 0.6x the seed's at every size (the
       walls' bias removed); the lobe's energy in [0.9, 1.05] and within 3% of 32 cells' at 16 and 48
       (measured 2.4% and 0.9%; 4.0% and 2.4% with the half-cell lookup); caustic-ring the lobe within
       0.02 of the seed's (the default changes nothing there); 2 iterations add at least 30% and raise
       the error (why the default is no iterations). */
    static const double bound_lobe[3] = {0.31, 0.27, 0.28};
    for (int i = 0; i < 3; i++) {
        assert_true(err[1][0][i] < bound_lobe[i]);
        assert_true(err[1][0][i] < 0.6 * err[0][0][i]);
        assert_true(ratio[1][0][i] > 0.9 && ratio[1][0][i] < 1.05);
        assert_true(fabs(ratio[1][0][i] / ratio[1][0][1] - 1.0) < 0.03);
        assert_true(fabs(err[1][1][i] - err[0][1][i]) < 0.02);
        assert_true(ratio2[i] > 1.3 * ratio[LOBE ? 1 : 0][0][i]);
        assert_true(err2[i] > err[LOBE ? 1 : 0][0][i]);
    }
    /* Fig. 9's trend, the error falling as the grid grows, on the error without the photon noise
       (noise_free_error: the 4 frames' two halves; the noise grows with the size as the photons per
       cell fall, and at 1M photons it outweighs what 48 cells gain over 32: the plain error rises).
       Measured (GK_LGV_FIG9=1, fig9_photon_study: 16 groups of 1M photons per size): 0.2713 / 0.2278 /
       0.2228, sd 0.0024 / 0.0020 / 0.0021 (the same from 16M photons: 0.2713 / 0.2279 / 0.2230, so the
       estimate is unbiased; this test's 4 frames, the study's first group, 0.2759 / 0.2305 / 0.2256:
       0.0046 / 0.0027 / 0.0028 above the mean at every size, the sizes' noise moves together). With
       the photons snapped onto the texels' distances (plane_hits off) the
       16M errors were 0.275 / 0.241 / 0.243, without the noise (the 1M noise / 4) 32 / 48 0.240 / 0.242: the rise this
       asserts against (GK_LGV_PLANE=0: this test's 0.2794 / 0.2421 / 0.2436, and the second bound fails). Bounds: 16 above 32 by 0.03 (measured 0.044; the difference's sd, were the
       sizes' noise independent, 0.0031: 0.03 is 4 sd below); 48 below 32 (measured 0.0050, 1.7 of
       that sd; the sizes' noise is not independent: every size traces the same photons, the frames'
       hash keys do not depend on the grid, so the sd of the difference is smaller). */
    assert_true(bias[0] - bias[1] > 0.03);
    assert_true(bias[2] < bias[1]);
}

/* Each region's part of the rel. RMSE of `ours` against `ref` (both top row first): sqrt(its squared
   error / all values) / the reference's mean, so the parts' squares add up to the whole's square;
   and its brightness, its sum in ours over its sum in the reference. */
static void region_parts(const gk_image *ref, const gk_image *ours, const unsigned char *region, double part[REGIONS],
                         double bright[REGIONS])
{
    double sq[REGIONS] = {0}, so[REGIONS] = {0}, sr[REGIONS] = {0}, mean = 0;
    for (int i = 0; i < W * HH; i++)
        for (int ch = 0; ch < 3; ch++) {
            double r = ref->pixels[i * ref->channels + ch], o = ours->pixels[i * 3 + ch];
            sq[region[i]] += (o - r) * (o - r);
            so[region[i]] += o, sr[region[i]] += r;
            mean += r;
        }
    double values = 3.0 * W * HH;
    mean /= values;
    for (int k = 0; k < REGIONS; k++) {
        part[k] = sqrt(sq[k] / values) / mean;
        bright[k] = sr[k] > 0 ? so[k] / sr[k] : 0;
    }
}

/* Fig. 9's bias, by region (GK_LGV_DUMP keeps the images): glass's indirect light (LGV, no gathering,
   4 x 262144 photons) per lgv_size with the seed's injection (eq. 4-5 as written) and the photons
   leaving glass traced on its exit map (the default) or on the lattice maps, and with the cosine-lobe
   injection (gk_lgv_debug.inject_lobe, the default) on the exit maps, the lookup reading the surface's
   own cell (gk_lgv_debug.lookup_own_cell, the default) or half a cell along the normal. */
enum { VARIANT_EXIT, VARIANT_LATTICE, VARIANT_LOBE, VARIANT_OFFSET, VARIANTS };
static const char *const VARIANT_NAMES[VARIANTS] = {"seed's injection, exit maps", "seed's injection, lattice maps",
                                                      "lobe injection (the default), exit maps",
                                                      "lobe injection, exit maps, lookup half a cell along n"};

static void fig9_regions(void **state)
{
    (void)state;
    static const char *const sizes[3] = {"16", "32", "48"};
    unsigned char region[W * HH];
    gk_image ref = {0}, ours = {0};
    gk_err e = {0};
    assert_int_equal(gk_image_read("tests/references/glass-indirect.exr", &ref, &e), 0);
    double part[VARIANTS][3][REGIONS], bright[VARIANTS][3][REGIONS], whole[VARIANTS][3], no_sphere[VARIANTS][3];
    bool lobe_default = LOBE;
    for (int v = 0; v < VARIANTS; v++)
        for (int i = 0; i < 3; i++) {
            char budget[96];
            snprintf(budget, sizeof budget, "lgv_photons=262144,lgv_size=%s,lgv_iters=0", sizes[i]);
            EXIT_MAPS = v != VARIANT_LATTICE;
            LOBE = v == VARIANT_LOBE || v == VARIANT_OFFSET;
            OWN_CELL = v != VARIANT_OFFSET;
            ruler r;
            indirect_on("glass", budget, &r); /* leaves the camera in H and the 4 frames' average in H.img */
            glass_regions(region);
            as_image(&ours);
            region_parts(&ref, &ours, region, part[v][i], bright[v][i]);
            gk_image_free(&ours);
            whole[v][i] = r.rel_all;
            double sum_sq = 0;
            for (int k = 0; k < REGIONS; k++)
                sum_sq += part[v][i][k] * part[v][i][k];
            assert_true(fabs(sqrt(sum_sq) - r.rel_all) < 1e-3); /* the parts make up gk_metrics' whole */
            /* the sphere's pixels show what the harness cannot: it draws no glass pass */
            no_sphere[v][i] = sqrt(sum_sq - part[v][i][REGION_SPHERE] * part[v][i][REGION_SPHERE]);
        }
    EXIT_MAPS = true;
    LOBE = lobe_default;
    OWN_CELL = true;
    gk_image_free(&ref);
    for (int v = 0; v < VARIANTS; v++) {
        for (int k = 0; k < REGIONS; k++)
            printf("# fig9 regions, %s: %s's part of the rel. RMSE %.3f / %.3f / %.3f at 16 / 32 / 48 cells, brightness "
                   "%.3f / %.3f / %.3f of the reference's\n", VARIANT_NAMES[v], REGION_NAMES[k], part[v][0][k],
                   part[v][1][k], part[v][2][k], bright[v][0][k], bright[v][1][k], bright[v][2][k]);
        printf("# fig9 regions, %s: whole %.3f / %.3f / %.3f, without the sphere's pixels %.3f / %.3f / %.3f\n",
               VARIANT_NAMES[v], whole[v][0], whole[v][1], whole[v][2], no_sphere[v][0], no_sphere[v][1], no_sphere[v][2]);
    }
    double (*p0)[REGIONS] = part[VARIANT_EXIT];
    double (*p1)[REGIONS] = part[VARIANT_LATTICE];
    /* Measured (llvmpipe, deterministic photons; the plane hits, the default), seed's injection: with
       the lattice maps the floor under the sphere's part rises with the grid, 0.278 / 0.542 / 0.668
       (the whole's rise, 0.565 / 0.741 / 0.842): no lattice map sees that floor, which the sphere hides from every centre outside
       it, so the photons the sphere focuses there (light from the walls and ceiling) landed on the
       floor the maps see beside it, a crescent the finer grids draw sharper. On the exit maps the part
       is flat, 0.199 / 0.203 / 0.219. The sphere's part, 0.294 / 0.297 / 0.299, hardly depends on the
       grid: these pixels show the floor behind the sphere (the harness draws no glass pass; the
       renderer's refracts the image there, render_glass.c), the reference the room seen through the
       glass; the whole without them 0.435 / 0.436 / 0.447. The walls (away from the edges) are dark,
       0.693 / 0.683 / 0.682 of the reference's, part 0.348 / 0.354 / 0.357 (the rest of the floor 1.13
       / 1.13 / 1.12; the edges 1.11 / 1.01 / 0.97; the camera sees no ceiling). Eq. (4)'s (Theta, n)+
       times eq. (7)'s y(-n) weighs a photon by cos g (0.25 + 0.75 cos g), normalised for
       cosine-distributed arrivals; the walls' light comes from the floor at grazing angles. With the
       lobe (every photon weighed alike on its own surface) the walls are 0.986 / 0.978 / 0.977, part
       0.077 / 0.086 / 0.102 (snapped photons: 0.080 / 0.098 / 0.120); the rest of the floor 0.983 /
       0.979 / 0.976; the floor under the sphere's part 0.167 / 0.125 / 0.128 (the sphere's focus on the
       floor, blurred at 16 cells: B.5 item 7's profile under an object, Fig. 9's detail); the whole
       0.278 / 0.242 / 0.249 (0.220 / 0.173 / 0.184 without the sphere's pixels). The edges, 1.146 /
       1.048 / 1.009 with the lobe (part 0.117 / 0.077 / 0.072): a coarse cell at an edge holds two
       surfaces' photons and eq. (7) reads both (the lobe's 0.25 for the other surface's), so the
       coarse grids are too bright there. Away from them the walls' part still rises with the size at
       these 1M photons: the photon noise (at 16M it is flat, 0.075 / 0.074 / 0.076; with the snapped
       photons it rose there too, 0.077 / 0.089 / 0.100, the texels' pattern: README lgv).
       Bounds: the seed's flat floor part < 0.24 and within 15% across sizes; the lattice maps' rising
       at least 2x from 16 to 48 cells (measured 2.40) and at 48 cells at least 2.5x the exit maps'
       (3.05); the sphere's part within 0.01 across sizes; the seed's walls below 0.8 of the
       reference's brightness and the lobe's in [0.9, 1.1], its walls' part at most half the seed's;
       the lobe's edges at 16 cells at least 1.1x as bright as at 48 (measured 1.14); the lobe's floor
       under the sphere's part at 32 and 48 cells at most 0.85x that at 16 (measured 0.75 and 0.77). */
    for (int i = 0; i < 3; i++) {
        assert_true(p0[i][REGION_FLOOR] < 0.24);
        assert_true(p0[i][REGION_FLOOR] < 1.15 * p0[0][REGION_FLOOR] && p0[i][REGION_FLOOR] > p0[0][REGION_FLOOR] / 1.15);
        assert_true(fabs(p0[i][REGION_SPHERE] - p0[0][REGION_SPHERE]) < 0.01);
    }
    assert_true(p1[2][REGION_FLOOR] > 2.0 * p1[0][REGION_FLOOR]);
    assert_true(p1[2][REGION_FLOOR] > 2.5 * p0[2][REGION_FLOOR]);
    for (int i = 0; i < 3; i++) {
        assert_true(bright[VARIANT_EXIT][i][REGION_WALLS] < 0.8);
        assert_true(bright[VARIANT_LOBE][i][REGION_WALLS] > 0.9 && bright[VARIANT_LOBE][i][REGION_WALLS] < 1.1);
        assert_true(part[VARIANT_LOBE][i][REGION_WALLS] < 0.5 * p0[i][REGION_WALLS]);
    }
    assert_true(bright[VARIANT_LOBE][0][REGION_EDGES] > 1.1 * bright[VARIANT_LOBE][2][REGION_EDGES]);
    for (int i = 1; i < 3; i++)
        assert_true(part[VARIANT_LOBE][i][REGION_FLOOR] < 0.85 * part[VARIANT_LOBE][0][REGION_FLOOR]);
    /* The lookup half a cell along n reads a surface f of a cell inside its cell at 1 - f of its own
       cell (and f of the empty one in front). Glass's box faces lie at the bounds, which the tracer
       pads by 0.1% of the extent (lgv_method.c set_scene), and the grid starts at the padded bounds
       with l = 1.002 x the extent / lgv_size: f = 0.001 x lgv_size / 1.002, 0.016 / 0.032 / 0.048,
       a fall with the size. The own cell reads the whole of it: the walls' and the rest of the
       floor's brightness with it over that with the offset is 1 / (1 - f), 1.0162 / 1.0330 / 1.0503.
       Measured (the plane hits): walls 0.986 / 0.978 / 0.977 over 0.971 / 0.947 / 0.931 (1.015 /
       1.033 / 1.049 from the printed digits), the rest of the floor 0.983 / 0.979 / 0.976 over 0.968 /
       0.948 / 0.930 (1.016 / 1.033 / 1.049); with the snapped photons 1.0165 / 1.0328 / 1.0506 and
       1.0163 / 1.0320 / 1.0501. Bounds: that ratio within 0.005 of 1 / (1 - f) on both regions at
       every size; with the offset the rest of the floor falls by more than 0.025 from 16 to 48 cells
       (0.038; snapped 0.042), with the own cell by less than 0.02 (0.007; snapped 0.011). */
    static const double cells[3] = {16, 32, 48};
    for (int i = 0; i < 3; i++) {
        double f = 1e-3 * cells[i] / 1.002; /* the pad over l; glass's box is a cube */
        assert_true(fabs(bright[VARIANT_LOBE][i][REGION_WALLS] / bright[VARIANT_OFFSET][i][REGION_WALLS] - 1.0 / (1.0 - f)) < 0.005);
        assert_true(fabs(bright[VARIANT_LOBE][i][REGION_FLOOR_REST] / bright[VARIANT_OFFSET][i][REGION_FLOOR_REST] -
                         1.0 / (1.0 - f)) < 0.005);
    }
    assert_true(bright[VARIANT_OFFSET][0][REGION_FLOOR_REST] - bright[VARIANT_OFFSET][2][REGION_FLOOR_REST] > 0.025);
    assert_true(fabs(bright[VARIANT_LOBE][0][REGION_FLOOR_REST] - bright[VARIANT_LOBE][2][REGION_FLOOR_REST]) < 0.02);
}

/* Eq. (6)'s gathering: iterations 0 / 2 / 4 / 8 / 12 x LGV size 16 / 32 / 48 against the indirect
   references, printed (GK_LGV_SWEEP=1 runs it alone: the README's table, 15 x 4 frames of 262144
   photons a scene; GK_LGV_REPLACE=1 the last iteration alone, GK_LGV_SCENES1=1 glass only). */
static void gathering_sweep(void **state)
{
    (void)state;
    static const char *const scenes[2] = {"glass", "caustic-ring"};
    REPLACE = getenv("GK_LGV_REPLACE") != NULL;
    int n_scenes = getenv("GK_LGV_SCENES1") ? 1 : 2;
    static const char *const sizes[3] = {"16", "32", "48"};
    static const char *const iters[5] = {"0", "2", "4", "8", "12"};
    for (int sc = 0; sc < n_scenes; sc++)
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 5; k++) {
                char budget[128];
                snprintf(budget, sizeof budget, "lgv_photons=262144,lgv_size=%s,lgv_iters=%s", sizes[i], iters[k]);
                ruler r;
                indirect_on(scenes[sc], budget, &r);
                printf("# sweep%s %s size %s iters %s: rel. RMSE %.3f energy %.3f\n", REPLACE ? " (last iteration)" : "", scenes[sc],
                       sizes[i], iters[k], r.rel_all, r.energy);
                fflush(stdout);
            }
}

/* Rel. RMSE of image `ours` against image `ref` (both as the references: top row first, RGB). */
static double rel_rmse(const gk_image *ref, const gk_image *ours)
{
    gk_metrics m;
    gk_err e = {0};
    assert_int_equal(gk_metrics_compute(ref, ours, gk_metrics_auto_exposure(ref), &m, &e), 0);
    return m.rel_rmse;
}

/* Fig. 9's cause (GK_LGV_FIG9=1 runs it alone; GK_LGV_FIG9_ITERS sets lgv_iters, default 0): glass's
   indirect light (LGV) per lgv_size averaged over 4, 16 and 64 frames of 262144 photons (1M, 4M, 16M)
   against glass-indirect.exr, and the 1M and 4M averages against the 16M one (the photon noise: the
   16M average stands in for the noise-free estimate at that size); the error without the noise
   (noise_free_error) from each group of 4 frames (1M photons: mean and sd over the 16 groups, what
   lgv_size_tradeoff's bounds come from) and from the 64 frames' halves; and fig9_regions' parts and
   brightness of the 1M and 16M averages. The error that does not fall with the photons is the grid's
   bias at that size. */
static void fig9_photon_study(void **state)
{
    (void)state;
    static const char *const sizes[3] = {"16", "32", "48"};
    const char *iters = getenv("GK_LGV_FIG9_ITERS") ? getenv("GK_LGV_FIG9_ITERS") : "0";
    static float sum[W * HH * 4], half[2][W * HH * 4], halves[2][W * HH * 4];
    gk_image ref = {0}, avg[3] = {{0}};
    gk_err e = {0};
    assert_int_equal(gk_image_read("tests/references/glass-indirect.exr", &ref, &e), 0);
    for (int i = 0; i < 3; i++) {
        char budget[96];
        snprintf(budget, sizeof budget, "lgv_photons=262144,lgv_size=%s,lgv_iters=%s", sizes[i], iters);
        assert_int_equal(open_scene(&H, load("glass")), 0);
        memset(sum, 0, sizeof sum);
        memset(half, 0, sizeof half);
        double g_err[16], g_bias[16], g_noise[16];
        for (int f = 1, k = 0; f <= 64; f++) {
            frame(budget, GK_LGV_PART_LGV, 0);
            for (int j = 0; j < W * HH * 4; j++)
                sum[j] += H.img[j], half[(f - 1) / 2 % 2][j] += 0.5f * H.img[j], halves[(f - 1) / 32][j] += H.img[j] / 32.0f;
            if (f % 4 == 0) { /* this group of 4 frames (1M photons): its two halves' noise-free error */
                gk_image ha = {0}, hb = {0};
                memcpy(H.img, half[0], sizeof sum), as_image(&ha);
                memcpy(H.img, half[1], sizeof sum), as_image(&hb);
                int g = f / 4 - 1;
                g_bias[g] = noise_free_error(&ref, ha.pixels, hb.pixels, &g_err[g], &g_noise[g]);
                gk_image_free(&ha), gk_image_free(&hb);
                memset(half, 0, sizeof half);
            }
            if (f != 4 && f != 16 && f != 64)
                continue;
            for (int j = 0; j < W * HH * 4; j++)
                H.img[j] = sum[j] / (float)f;
            as_image(&avg[k++]);
        }
        close_scene(&H);
        double err[3], noise[2];
        for (int k = 0; k < 3; k++)
            err[k] = rel_rmse(&ref, &avg[k]);
        for (int k = 0; k < 2; k++)
            noise[k] = rel_rmse(&avg[2], &avg[k]);
        printf("# fig9 glass size %s iters %s: rel. RMSE vs glass-indirect.exr at 1M / 4M / 16M photons %.3f / %.3f / %.3f; "
               "1M and 4M vs the 16M average %.3f / %.3f\n", sizes[i], iters, err[0], err[1], err[2], noise[0], noise[1]);
        gk_image h0 = {0}, h1 = {0};
        memcpy(H.img, halves[0], sizeof sum), as_image(&h0);
        memcpy(H.img, halves[1], sizeof sum), as_image(&h1);
        double e16, n16, b16 = noise_free_error(&ref, h0.pixels, h1.pixels, &e16, &n16);
        gk_image_free(&h0), gk_image_free(&h1);
        memset(halves, 0, sizeof halves);
        double m[3] = {0}, sd[3] = {0};
        for (int g = 0; g < 16; g++)
            m[0] += g_err[g] / 16, m[1] += g_noise[g] / 16, m[2] += g_bias[g] / 16;
        for (int g = 0; g < 16; g++)
            sd[0] += (g_err[g] - m[0]) * (g_err[g] - m[0]) / 15, sd[1] += (g_noise[g] - m[1]) * (g_noise[g] - m[1]) / 15,
                sd[2] += (g_bias[g] - m[2]) * (g_bias[g] - m[2]) / 15;
        printf("# fig9 glass size %s: 16 groups of 1M photons: error %.4f (sd %.4f), noise %.4f (sd %.4f), noise-free "
               "error %.4f (sd %.4f); 16M photons: error %.4f, noise %.4f, noise-free error %.4f\n", sizes[i], m[0],
               sqrt(sd[0]), m[1], sqrt(sd[1]), m[2], sqrt(sd[2]), e16, n16, b16);
        unsigned char region[W * HH];
        glass_regions(region);
        for (int k = 0; k < 3; k += 2) {
            double part[REGIONS], bright[REGIONS];
            region_parts(&ref, &avg[k], region, part, bright);
            for (int g = 0; g < REGIONS; g++)
                if (g != REGION_CEILING)
                    printf("# fig9 glass size %s at %s photons: %s's part %.3f, brightness %.3f\n", sizes[i], k ? "16M" : "1M",
                           REGION_NAMES[g], part[g], bright[g]);
        }
        fflush(stdout);
        for (int k = 0; k < 3; k++)
            gk_image_free(&avg[k]);
    }
    gk_image_free(&ref);
}

/* light-leak's LGV after 4 frames of 262144 photons (the last frame's grid): the share of the grid's
   flux (band 0's luminance summed over the cells) in the cells of the dark room, x > 0, and (when
   geo is not NULL) the geometry volume's mean x-opacity on the corner plane nearest the wall. */
static double dark_share(const char *budget, bool occlusion, double *geo)
{
    OCCLUSION = occlusion;
    assert_int_equal(open_scene(&H, load("light-leak")), 0);
    for (int f = 0; f < 4; f++)
        frame(budget, GK_LGV_PART_LGV, 0);
    const gk_lgv_stats *st = gk_lgv_get_stats(H.self);
    int d[3] = {st->dims[0], st->dims[1], st->dims[2]};
    float cell = st->cell, x0 = (float)H.scene->bmin.x - 1e-3f * (float)(H.scene->bmax.x - H.scene->bmin.x);
    long n = 12L * d[0] * d[1] * d[2];
    float *v = malloc(sizeof(float) * (size_t)n);
    gk_err e = {0};
    assert_int_equal(gk_lgv_read_lgv(H.self, v, n, &e), n);
    double dark = 0, all = 0;
    for (long c = 0; c < n / 12; c++) {
        double lum = gk_luminance(v[12 * c], v[12 * c + 4], v[12 * c + 8]);
        all += lum;
        if (x0 + ((float)(c % d[0]) + 0.5f) * cell > 0.0f)
            dark += lum;
    }
    free(v);
    if (geo) {
        int gd[3];
        long gn = 3L * (d[0] + 1) * (d[1] + 1) * (d[2] + 1);
        float *g = malloc(sizeof(float) * (size_t)gn);
        assert_int_equal(gk_lgv_read_geometry(H.self, g, gn, gd, &e), gn);
        int plane = (int)lroundf(-x0 / cell); /* the corners nearest x = 0 */
        double sum = 0;
        for (int z = 0; z < gd[2]; z++)
            for (int y = 0; y < gd[1]; y++)
                sum += g[3 * (((long)z * gd[1] + y) * gd[0] + plane)];
        *geo = sum / (gd[1] * gd[2]);
        free(g);
    }
    close_scene(&H);
    OCCLUSION = true;
    return dark / all;
}

/* Eq. (6)'s G blocks the gathering at a wall: on light-leak, 12 iterations must not carry the lit
   room's flux into the dark room. The dark room's share of the LGV's flux with no iterations is
   what the tracer itself puts there (photons through the 2 cm wall); 12 iterations without G
   (G = 1) carry the lit room's flux through; with G they must not. 8 maps: with the default 27 the
   lattice's middle centre, pushed out of the wall, lies beside it and the photons on the wall's
   other side traced on it pass through (0.55 of the flux in the dark room with no iterations; with
   gk_lgv_debug.seeing_maps 0.18), which would hide what the gathering carries. */
static void occlusion_blocks_a_wall(void **state)
{
    (void)state;
    double geo = 0;
    double none = dark_share("lgv_photons=262144,lgv_maps=8,lgv_iters=0", true, NULL);
    double open = dark_share("lgv_photons=262144,lgv_maps=8,lgv_iters=12", false, NULL);
    double shut = dark_share("lgv_photons=262144,lgv_maps=8,lgv_iters=12", true, &geo);
    printf("# light-leak, the dark room's share of the LGV's flux: 0 iterations %.4f; 12 iterations without G "
           "%.4f, with G %.4f; mean x-opacity on the wall's corner plane %.3f\n", none, open, shut, geo);
    /* Measured (llvmpipe, 8 maps, 4 x 262144 photons): 0.0504 with no iterations; 12 iterations
       without G 0.2424 (+0.192), with G 0.0719 (+0.022: G stops 89% of what crossed); the wall's
       corner plane 0.927 opaque (the corners at the rooms' edges see half a cell of wall). With the
       lobe injection 0.0456 / 0.2085 / 0.0608 (the seed's, since the exit maps: 0.0451 / 0.2194 /
       0.0643); with the plane hits too (the defaults) 0.0383 / 0.2023 / 0.0439 (+0.0056: G stops 97%;
       fewer photons in the dark room with no iterations; not analysed further). Bounds:
       without G the gathering leaks (> +0.15), with G at most +0.04, the wall's plane > 0.85. */
    assert_true(open - none > 0.15);
    assert_true(shut - none < 0.04);
    assert_true(geo > 0.85);
}

/* B.5 item 6, temporal discontinuity: a static scene at the default 65536 photons, a new photon
   hash key every frame (the method's own frame index): the per-pixel temporal standard deviation of
   the indirect light (LGV) over 8 frames, relative to its mean, over the pixels the LGV lights
   (mean above 1% of the brightest pixel's). And the fixed-point injection's determinism: the same
   frame rendered twice by two fresh instances is identical, bit for bit. */
static void temporal_noise_and_determinism(void **state)
{
    (void)state;
    enum { FRAMES = 8 };
    static float m1[W * HH], m2[W * HH], first[W * HH * 4];
    memset(m1, 0, sizeof m1), memset(m2, 0, sizeof m2);
    assert_int_equal(open_scene(&H, load("glass")), 0);
    for (int f = 0; f < FRAMES; f++) {
        frame(NULL, GK_LGV_PART_LGV, 0);
        if (f == 0)
            memcpy(first, H.img, sizeof first);
        for (int i = 0; i < W * HH; i++) {
            float l = gk_luminance(H.img[4 * i], H.img[4 * i + 1], H.img[4 * i + 2]);
            m1[i] += l / FRAMES, m2[i] += l * l / FRAMES;
        }
    }
    close_scene(&H);
    assert_int_equal(open_scene(&H, load("glass")), 0);
    frame(NULL, GK_LGV_PART_LGV, 0);
    int same = memcmp(first, H.img, sizeof first) == 0;
    close_scene(&H);
    float peak = 0;
    for (int i = 0; i < W * HH; i++)
        peak = fmaxf(peak, m1[i]);
    double sum = 0;
    int n = 0;
    for (int i = 0; i < W * HH; i++)
        if (m1[i] > 0.01f * peak) {
            sum += sqrt(fmax(m2[i] - m1[i] * m1[i], 0.0)) / m1[i];
            n++;
        }
    printf("# glass, LGV at 65536 photons, 8 frames with new photons: mean relative temporal std %.4f over %d pixels; "
           "the same frame twice identical: %s\n", sum / n, n, same ? "yes" : "no");
    /* Measured (llvmpipe): 0.215 over 16269 pixels with the default (the lobe injection, no gathering
       iterations); 0.234 over 16118 with the seed's injection (0.232
       over 13873 before the exit maps; eq. 7 alone is a one-cell density estimate: the seed's "temporal discontinuity" at the default
       photons); 0.157 over 14872 with 4 iterations (their sum spreads each photon over more cells;
       before the tracer's bounds hits, 0.197 with 4 and 0.293 without); identical twice. Bound: the
       measurement + 0.04. */
    assert_true(same);
    assert_true(sum / n < 0.27);
}

/* ---- each pass's work (lgv_work.c, the bench's efficiency) against hand counts ---- */

static double work_of(const char *pass, const char *kind)
{
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = gk_gi_lgv.pass_work(H.self, w, GK_MAX_PASS_WORK);
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].pass, pass) && !strcmp(w[i].kind, kind))
            return w[i].fetches;
    return 0.0;
}

/* Rays from each lattice map's centre whose hit lies nearer that centre than any other (by 20%):
   the tracer picks that map for the ray and for its hit. Returns how many (6 floats each). */
static int centre_rays(float *rays, int cap)
{
    float c[4 * 64], hits[4];
    int maps = gk_lgv_centres(H.self, c, 64), n = 0;
    uint32_t rng = 7u;
    for (int m = 0; m < maps && n < cap; m++)
        for (int k = 0; k < 64 && n < cap; k++) {
            vec3 d = sphere_dir(&rng);
            float *r = &rays[6 * n];
            r[0] = c[4 * m], r[1] = c[4 * m + 1], r[2] = c[4 * m + 2], r[3] = d.x, r[4] = d.y, r[5] = d.z;
            gk_err e = {0};
            assert_int_equal(gk_lgv_probe(H.self, r, 1, hits, NULL, &e), 1);
            if (hits[3] != 1.0f)
                continue;
            vec3 hit = v3(hits[0], hits[1], hits[2]);
            float own = v3_len(v3_sub(hit, v3(c[4 * m], c[4 * m + 1], c[4 * m + 2]))), other = 1e30f;
            for (int o = 0; o < maps; o++)
                if (o != m)
                    other = fminf(other, v3_len(v3_sub(hit, v3(c[4 * o], c[4 * o + 1], c[4 * o + 2]))));
            n += own < 0.8f * other;
        }
    return n;
}

static void work_counts_on_the_furnace_box(void **state)
{
    (void)state;
    /* the gathering model against a hand count: 2^3 cells, each with 3 neighbours in the grid (24
       pairs); the resolve and the volume 3 vec4s a cell each (24 + 24), each of 2 iterations 24
       pairs x (3 + 1 with the occlusion) + 3 a cell for the accumulator (96 + 24) */
    assert_true(gk_lgv_gather_loads((const int[3]){2, 2, 2}, 2, true) == 288.0);
    assert_true(gk_lgv_gather_loads((const int[3]){2, 2, 2}, 0, false) == 48.0);
    /* the furnace: the inside of a closed box, nothing else; the camera inside it */
    assert_int_equal(open_scene(&H, load("furnace")), 0);
    COUNT = true, C0 = 1e6f; /* h spans the scene: every neighbour in the screen grid is accepted */
    frame("lgv_maps=8,lgv_map_res=32,lgv_sslgv=128,lgv_iters=2", GK_LGV_PART_ALL, 0);
    COUNT = false, C0 = 1.0f;
    const gk_lgv_stats *st = gk_lgv_get_stats(H.self);
    /* the maps: from inside a convex box each texel of each face is one wall's fragment, once */
    double maps = work_of("gi.lgv_maps", "raster_r16f_depth_fill");
    printf("# furnace, %d maps of 32^2: %.0f fragments counted\n", st->n_maps, maps);
    assert_true(maps == 6.0 * 32 * 32 * st->n_maps);
    /* the min mips in the same pass: 4 loads per texel of levels 1 (16^2) and 2 (8^2) of every face */
    assert_true(work_of("gi.lgv_maps", "image3d_rgba16f_load") == 4.0 * 6 * (16 * 16 + 8 * 8) * st->n_maps);
    /* the geometry volume, built in this first frame's gathering (2 iterations: the occlusion): one
       distance read per texel of each lattice map, and 3 opacity atomics for each, every texel
       seeing a wall of the closed box */
    double geo_reads = work_of("gi.lgv_gather", "tex2d_r32ui_nearest");
    printf("# furnace: %.0f geometry distance reads, %.0f atomics\n", geo_reads,
           work_of("gi.lgv_gather", "ssbo_r32ui_atomic"));
    assert_true(geo_reads == 6.0 * 32 * 32 * st->n_maps);
    assert_true(work_of("gi.lgv_gather", "ssbo_r32ui_atomic") == 3.0 * geo_reads);
    /* the lookup: 3 trilinear volume reads and 3 filtered SSLGV reads (128 wide < 160) per pixel it
       shades, the pixels where it wrote (alpha 1 over the cleared 0) */
    double shaded = 0;
    for (int i = 0; i < W * HH; i++)
        shaded += H.img[4 * i + 3] == 1.0f;
    assert_true(shaded > 0);
    assert_true(work_of("gi.lgv_lookup", "tex3d_rgba16f_trilinear") == 3.0 * shaded);
    assert_true(work_of("gi.lgv_lookup", "tex2d_rgba16f_trilinear") == 3.0 * shaded);
    /* the SSLGV's 12 iterations over 128 x 96 pixels, all surface: per pixel its own 12 floats and
       each neighbour's inside the grid (3 vec4s each), a depth read for itself and each neighbour */
    double w = 128, h = 96, own = w * h, pairs = 2 * (w - 1) * h + 2 * w * (h - 1);
    assert_true(shaded == W * HH);
    assert_true(work_of("gi.lgv_sslgv", "ssbo_rgba32f_load") == 12 * 3 * (own + pairs));
    assert_true(work_of("gi.lgv_sslgv", "tex2d_depth32f_nearest") == 12 * (own + pairs));
    /* the gathering at the frame's grid, 2 iterations with the occlusion */
    assert_true(work_of("gi.lgv_gather", "ssbo_rgba32f_load") == gk_lgv_gather_loads(st->dims, 2, true));
    /* the tracer: a ray from a map's centre has its ITP at once (1 texel: the centre sees the ray's
       direction), then the secant's bracket (2) and its 6 steps; 1 more when the bracket's far end,
       the ITP's distance recomputed from its point, rounds to just in front of the surface (the
       undershoot step). Rays whose map sees the wall beyond the bounds (the nearest texel's distance
       is its centre's: at 32^2 a wall seen obliquely lies farther than the 0.1% padding) end at the
       bounds hit's one texel instead (4 in all, 212 rays: 7.76 a ray): without the bounds hits those
       rays leave the scene and centre_rays leaves them out. */
    gk_lgv_debug d;
    gk_lgv_default_debug(&d);
    d.bounds_hits = false;
    gk_lgv_set_debug(H.self, &d);
    enum { CAP = 512 };
    float *rays = malloc(sizeof(float) * 6 * CAP), *hits = malloc(sizeof(float) * 4 * CAP);
    int n = centre_rays(rays, CAP);
    double fetches = 0;
    gk_err e = {0};
    assert_int_equal(gk_lgv_probe(H.self, rays, n, hits, &fetches, &e), n);
    printf("# furnace, %d rays from the maps' centres: %.0f distance texels (%.3f a ray)\n", n, fetches, fetches / n);
    assert_true(n >= 100);
    assert_true(fetches >= 9.0 * n && fetches <= 10.0 * n);
    free(rays), free(hits);
    close_scene(&H);
    /* the injection on glass (a lamp, photons bouncing): 12 atomics into the LGV per photon the
       stats count as injected, and one per caustic photon appended */
    assert_int_equal(open_scene(&H, load("glass")), 0);
    COUNT = true;
    frame("lgv_photons=16384", GK_LGV_PART_ALL, 0);
    COUNT = false;
    st = gk_lgv_get_stats(H.self);
    double atomics = work_of("gi.lgv_trace", "ssbo_r32ui_atomic"), texels = work_of("gi.lgv_trace", "tex2d_r32ui_nearest");
    printf("# glass, 16384 photons: %u rays, %u injected, %u caustic; %.0f LGV atomics, %.0f distance texels (%.1f a ray)\n",
           st->rays, st->injected, st->caustic, atomics, texels, texels / st->rays);
    assert_true(st->injected > 0);
    assert_true(atomics == 12.0 * st->injected + st->caustic);
    close_scene(&H);
}

/* The tracer's counted distance texels against its CPU replay (tests/common/lgv_replay.c) on the same
   maps and photon-like rays, ray by ray: the replay's float arithmetic is the shader's, but llvmpipe's
   acos, sin, cos and normalize are its own approximations, so a ray whose ITP or bracket lies at a
   texel's or a branch's edge can take another path. */
static void trace_count_against_a_replay(void **state)
{
    (void)state;
    gk_scene *s = load("glass");
    assert_int_equal(open_scene(&H, s), 0);
    frame("lgv_photons=16384", GK_LGV_PART_ALL, 0);
    gk_lgv_debug d;
    gk_lgv_default_debug(&d);
    gk_lgv_set_debug(H.self, &d);
    enum { N = 2048, CAP = 27 * 6 * (64 * 64 + 32 * 32 + 16 * 16) + 4 * 6 * (64 * 64 + 32 * 32 + 16 * 16) };
    uint32_t *maps = malloc(sizeof(uint32_t) * CAP);
    float c[4 * 64], *rays = malloc(sizeof(float) * 6 * N), hit[4];
    gkt_lgv_replay R = {.maps = maps, .centres = c, .bounds_hits = d.bounds_hits};
    gk_err e = {0};
    assert_true(gk_lgv_read_maps(H.self, maps, CAP, &R.info, &e) > 0);
    assert_true(gk_lgv_centres(H.self, c, 64) >= R.info.n_maps);
    exact x;
    exact_build(&x, s);
    make_rays(&x, H.lights[0].position, N, rays);
    double counted = 0, replayed = 0;
    int differ = 0;
    for (int i = 0; i < N; i++) {
        double one = 0;
        assert_int_equal(gk_lgv_probe(H.self, &rays[6 * i], 1, hit, &one, &e), 1);
        long before = R.fetches;
        gkt_lgv_replay_trace(&R, v3(rays[6 * i], rays[6 * i + 1], rays[6 * i + 2]),
                             v3(rays[6 * i + 3], rays[6 * i + 4], rays[6 * i + 5]));
        double mine = (double)(R.fetches - before);
        counted += one, replayed += mine;
        differ += one != mine;
    }
    printf("# glass, %d photon-like rays: %.0f distance texels counted, %.0f replayed (%.2f a ray); %d rays differ\n", N,
           counted, replayed, replayed / N, differ);
    /* Measured (llvmpipe): 79 250 counted, 79 240 replayed (0.013%, 38.7 a ray), 20 of the 2048 rays
       differ (1.0%), either way. Bounds: 0.1% of the texels, 2% of the rays. */
    assert_true(fabs(counted - replayed) <= 0.001 * replayed);
    assert_true(differ <= N / 50);
    free(maps), free(rays);
    gk_bvh_free(&x.bvh);
    free(x.verts);
    close_scene(&H);
}

/* Fig. 9's fall of the walls' brightness with the grid, the candidate "flux in cells the lookup never
   reads": glass's injected LGV (band 0's luminance, one frame of 262144 photons, no gathering) by the
   cell layer it lies in, counted from the grid's boundary: every diffuse surface of glass is a face
   of the box, at the bounds, so a photon the tracer places off its surface by more than the boundary
   cell (or beyond the grid's clamp, trace.comp inject) shows up deeper or not at all. */
static void fig9_flux_in_boundary_cells(void **state)
{
    (void)state;
    static const char *const sizes[3] = {"16", "32", "48"};
    double boundary[3];
    unsigned injected[3];
    for (int i = 0; i < 3; i++) {
        char budget[96];
        snprintf(budget, sizeof budget, "lgv_photons=262144,lgv_size=%s,lgv_iters=0", sizes[i]);
        assert_int_equal(open_scene(&H, load("glass")), 0);
        frame(budget, GK_LGV_PART_LGV, 0);
        const gk_lgv_stats *st = gk_lgv_get_stats(H.self);
        int d[3] = {st->dims[0], st->dims[1], st->dims[2]};
        long n = 12L * d[0] * d[1] * d[2];
        float *v = malloc(sizeof(float) * (size_t)n);
        gk_err e = {0};
        assert_int_equal(gk_lgv_read_lgv(H.self, v, n, &e), n);
        double layer[3] = {0}, all = 0;
        for (long c = 0; c < n / 12; c++) {
            int q[3] = {(int)(c % d[0]), (int)(c / d[0] % d[1]), (int)(c / d[0] / d[1])}, depth = 2;
            for (int a = 0; a < 3; a++) {
                int from_edge = q[a] < d[a] - 1 - q[a] ? q[a] : d[a] - 1 - q[a];
                depth = from_edge < depth ? from_edge : depth;
            }
            double lum = gk_luminance(v[12 * c], v[12 * c + 4], v[12 * c + 8]);
            all += lum;
            layer[depth] += lum;
        }
        boundary[i] = layer[0] / all, injected[i] = st->injected;
        printf("# fig9 flux by cell layer, %s cells (%dx%dx%d, l %.4f m): boundary / next / deeper %.5f / %.5f / %.5f; "
               "%u photons injected\n", sizes[i], d[0], d[1], d[2], st->cell, layer[0] / all, layer[1] / all,
               layer[2] / all, st->injected);
        free(v);
        close_scene(&H);
    }
    /* Measured (llvmpipe, deterministic): the boundary cells hold 1.00000 of the flux at every size,
       and the same photons are injected at every size (the grid does not change the tracing, so a
       difference would be photons dropped more than a cell outside the grid). Bounds: 0.9999 (a
       photon off its wall by more than a 48-cell cell, 11.6 mm, would show), equal counts. */
    for (int i = 0; i < 3; i++) {
        assert_true(boundary[i] > 0.9999);
        assert_int_equal(injected[i], injected[0]);
    }
}

/* ---- Fig. 9's chart (GK_LGV_FIG9_OUT=DIR): the data tools/fig9_chart.sh plots for `make bench` ----
   Per LGV size, glass's indirect light (the LGV alone, as lgv_size_tradeoff: no gathering, the
   defaults' injection and lookup) averaged over GK_LGV_FIG9_FRAMES frames (default 4) of
   GK_LGV_FIG9_PHOTONS photons (default 262144: 1M in all, lgv_size_tradeoff's) against
   glass-indirect.exr: the rel. RMSE, the photon noise and the error without it (noise_free_error,
   the frames' first and second halves), and the passes' times by the renderer's clock in its CPU
   mode (llvmpipe's: wall clock around a fence at each pass), the median over the frames after the
   first (which renders the cube maps and builds the geometry volume, once for a static scene). Writes
   DIR/fig9-glass.csv and, per size, the average and its two halves as EXRs (top row first, as the
   references), so each error can be recomputed by `gikiosk compare` (tests/e2e/fig9_chart.sh).
   GK_LGV_FIG9_SIZES (default 16,32,48) picks the sizes. */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median_of(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* img (H.img's layout: bottom row first, RGBA) written to DIR/fig9-glass-SIZE{,-a,-b}.exr and returned in out. */
static void write_average(const char *dir, const char *size, const char *suffix, const float *img, gk_image *out)
{
    char path[512];
    gk_err e = {0};
    memcpy(H.img, img, sizeof H.img);
    as_image(out);
    snprintf(path, sizeof path, "%s/fig9-glass-%s%s.exr", dir, size, suffix);
    if (gk_image_write_float(path, out, NULL, &e))
        fail_msg("%s: %s", path, e.msg);
}

static void fig9_chart(void **state)
{
    (void)state;
    const char *dir = getenv("GK_LGV_FIG9_OUT");
    const char *photons = getenv("GK_LGV_FIG9_PHOTONS") ? getenv("GK_LGV_FIG9_PHOTONS") : "262144";
    const char *sizes = getenv("GK_LGV_FIG9_SIZES") ? getenv("GK_LGV_FIG9_SIZES") : "16,32,48";
    int frames = getenv("GK_LGV_FIG9_FRAMES") ? atoi(getenv("GK_LGV_FIG9_FRAMES")) : 4;
    if (frames < 2 || frames % 2 || frames > 64)
        fail_msg("GK_LGV_FIG9_FRAMES=%d: an even count from 2 to 64 (two halves for the noise)", frames);
    char path[512];
    snprintf(path, sizeof path, "%s/fig9-glass.csv", dir);
    FILE *csv = fopen(path, "w");
    if (!csv)
        fail_msg("cannot write %s", path);
    fputs("scene,lgv_size,dims,photons,frames,rel_rmse,noise,noise_free_error,mean_ratio,gi.lgv_gather_ms,gi.lgv_trace_ms,gi_ms\n",
          csv);
    gk_image ref = {0};
    gk_err e = {0};
    assert_int_equal(gk_image_read("tests/references/glass-indirect.exr", &ref, &e), 0);
    gk_timer *timer = gk_timer_create(false); /* CPU mode: what the renderer uses on llvmpipe */
    assert_non_null(timer);
    const gk_pass_ctx clock = {.timer = timer, .programs = H.programs};
    static float sum[W * HH * 4], half[2][W * HH * 4];
    char list[128];
    snprintf(list, sizeof list, "%s", sizes);
    for (char *size = strtok(list, ","); size; size = strtok(NULL, ",")) {
        char budget[128];
        snprintf(budget, sizeof budget, "lgv_photons=%s,lgv_size=%s,lgv_iters=0", photons, size);
        assert_int_equal(open_scene(&H, load("glass")), 0);
        memset(sum, 0, sizeof sum);
        memset(half, 0, sizeof half);
        double gather[64], trace[64], gi[64];
        PASS = &clock;
        for (int f = 0; f < frames; f++) {
            frame(budget, GK_LGV_PART_LGV, 0);
            gather[f] = gk_frame_report_ms(&REPORT, "gi.lgv_gather");
            trace[f] = gk_frame_report_ms(&REPORT, "gi.lgv_trace");
            gi[f] = gk_frame_report_ms(&REPORT, "gi");
            if (getenv("GK_LGV_FIG9_VERBOSE"))
                printf("# frame %d: lgv_maps %.2f, lgv_trace %.2f, lgv_gather %.2f, lgv_sslgv %.2f, lgv_lookup %.2f, gi %.2f ms\n", f,
                       gk_frame_report_ms(&REPORT, "gi.lgv_maps"), trace[f], gather[f],
                       gk_frame_report_ms(&REPORT, "gi.lgv_sslgv"), gk_frame_report_ms(&REPORT, "gi.lgv_lookup"), gi[f]);
            for (int k = 0; k < W * HH * 4; k++)
                sum[k] += H.img[k] / (float)frames, half[2 * f / frames][k] += 2.0f * H.img[k] / (float)frames;
        }
        PASS = NULL;
        const gk_lgv_stats *st = gk_lgv_get_stats(H.self);
        int dims[3] = {st->dims[0], st->dims[1], st->dims[2]};
        close_scene(&H);
        gk_image avg = {0}, ha = {0}, hb = {0};
        write_average(dir, size, "-a", half[0], &ha);
        write_average(dir, size, "-b", half[1], &hb);
        double err, noise, bias = noise_free_error(&ref, ha.pixels, hb.pixels, &err, &noise);
        write_average(dir, size, "", sum, &avg);
        /* the times of the frames after the first, which renders the maps and builds the geometry
           volume once (a static scene's steady state, as the bench's warm-up frames leave it) */
        double gather_ms = median_of(gather + 1, frames - 1), trace_ms = median_of(trace + 1, frames - 1),
               gi_ms = median_of(gi + 1, frames - 1);
        gk_metrics m;
        assert_int_equal(gk_metrics_compute(&ref, &avg, gk_metrics_auto_exposure(&ref), &m, &e), 0);
        /* the halves' average is the average: noise_free_error's error is gk_metrics' */
        assert_true(fabs(err - m.rel_rmse) < 1e-4 * m.rel_rmse);
        fprintf(csv, "glass,%s,%dx%dx%d,%lld,%d,%.6f,%.6f,%.6f,%.6f,%.4f,%.4f,%.4f\n", size, dims[0], dims[1], dims[2],
                (long long)atoll(photons) * frames, frames, m.rel_rmse, noise, bias, m.mean_ratio, gather_ms, trace_ms, gi_ms);
        printf("# fig9 chart: glass lgv_size %s (%dx%dx%d), %d x %s photons: rel. RMSE %.4f, noise %.4f, noise-free "
               "error %.4f; lgv_gather %.2f ms, the method %.1f ms (medians)\n", size, dims[0], dims[1], dims[2], frames,
               photons, m.rel_rmse, noise, bias, gather_ms, gi_ms);
        fflush(stdout);
        gk_image_free(&avg), gk_image_free(&ha), gk_image_free(&hb);
    }
    gk_timer_destroy(timer);
    gk_image_free(&ref);
    assert_int_equal(fclose(csv), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(tracer_against_exact_rays),
        cmocka_unit_test(caustic_against_reference),
        cmocka_unit_test(energy_constant_in_n_and_c0),
        cmocka_unit_test(lgv_size_tradeoff),
        cmocka_unit_test(fig9_regions),
        cmocka_unit_test(fig9_flux_in_boundary_cells),
        cmocka_unit_test(temporal_noise_and_determinism),
        cmocka_unit_test(occlusion_blocks_a_wall),
        cmocka_unit_test(work_counts_on_the_furnace_box),
        cmocka_unit_test(trace_count_against_a_replay),
    };
    const struct CMUnitTest sweep[] = {cmocka_unit_test(gathering_sweep)};
    const struct CMUnitTest fig9[] = {cmocka_unit_test(fig9_photon_study)};
    const struct CMUnitTest chart[] = {cmocka_unit_test(fig9_chart)};
    if (getenv("GK_LGV_FIG9_OUT"))
        return cmocka_run_group_tests(chart, setup, teardown);
    if (getenv("GK_LGV_SWEEP"))
        return cmocka_run_group_tests(sweep, setup, teardown);
    if (getenv("GK_LGV_FIG9"))
        return cmocka_run_group_tests(fig9, setup, teardown);
    if (getenv("GK_LGV_ONLY")) /* one test by name (a glob), e.g. GK_LGV_ONLY=occlusion_blocks_a_wall */
        cmocka_set_test_filter(getenv("GK_LGV_ONLY"));
    return cmocka_run_group_tests(tests, setup, teardown);
}
