/* The lightmap method's caustic counting and filter (app/gi/lightmap/lm_caustic_gpu.h), B.6 #6 and
 * M14/M16/M19 of photon-mapping-000-004.md, on a hand-made G-buffer: a white Lambertian plane z = 0
 * (normal +z, pure Lambert) seen by an orthographic camera whose world units are pixels, so every
 * pixel's footprint is 1 m² and the filter's output is exactly (1/π) E with E = Φ c / 1 m²:
 *  - one photon of flux π·156.76 gives, around its pixel, the seed's weights sqrt(19 - i² - j²)
 *    themselves (the filter weights as an image) and 0 outside the 7x7;
 *  - tile culling (occlusion queries over the tiles dilated by k = 3) is bit-identical to
 *    filtering the whole screen, with photons 1 pixel from a tile border and at the screen's edge
 *    (M16), and filters fewer tiles than there are;
 *  - a photon behind the visible surface is not counted; photons on it are (M19);
 *  - the count and cull passes' work (#21): one point fragment per photon on the screen, hidden
 *    ones included (counted by the pass's counting variant), and the cull's dilated tiles' areas
 *    against a pixel-by-pixel count of the tiles each pixel's query draws it in;
 *  - 300 photons in one pixel count 255 (the seed's 8-bit count, M14), and 300 in the R16F count
 *    target of lightmap_count=float. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "gi/lightmap/lm_caustic_gpu.h"
#include "gi/lightmap/lm_caustics.h"

#define W 100
#define H 60

static gkt_gl GL;
static gk_program_cache *P;
static gk_gbuffer_view GB;
static gk_target OUT;

static GLuint tex(GLenum fmt, GLenum format, GLenum type, const void *data)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexStorage2D(GL_TEXTURE_2D, 1, fmt, W, H);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, W, H, format, type, data);
    return t;
}

static int setup(void **state)
{
    (void)state;
    if (gkt_gl_open(&GL))
        return -1;
    P = gkt_programs(GL.egl.gles_version);
    static float depth[W * H], normal[W * H * 4], emission[W * H * 4];
    static unsigned char albedo[W * H * 4], specular[W * H * 4];
    for (int i = 0; i < W * H; i++) {
        depth[i] = 0.5f; /* z = 0 through m4_ortho(.., -1, 1) */
        normal[4 * i + 2] = 1.0f, normal[4 * i + 3] = 1.0f;
        albedo[4 * i] = albedo[4 * i + 1] = albedo[4 * i + 2] = 255; /* white, metallic 0 */
        /* specular weight 0: pure Lambert */
    }
    GB.width = W, GB.height = H;
    GB.depth = tex(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    GB.normal = tex(GL_RGBA16F, GL_RGBA, GL_FLOAT, normal);
    GB.emission = tex(GL_RGBA16F, GL_RGBA, GL_FLOAT, emission);
    GB.albedo = tex(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, albedo);
    GB.specular = tex(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, specular);
    GB.view = m4_identity();
    GB.proj = m4_ortho(0, W, 0, H, -1, 1);
    GB.view_proj = GB.proj;
    GB.inv_view_proj = m4_inverse(GB.proj);
    GB.eye = v3(W / 2.0f, H / 2.0f, 100.0f); /* the hidden test's tolerance is 1/500 of the distance */
    const GLenum f32[1] = {GL_RGBA32F};
    return gkt_target(&OUT, "caustic output", W, H, 1, f32, false);
}

static int teardown(void **state)
{
    (void)state;
    gk_target_destroy(&OUT);
    gk_program_cache_destroy(P);
    gkt_gl_close(&GL);
    return 0;
}

