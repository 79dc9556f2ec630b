/* The radiosity method's GPU bounces (shaders_gles/radiosity/gather.comp, pullup.comp, driven by
 * app/gi/radiosity/rad_gpu.c) against the CPU oracle (rad_solve_cpu) on the same geometry and the
 * same initial radiance: cornell at the method's defaults (2,983 surfels, 6x12² bins), 1, 2 and 4
 * bounces, on the GLES 3.1 path (and the bounces' work model: links x bounces). The GPU sums in float in link order, the CPU in double: the
 * per-leaf difference is rounding (bound below, from measurement). Also: the worker publishes
 * nothing new for a request that changes nothing (static scene: one geometry build, one direct
 * update over many requests). A moving mesh (cornell's short block made animated, moved twice, links
 * rebuilt every second move): the vertex buffer the display draws holds the refit vertices
 * exactly, after the link rebuild and after the refit without one (the vertices-only upload), and
 * the GPU bounces still equal the CPU oracle on the published geometry. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "gi/radiosity/rad_direct.h"
#include "gi/radiosity/rad_internal.h"

static gkt_gl GL;

static int setup(void **state)
{
    (void)state;
    return gkt_gl_open(&GL);
}

static int teardown(void **state)
{
    (void)state;
    gkt_gl_close(&GL);
    return 0;
}

static void test_gpu_bounces_match_cpu(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_scene *sc = gk_scene_load("config/scenes/cornell.gltf", &e);
    if (!sc)
        fail_msg("%s", e.msg);
    gk_scene_evaluate(sc, 0.0f);
    gk_gi_context ctx = {.gles_version = 31};
    rad_state *s = gk_gi_radiosity.create(&ctx, &e);
    assert_non_null(s);
    assert_int_equal(gk_gi_radiosity.set_scene(s, sc, &e), 0);
    rad_settings set = rad_settings_for(sc, 24.0f, 12, RAD_WEIGHT_SPILL);
    for (int i = 0; i < 5; i++) /* the same request again and again: one build, one publication */
        rad_worker_submit(s->worker, sc, &set);
    rad_worker_wait(s->worker);
    assert_true(rad_worker_take(s->worker, &s->seen, rad_gpu_take, s));
    rad_worker_submit(s->worker, sc, &set);
    rad_worker_wait(s->worker);
    assert_false(rad_worker_take(s->worker, &s->seen, rad_gpu_take, s)); /* nothing new */
    rad_worker_stats ws;
    rad_worker_get_stats(s->worker, &ws);
    assert_false(ws.failed);
    assert_int_equal(ws.geometry_builds, 1);
    assert_int_equal(ws.direct_updates, 1);
    assert_int_equal(ws.publications, 1);

    /* the oracle: the same geometry, direct light and B0, bounced on the CPU */
    rad_geometry g;
    assert_int_equal(rad_geometry_build(&g, sc, set.edge, set.max_verts, set.n_face, set.weight, &e), 0);
    gk_ref_scene rs;
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, sc, id, id, v3(0, 0, 0), 1, 1, &e), 0);
    int nl = g.tree.n_leaves, nn = g.tree.n_nodes;
    assert_int_equal(nl, s->gpu.n_leaves);
    float *ed = malloc(sizeof *ed * 3 * (size_t)nl), *b0 = malloc(sizeof *b0 * 3 * (size_t)nn);
    float *cpu = malloc(sizeof *cpu * 3 * (size_t)nl), *gpu = malloc(sizeof *gpu * 3 * (size_t)nl);
    rad_direct_irradiance(&rs, &g.tree, set.samples, 0, nl, ed);
    rad_initial_radiance(&g, ed, b0);
    const int bounces[] = {1, 2, 4};
    for (int bi = 0; bi < 3; bi++) {
        gk_gi_frame f = {0};
        assert_int_equal(rad_gpu_bounce(s, &f, bounces[bi], &e), 0);
        /* the bounces' work model (rad_work.c): one radiance load per link per bounce, against the
           oracle's own link set */
        gk_pass_work w[GK_MAX_PASS_WORK];
        assert_int_equal(gk_gi_radiosity.pass_work(s, w, GK_MAX_PASS_WORK), 1);
        assert_string_equal(w[0].pass, "gi.radiosity_bounce");
        assert_true(w[0].fetches == (double)bounces[bi] * (double)g.links.offset[nl]);
        assert_int_equal(gk_radiosity_read_irradiance(s, gpu, nl), nl);
        assert_int_equal(rad_solve_cpu(&g, b0, bounces[bi], cpu), 0);
        double worst = 0.0, top = 0.0, sum_g = 0.0, sum_c = 0.0;
        for (int i = 0; i < 3 * nl; i++)
            top = fmax(top, cpu[i]);
        for (int i = 0; i < 3 * nl; i++) {
            worst = fmax(worst, fabs(gpu[i] - cpu[i]) / top);
            sum_g += gpu[i], sum_c += cpu[i];
        }
        printf("# cornell %d surfels, %d bounce(s): GPU vs CPU worst |diff| / max %.2e, sums %.6f / %.6f\n", nl,
               bounces[bi], worst, sum_g, sum_c);
        /* measured 6.8e-7 .. 7.0e-7 (float rounding); a lost link or node is far above 1e-5 */
        assert_true(worst < 1e-5);
        assert_true(sum_c > 0.0);
    }
    assert_int_equal(glGetError(), GL_NO_ERROR);
    free(ed), free(b0), free(cpu), free(gpu);
    gk_ref_scene_free(&rs);
    rad_geometry_free(&g);
    gk_gi_radiosity.destroy(s);
    gk_scene_free(sc);
}

