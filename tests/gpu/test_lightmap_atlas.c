/* The light-map atlas of the lightmap method (app/gi/lightmap/lm_atlas.h) on shipped scenes, built
 * as the method builds it (walls split the surfaces they cross first: light-leak and atrium are cut):
 *  - every chart's rect and gutter lie inside the atlas and no two overlap; every vertex of a
 *    chart maps into its own interior rect; the seed's resolution rule (largest chart 5 texels
 *    along its longer side);
 *  - rendered texel ids (the GPU rasterising each chart in atlas space, ids blended with MIN and
 *    with MAX): no texel is covered by two charts, and every covered texel is inside its chart's
 *    rect;
 *  - no bleeding: an atlas holding each chart's id in its texels, gutters filled by
 *    lm_atlas_dilate, sampled bilinearly at 4x4 points per texel over every chart's triangles,
 *    returns exactly the chart's own id everywhere. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "gi/lightmap/lm_atlas.h"

static gkt_gl GL;
static gk_program_cache *P;

static int setup(void **state)
{
    (void)state;
    if (gkt_gl_open(&GL))
        return -1;
    P = gkt_programs(GL.egl.gles_version);
    return P ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    gk_program_cache_destroy(P);
    gkt_gl_close(&GL);
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
    gk_scene_evaluate(s, 0.0f);
    return s;
}

static void check_layout(const lm_atlas *a)
{
    for (int i = 0; i < a->n_charts; i++) {
        const lm_chart *c = &a->charts[i];
        assert_true(c->w >= 1 && c->h >= 1);
        assert_true(c->x - LM_GUTTER >= 0 && c->y - LM_GUTTER >= 0);
        assert_true(c->x + c->w + LM_GUTTER <= a->width && c->y + c->h + LM_GUTTER <= a->height);
        for (int j = i + 1; j < a->n_charts; j++) {
            const lm_chart *d = &a->charts[j];
            bool apart = c->x + c->w + LM_GUTTER <= d->x - LM_GUTTER || d->x + d->w + LM_GUTTER <= c->x - LM_GUTTER ||
                         c->y + c->h + LM_GUTTER <= d->y - LM_GUTTER || d->y + d->h + LM_GUTTER <= c->y - LM_GUTTER;
            if (!apart)
                fail_msg("charts %d and %d overlap (gutters included)", i, j);
        }
    }
    for (int t = 0; t < a->n_verts / 3; t++) {
        int ci = a->vert_chart[t];
        if (ci < 0)
            continue;
        const lm_chart *c = &a->charts[ci];
        for (int k = 0; k < 3; k++) {
            const float *v = &a->verts[(size_t)(3 * t + k) * LM_VERT_FLOATS];
            float tx = v[3] * (float)a->width, ty = v[4] * (float)a->height;
            if (tx < (float)c->x - 1e-3f || tx > (float)(c->x + c->w) + 1e-3f || ty < (float)c->y - 1e-3f ||
                ty > (float)(c->y + c->h) + 1e-3f)
                fail_msg("chart %d: a vertex maps to texel (%.3f, %.3f), outside its rect", ci, tx, ty);
        }
    }
}

/* The charted triangles as (uv, chart id) vertices. */
static GLuint upload(const lm_atlas *a, int *count)
{
    float *buf = malloc(sizeof(float) * 3 * (size_t)a->n_verts);
    int n = 0;
    for (int t = 0; t < a->n_verts / 3; t++) {
        if (a->vert_chart[t] < 0)
            continue;
        for (int k = 0; k < 3; k++) {
            const float *v = &a->verts[(size_t)(3 * t + k) * LM_VERT_FLOATS];
            buf[3 * n] = v[3], buf[3 * n + 1] = v[4], buf[3 * n + 2] = (float)a->vert_chart[t];
            n++;
        }
    }
    GLuint vao, vbo;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 3 * (size_t)n), buf, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 12, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 12, (void *)8);
    free(buf);
    *count = n;
    return vao;
}

static void draw_into(const gk_target *t, GLuint prog, GLuint vao, int n, GLenum eq, float clear)
{
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(0, 0, t->width, t->height);
    glClearColor(clear, clear, clear, clear);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_BLEND);
    glBlendEquation(eq);
    glUseProgram(prog);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, n);
    glDisable(GL_BLEND);
}