/* Filters the photons (xyz each) into OUT (cleared first); returns the readback (W*H*4 floats). */
static float *filter(const float *pts, int n, vec3 flux, bool cull, lm_caustic_gpu *g)
{
    gk_err e = {0};
    glBindFramebuffer(GL_FRAMEBUFFER, OUT.fbo);
    const GLfloat zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    if (lm_caustic_gpu_upload(g, pts, n, 3, &e) || lm_caustic_gpu_draw(g, P, &GB, flux, cull, OUT.fbo, NULL, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    float *out = malloc(sizeof(float) * 4 * W * H);
    gkt_read_rgba(&OUT, 0, GL_FLOAT, out);
    return out;
}

static void test_single_photon_shows_the_weights(void **state)
{
    (void)state;
    lm_caustic_gpu g = {0};
    const float pt[3] = {50.5f, 30.5f, 0.0f};
    double wsum = 0;
    for (int j = -3; j <= 3; j++)
        for (int i = -3; i <= 3; i++)
            wsum += lm_caustic_weight(i, j);
    float phi = (float)(M_PI * wsum);
    float *out = filter(pt, 1, v3(phi, phi, phi), true, &g);
    double worst = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = x - 50, j = y - 30;
            float v = out[4 * (y * W + x)];
            if (abs(i) <= 3 && abs(j) <= 3) {
                double rel = fabs(v - lm_caustic_weight(i, j)) / lm_caustic_weight(i, j);
                worst = rel > worst ? rel : worst;
            } else {
                assert_true(v == 0.0f);
            }
        }
    print_message("one photon: the filtered image matches sqrt(19 - i^2 - j^2) within %.2e\n", worst);
    /* fp32 shader arithmetic (the weights summed in the shader, the pixel area from unprojected
       rays): measured 7.5e-6; bound 4x that */
    assert_true(worst < 3e-5);
    free(out);
    lm_caustic_gpu_free(&g);
}

/* The count texels the culled filter reads, counted pixel by pixel: the tiles within k = 3 pixels
   of a photon's pixel (every photon here lies on the plane, so each is counted), each of their
   pixels' 7 x 7 neighbours on the screen. */
static double culled_reads(const float *pts, int n, int tile)
{
    double reads = 0.0;
    for (int ty = 0; ty * tile < H; ty++)
        for (int tx = 0; tx * tile < W; tx++) {
            bool on = false;
            for (int i = 0; i < n && !on; i++) {
                int px = (int)pts[3 * i], py = (int)pts[3 * i + 1];
                on = px >= tx * tile - 3 && px < (tx + 1) * tile + 3 && py >= ty * tile - 3 && py < (ty + 1) * tile + 3;
            }
            for (int y = ty * tile; on && y < (ty + 1) * tile && y < H; y++)
                for (int x = tx * tile; x < (tx + 1) * tile && x < W; x++)
                    for (int j = -3; j <= 3; j++)
                        for (int i = -3; i <= 3; i++)
                            reads += x + i >= 0 && x + i < W && y + j >= 0 && y + j < H;
        }
    return reads;
}

/* The cull's fragments, pixel by pixel: each pixel is drawn once per tile whose rect dilated by
   k = 3 (and clipped to the screen) holds it -- once inside a tile, twice within 3 px of a border,
   4 times near a corner. */
static double cull_fragments(int tile)
{
    double n = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int ty = 0; ty * tile < H; ty++)
                for (int tx = 0; tx * tile < W; tx++)
                    n += x >= tx * tile - 3 && x < (tx + 1) * tile + 3 && y >= ty * tile - 3 && y < (ty + 1) * tile + 3;
    return n;
}