/* rad_take_fn: the GPU's take, plus a copy of what it took (the oracle's input) */
typedef struct oracle { rad_state *s; rad_geometry g; float *b0; bool have; } oracle;

static void take_and_copy(void *ctx, const rad_geometry *g, uint64_t geometry_id, const float *b0)
{
    oracle *o = ctx;
    rad_gpu_take(o->s, g, geometry_id, b0);
    if (o->have)
        rad_geometry_free(&o->g), free(o->b0);
    assert_int_equal(rad_geometry_clone(&o->g, g), 0);
    o->b0 = malloc(sizeof *o->b0 * 3 * (size_t)g->tree.n_nodes);
    memcpy(o->b0, b0, sizeof *o->b0 * 3 * (size_t)g->tree.n_nodes);
    o->have = true;
}

static void test_gpu_moving_mesh(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_scene *sc = gk_scene_load("config/scenes/cornell.gltf", &e);
    if (!sc)
        fail_msg("%s", e.msg);
    gk_scene_evaluate(sc, 0.0f);
    int block = -1;
    for (int i = 0; i < sc->n_nodes; i++)
        if (strcmp(sc->nodes[i].name, "short-block") == 0)
            block = i;
    assert_true(block >= 0);
    sc->nodes[block].animated = true;
    sc->path[0] = '\0'; /* the method reads this scene, not a fresh load without the flag */
    gk_gi_context ctx = {.gles_version = 31};
    rad_state *s = gk_gi_radiosity.create(&ctx, &e);
    assert_non_null(s);
    assert_int_equal(gk_gi_radiosity.set_scene(s, sc, &e), 0);
    rad_settings set = rad_settings_for(sc, 16.0f, 8, RAD_WEIGHT_SPILL);
    set.link_every = 2;
    mat4 rest = sc->nodes[block].world;
    oracle o = {.s = s};
    uint64_t links[3];
    for (int step = 0; step < 3; step++) {
        mat4 shift = m4_trs(v3(0.03f * (float)step, 0.0f, 0.02f * (float)step), (quat){0, 0, 0, 1}, v3(1, 1, 1));
        sc->nodes[block].world = m4_mul(shift, rest);
        rad_worker_submit(s->worker, sc, &set);
        rad_worker_wait(s->worker);
        assert_true(rad_worker_take(s->worker, &s->seen, take_and_copy, &o));
        links[step] = s->gpu.links_id;
        int nv = o.g.mesh.n_verts, nl = o.g.tree.n_leaves;
        glBindBuffer(GL_ARRAY_BUFFER, s->gpu.vbo);
        const float *p = glMapBufferRange(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(float) * 3 * (size_t)nv), GL_MAP_READ_BIT);
        assert_non_null(p);
        int off = 0;
        for (int i = 0; i < nv; i++)
            off += p[3 * i] != o.g.mesh.pos[i].x || p[3 * i + 1] != o.g.mesh.pos[i].y || p[3 * i + 2] != o.g.mesh.pos[i].z;
        glUnmapBuffer(GL_ARRAY_BUFFER);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        assert_int_equal(off, 0);
        gk_gi_frame f = {0};
        assert_int_equal(rad_gpu_bounce(s, &f, 2, &e), 0);
        float *cpu = malloc(sizeof *cpu * 3 * (size_t)nl), *gpu = malloc(sizeof *gpu * 3 * (size_t)nl);
        assert_int_equal(gk_radiosity_read_irradiance(s, gpu, nl), nl);
        assert_int_equal(rad_solve_cpu(&o.g, o.b0, 2, cpu), 0);
        double worst = 0.0, top = 0.0;
        for (int i = 0; i < 3 * nl; i++)
            top = fmax(top, cpu[i]);
        for (int i = 0; i < 3 * nl; i++)
            worst = fmax(worst, fabs(gpu[i] - cpu[i]) / top);
        printf("# moving block, step %d (links %llu): GPU vs CPU worst |diff| / max %.2e\n", step,
               (unsigned long long)links[step], worst);
        assert_true(worst < 1e-5); /* the bound of test_gpu_bounces_match_cpu */
        free(cpu), free(gpu);
    }
    /* step 1 refit without new links (the vertices-only upload), step 2 rebuilt them */
    assert_true(links[1] == links[0]);
    assert_true(links[2] != links[1]);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    rad_geometry_free(&o.g), free(o.b0);
    gk_gi_radiosity.destroy(s);
    gk_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gpu_bounces_match_cpu),
        cmocka_unit_test(test_gpu_moving_mesh),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