static void check_scene(const char *name)
{
    gk_scene *s = load(name);
    gk_err e = {0};
    lm_atlas a;
    /* as the method builds it: walls split the surfaces they cross first (scene/wall_split.h) */
    gk_wall_regions r;
    int cuts = gk_split_walls(s, &r, &e);
    if (cuts < 0 || lm_atlas_build_regions(&a, s, 5, &r, &e))
        fail_msg("%s", e.msg);
    gk_wall_regions_free(&r);
    print_message("# %s: %d wall cuts\n", name, cuts);
    check_layout(&a);
    /* the seed's rule: the largest chart is 5 texels along its longer side */
    int longest = 0;
    for (int i = 0; i < a.n_charts; i++)
        longest = a.charts[i].w > longest ? a.charts[i].w : (a.charts[i].h > longest ? a.charts[i].h : longest);
    assert_int_equal(longest, 5);

    GLuint ids = gk_program_get(P, "lightmap/test/atlas.vert", "lightmap/test/ids.frag", NULL, &e);
    GLuint bleed = gk_program_get(P, "lightmap/test/atlas.vert", "lightmap/test/bleed.frag", NULL, &e);
    if (!ids || !bleed)
        fail_msg("%s", e.msg);
    int n;
    GLuint vao = upload(&a, &n);
    const GLenum r32[1] = {GL_R32F};
    gk_target tmin, tmax;
    assert_int_equal(gkt_target(&tmin, "ids min", a.width, a.height, 1, r32, false), 0);
    assert_int_equal(gkt_target(&tmax, "ids max", a.width, a.height, 1, r32, false), 0);
    draw_into(&tmin, ids, vao, n, GL_MIN, 1e9f);
    draw_into(&tmax, ids, vao, n, GL_MAX, -1.0f);
    size_t texels = (size_t)a.width * (size_t)a.height;
    float *lo = malloc(sizeof(float) * 4 * texels), *hi = malloc(sizeof(float) * 4 * texels);
    gkt_read_rgba(&tmin, 0, GL_FLOAT, lo);
    gkt_read_rgba(&tmax, 0, GL_FLOAT, hi);
    int covered = 0;
    for (size_t t = 0; t < texels; t++) {
        if (hi[4 * t] < 0.0f)
            continue;
        covered++;
        int id = (int)hi[4 * t];
        if (lo[4 * t] != hi[4 * t])
            fail_msg("%s: texel %zu is covered by charts %d and %d", name, t, (int)lo[4 * t], id);
        const lm_chart *c = &a.charts[id];
        int x = (int)(t % (size_t)a.width), y = (int)(t / (size_t)a.width);
        if (x < c->x || x >= c->x + c->w || y < c->y || y >= c->y + c->h)
            fail_msg("%s: chart %d covers texel (%d, %d), outside its rect", name, id, x, y);
    }

    /* an atlas of ids, gutters dilated, sampled bilinearly at 4x4 points per texel */
    float *tex = calloc(texels * 4, sizeof(float));
    for (int i = 0; i < a.n_charts; i++) {
        const lm_chart *c = &a.charts[i];
        for (int y = c->y; y < c->y + c->h; y++)
            for (int x = c->x; x < c->x + c->w; x++) {
                float *p = &tex[4 * ((size_t)y * (size_t)a.width + (size_t)x)];
                p[0] = (float)(i % 256), p[1] = (float)(i / 256);
            }
    }
    lm_atlas_dilate(&a, tex, 4);
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA16F, a.width, a.height);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, a.width, a.height, GL_RGBA, GL_FLOAT, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gk_target terr;
    assert_int_equal(gkt_target(&terr, "bleed", 4 * a.width, 4 * a.height, 1, r32, false), 0);
    glUseProgram(bleed);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, t);
    gk_uniform_1i(bleed, "u_ids", 0);
    draw_into(&terr, bleed, vao, n, GL_MAX, 0.0f);
    float *err = malloc(sizeof(float) * 4 * texels * 16);
    gkt_read_rgba(&terr, 0, GL_FLOAT, err);
    float worst = 0.0f;
    for (size_t i = 0; i < texels * 16; i++)
        worst = fmaxf(worst, err[4 * i]);
    print_message("# %s: %d charts, atlas %dx%d, texel %.4f m, %d texels covered, worst bleed %g\n", name, a.n_charts,
                  a.width, a.height, a.texel_size, covered, worst);
    assert_true(covered > 0);
    assert_true(worst == 0.0f);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    glDeleteTextures(1, &t);
    gk_target_destroy(&tmin), gk_target_destroy(&tmax), gk_target_destroy(&terr);
    free(lo), free(hi), free(tex), free(err);
    lm_atlas_free(&a);
    gk_scene_free(s);
}

static void cornell(void **state) { (void)state; check_scene("cornell"); }
static void caustic_ring(void **state) { (void)state; check_scene("caustic-ring"); }
static void atrium(void **state) { (void)state; check_scene("atrium"); }
static void light_leak(void **state) { (void)state; check_scene("light-leak"); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cornell),
        cmocka_unit_test(caustic_ring),
        cmocka_unit_test(atrium),
        cmocka_unit_test(light_leak),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