static void test_culling_is_bit_identical(void **state)
{
    (void)state;
    lm_caustic_gpu g = {0};
    /* tiles are 10 px (W / 10): a photon 1 px left of the border x = 30, one 1 px above y = 20, a
       cluster, and one in the screen's corner */
    const float pts[] = {29.5f, 45.5f, 0, 44.5f, 19.5f, 0, 70.5f, 40.5f, 0, 71.5f, 40.5f, 0, 71.5f, 41.5f, 0,
                         72.2f, 43.7f, 0, 0.5f,  0.5f,  0, 99.5f, 59.5f, 0};
    int n = (int)(sizeof pts / sizeof pts[0] / 3);
    vec3 flux = v3(1.0f, 0.8f, 0.3f);
    g.count_work = true;
    float *culled = filter(pts, n, flux, true, &g);
    g.count_work = false;
    int tiles = g.tiles_filtered, total = g.tiles_x * g.tiles_y;
    double culled_reads_model = g.filter_reads, culled_fragments = g.cull_fragments;
    /* the count pass: one point fragment per photon, all on the screen */
    assert_true(g.count_fragments.counted && g.count_fragments.value[0] == (double)n);
    print_message("culling: %.0f fragments in the tile queries (%d tiles of %d px)\n", culled_fragments, total, g.tile);
    assert_true(culled_fragments == cull_fragments(g.tile));
    float *full = filter(pts, n, flux, false, &g);
    print_message("culling: %d of %d tiles filtered\n", tiles, total);
    assert_memory_equal(culled, full, sizeof(float) * 4 * W * H);
    assert_false(g.count_fragments.counted); /* not a counting draw */
    assert_true(g.cull_fragments == 0.0);    /* no cull, no queries */
    /* the photon at x = 29.5 lights x = 30..32 in the next tile: only the dilation filters it */
    assert_true(culled[4 * (45 * W + 31)] > 0.0f);
    /* the photons' tiles and the ones within 3 px of them: 10 of 60 measured */
    assert_true(tiles > 0 && tiles < total);
    /* the filter's work (#21): the whole screen reads 7 x 7 texels a pixel, less what its edges cut
       off: per axis 7 n - 2 (3 + 2 + 1) */
    assert_true(g.filter_reads == (7.0 * W - 12.0) * (7.0 * H - 12.0));
    assert_true(culled_reads(pts, n, g.tile) == culled_reads_model);
    free(culled), free(full);
    lm_caustic_gpu_free(&g);
}

static void test_hidden_photons_and_saturation(void **state)
{
    (void)state;
    lm_caustic_gpu g = {0};
    /* behind the plane (z = -0.5 is farther from the eye at z = +100): not counted */
    const float behind[3] = {50.5f, 30.5f, -0.5f};
    g.count_work = true;
    float *out = filter(behind, 1, v3(1, 1, 1), true, &g);
    g.count_work = false;
    /* ... but rasterized: the count pass's work includes the fragments it discards */
    assert_true(g.count_fragments.counted && g.count_fragments.value[0] == 1.0);
    for (int i = 0; i < W * H; i++)
        assert_true(out[4 * i] == 0.0f);
    free(out);
    /* 300 photons in one pixel count 255: the centre shows 255 x one photon's */
    float *many = malloc(sizeof(float) * 3 * 300);
    for (int i = 0; i < 300; i++)
        many[3 * i] = 20.5f, many[3 * i + 1] = 10.5f, many[3 * i + 2] = 0.0f;
    double wsum = 0;
    for (int j = -3; j <= 3; j++)
        for (int i = -3; i <= 3; i++)
            wsum += lm_caustic_weight(i, j);
    float phi = (float)(M_PI * wsum);
    out = filter(many, 300, v3(phi, phi, phi), true, &g);
    float centre = out[4 * (10 * W + 20)];
    print_message("300 photons in one pixel: centre %.4f = %.2f photons (8-bit count)\n", centre,
                  centre / lm_caustic_weight(0, 0));
    assert_true(fabsf(centre / lm_caustic_weight(0, 0) - 255.0f) < 0.01f);
    free(out);
    g.count_format = GL_R16F; /* llvmpipe: GLES 3.2, R16F colour-renderable */
    out = filter(many, 300, v3(phi, phi, phi), true, &g);
    centre = out[4 * (10 * W + 20)];
    print_message("300 photons in one pixel, R16F count: %.2f photons\n", centre / lm_caustic_weight(0, 0));
    assert_true(fabsf(centre / lm_caustic_weight(0, 0) - 300.0f) < 0.01f);
    free(out), free(many);
    lm_caustic_gpu_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_single_photon_shows_the_weights),
        cmocka_unit_test(test_culling_is_bit_identical),
        cmocka_unit_test(test_hidden_photons_and_saturation),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
