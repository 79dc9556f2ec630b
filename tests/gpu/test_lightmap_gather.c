/* The lightmap method's GPU final gather (app/gi/lightmap/lm_gather.h), B.6 #5 of
 * photon-mapping-000-004.md:
 *  - the coverage of the a = 2 face is the discrete Σ F_h: 0.8329 / 0.8315 / 0.8312 at 8² / 16² /
 *    32² (not the seed's "about 86%");
 *  - a uniform environment of radiance L gathers E/π = L within 0.5% (fp32 sums, fp16 store);
 *  - a constant-radiance square of half-width 1 at distance 1 gives F = Σ F_h = 0.5541 (the
 *    closed form (4/π)(a/√(1+a²)) atan(a/√(1+a²))) within 0.5% at 16² and 32²;
 *  - the result lands in every target texel of the job (a texel and its gutter copies);
 *  - the reduction's reads (#21, app/gi/lightmap/lm_work.c): res² for the one job. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "gi/lightmap/lm_gather.h"

static gkt_gl GL;
static gk_program_cache *P;
static GLuint prog, vao, vbo;
static int n_verts;
static float radiance = 1.0f;

static int setup(void **state)
{
    (void)state;
    if (gkt_gl_open(&GL))
        return -1;
    P = gkt_programs(GL.egl.gles_version);
    gk_err e = {0};
    prog = gk_program_get(P, "lightmap/uv.vert", "lightmap/test/const.frag", NULL, &e);
    if (!prog) {
        fprintf(stderr, "%s\n", e.msg);
        return -1;
    }
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    gk_program_cache_destroy(P);
    gkt_gl_close(&GL);
    return 0;
}

/* quads as (position, uv) triangles */
static void upload_quads(const vec3 *corners, int n_quads)
{
    float *buf = malloc(sizeof(float) * 5 * 6 * (size_t)n_quads);
    static const int order[6] = {0, 1, 2, 0, 2, 3};
    int k = 0;
    for (int q = 0; q < n_quads; q++)
        for (int i = 0; i < 6; i++) {
            vec3 p = corners[4 * q + order[i]];
            float *o = &buf[5 * k++];
            o[0] = p.x, o[1] = p.y, o[2] = p.z, o[3] = 0, o[4] = 0;
        }
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 5 * (size_t)k), buf, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 20, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 20, (void *)12);
    n_verts = k;
    free(buf);
}

static int draw(void *ctx, const mat4 *vp, gk_err *e)
{
    (void)ctx, (void)e;
    glUseProgram(prog);
    mat4 id = m4_identity();
    gk_uniform_mat4(prog, "u_model", id.m);
    gk_uniform_mat4(prog, "u_viewproj", vp->m);
    gk_uniform_3f(prog, "u_radiance", radiance, radiance, radiance);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, n_verts);
    return 0;
}

/* Gathers one job from the origin looking down -z into a 4x4 RGBA16F map; returns texel (x, y). */
static float gather(int res, int tx, int ty, float *other)
{
    gk_err e = {0};
    lm_gather g;
    assert_int_equal(lm_gather_setup(&g, res, 4, &e), 0);
    GLuint iim;
    glGenTextures(1, &iim);
    glBindTexture(GL_TEXTURE_2D, iim);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA16F, 4, 4);
    lm_gather_job j = {v3(0, 0, 0), v3(0, 0, -1), v3(0, 1, 0), 2, {{tx, ty}, {3, 3}}};
    g.count_work = true;
    if (lm_gather_run(&g, P, &j, 1, 0.01f, 100.0f, draw, NULL, iim, &e))
        fail_msg("%s", e.msg);
    assert_true(g.reduce_fetches.counted && g.reduce_fetches.value[0] == (double)res * res);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, iim, 0);
    float px[16 * 4];
    glReadPixels(0, 0, 4, 4, GL_RGBA, GL_FLOAT, px);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    *other = px[4 * (3 * 4 + 3)];
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &iim);
    lm_gather_free(&g);
    return px[4 * (ty * 4 + tx)];
}

static void coverage_is_the_discrete_sum(void **state)
{
    (void)state;
    double c8 = lm_gather_coverage(8), c16 = lm_gather_coverage(16), c32 = lm_gather_coverage(32);
    print_message("# coverage at a = 2: %.4f (8²) %.4f (16²) %.4f (32²)\n", c8, c16, c32);
    assert_float_equal(c8, 0.8329, 1e-4);
    assert_float_equal(c16, 0.8315, 1e-4);
    assert_float_equal(c32, 0.8312, 1e-4);
}

static void uniform_environment(void **state)
{
    (void)state;
    /* a 10 m cube around the gathering point, radiance 1 on every wall */
    float s = 5.0f;
    vec3 c[24] = {
        v3(-s, -s, -s), v3(s, -s, -s), v3(s, s, -s), v3(-s, s, -s),  v3(-s, -s, s), v3(s, -s, s),
        v3(s, s, s),    v3(-s, s, s),  v3(-s, -s, -s), v3(-s, s, -s), v3(-s, s, s), v3(-s, -s, s),
        v3(s, -s, -s),  v3(s, s, -s),  v3(s, s, s),   v3(s, -s, s),  v3(-s, -s, -s), v3(s, -s, -s),
        v3(s, -s, s),   v3(-s, -s, s), v3(-s, s, -s), v3(s, s, -s),  v3(s, s, s),   v3(-s, s, s)};
    upload_quads(c, 6);
    radiance = 1.0f;
    for (int res = 8; res <= 32; res *= 2) {
        float other, E = gather(res, 1, 2, &other);
        print_message("# uniform L = 1, %d²: E/π = %.5f\n", res, E / 3.14159265f);
        assert_float_equal(E / 3.14159265f, 1.0f, 0.005f);
        assert_float_equal(other, E, 0.0f); /* the gutter copy */
    }
}

static void square_half_width_one(void **state)
{
    (void)state;
    vec3 c[4] = {v3(-1, -1, -1), v3(1, -1, -1), v3(1, 1, -1), v3(-1, 1, -1)};
    upload_quads(c, 1);
    radiance = 1.0f;
    for (int res = 16; res <= 32; res *= 2) {
        float other, E = gather(res, 0, 0, &other);
        double F = E / 3.14159265 * lm_gather_coverage(res); /* Σ F_h over the square */
        print_message("# square of half-width 1 at distance 1, %d²: F = %.4f (closed form 0.5541)\n", res, F);
        assert_float_equal(F, 0.5541, 0.005 * 0.5541);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(coverage_is_the_discrete_sum),
        cmocka_unit_test(uniform_environment),
        cmocka_unit_test(square_half_width_one),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
