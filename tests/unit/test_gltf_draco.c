/* KHR_draco_mesh_compression (gltf_draco.cpp): a displaced 16 x 16 grid with normals, UVs and 8-bit
 * vertex colours is Draco-encoded here (tests/common/draco_encode.cpp), wrapped in a glTF whose
 * accessors declare what the spec asks, and loaded from memory. The decoder may renumber points and
 * reorder faces, so each loaded triangle is matched to the source triangle with the nearest
 * centroid and compared vertex by vertex (same winding), within the quantization step of each
 * attribute. Broken files (a count that disagrees with the stream, a truncated stream, an
 * attribute id the stream lacks) are refused naming the file and the fault. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/draco_encode.h"
#include "common/grid_mesh.h"
#include "scene/scene.h"

#define GRID 16
#define NV ((GRID + 1) * (GRID + 1))
#define NT (2 * GRID * GRID)
#define POSITION_BITS 14

static float pos[NV * 3], nrm[NV * 3], uv[NV * 2];
static uint8_t rgba[NV * 4];
static uint32_t idx[NT * 3];

/* The shared grid (grid_mesh.h) with 8-bit colours: red along x, green along y. */
static void make_grid(void)
{
    gk_test_grid(GRID, pos, nrm, 3, uv, 1.0f, 0.0f, idx);
    for (int j = 0; j <= GRID; j++)
        for (int i = 0; i <= GRID; i++) {
            int v = j * (GRID + 1) + i;
            rgba[4 * v] = (uint8_t)(i * 15), rgba[4 * v + 1] = (uint8_t)(j * 15), rgba[4 * v + 2] = 200,
                      rgba[4 * v + 3] = 255;
        }
}

typedef struct variant {
    size_t stream_bytes;  /* 0: the whole stream */
    int position_count;   /* 0: NV */
    int position_id;      /* -1: the stream's */
} variant;

/* The glTF around one encoded stream (data: URI), per the extension's spec: accessors without
 * bufferViews, counts and types as decoded, POSITION's min/max. */
static char *make_gltf(const unsigned char *stream, size_t size, const gk_draco_ids *ids, variant v)
{
    size_t n = v.stream_bytes ? v.stream_bytes : size;
    char *b64 = gk_test_base64(stream, n);
    size_t cap = strlen(b64) + 4096;
    char *j = malloc(cap);
    snprintf(j, cap,
             "{\"asset\":{\"version\":\"2.0\"},"
             "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
             "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],"
             "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu}],"
             "\"accessors\":["
             "{\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\",\"min\":[0,0,-0.2],\"max\":[2,1,0.2]},"
             "{\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
             "{\"componentType\":5126,\"count\":%d,\"type\":\"VEC2\"},"
             "{\"componentType\":5121,\"normalized\":true,\"count\":%d,\"type\":\"VEC4\"},"
             "{\"componentType\":5125,\"count\":%d,\"type\":\"SCALAR\"}],"
             "\"meshes\":[{\"name\":\"grid\",\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
             "\"TEXCOORD_0\":2,\"COLOR_0\":3},\"indices\":4,\"extensions\":{\"KHR_draco_mesh_compression\":"
             "{\"bufferView\":0,\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,\"TEXCOORD_0\":%d,\"COLOR_0\":%d}}}}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
             n, b64, n, v.position_count ? v.position_count : NV, NV, NV, NV, 3 * NT,
             v.position_id >= 0 ? v.position_id : ids->position, ids->normal, ids->uv, ids->color);
    free(b64);
    return j;
}

static unsigned char *stream;
static size_t stream_size;
static gk_draco_ids ids;

static int setup(void **state)
{
    (void)state;
    make_grid();
    return gk_test_draco_encode(pos, nrm, uv, rgba, NV, idx, NT, POSITION_BITS, &stream, &stream_size, &ids);
}

static int teardown(void **state)
{
    (void)state;
    free(stream);
    return 0;
}

static bool as_glb;

/* The same JSON as a GLB's JSON chunk (the buffer stays a data: URI, which a GLB may have): the
   loader patches the JSON chunk of a GLB, not only a text file. */
static gk_scene *load(variant v, gk_err *e)
{
    char *json = make_gltf(stream, stream_size, &ids, v);
    size_t n = strlen(json), padded = (n + 3) & ~(size_t)3, total = 20 + padded;
    unsigned char *bytes = (unsigned char *)json;
    if (as_glb) {
        bytes = malloc(total);
        uint32_t head[5] = {0x46546C67u /* glTF */, 2, (uint32_t)total, (uint32_t)padded, 0x4E4F534Au /* JSON */};
        memcpy(bytes, head, sizeof head);
        memcpy(bytes + 20, json, n);
        memset(bytes + 20 + n, ' ', padded - n);
        n = total;
    }
    gk_scene *s = gk_scene_load_memory(bytes, n, "draco.gltf", NULL, e);
    if (bytes != (unsigned char *)json)
        free(bytes);
    free(json);
    return s;
}

static void centroid(const float *p, const uint32_t *t, float c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = (p[3 * t[0] + k] + p[3 * t[1] + k] + p[3 * t[2] + k]) / 3.0f;
}

static void test_round_trip_body(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_scene *s = load((variant){0, 0, -1}, &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    assert_int_equal(s->gltf.draco_primitives, 1);
    assert_non_null(strstr(s->gltf.extensions_read, "KHR_draco_mesh_compression"));
    const gk_mesh *m = &s->meshes[0];
    assert_int_equal(m->n_triangles, NT);
    assert_non_null(m->normals);
    assert_non_null(m->uvs);
    assert_non_null(m->colors);
    printf("# stream %zu bytes for %d vertices, %d triangles (%zu bytes uncompressed); %u points decoded\n",
           stream_size, NV, NT, (size_t)NV * (12 + 12 + 8 + 4) + (size_t)NT * 12, m->n_vertices);
    /* Quantization steps: positions over the largest extent (2 m) in 2^14 - 1 steps, UVs 12 bits
       over [0, 1]; colours are bytes, exact. */
    /* Rounding to the nearest quantization step errs by half a step at most (measured: exactly
       that, 6.1e-5 m and 1.2e-4); normals are octahedral, 2 / 1023 a step in the octahedron's
       square, stretched by at most 1.5 on the sphere (measured 1.9e-3). */
    const float pos_step = 2.0f / ((1 << POSITION_BITS) - 1), uv_step = 1.0f / 4095.0f;
    const float pos_tol = 0.5f * pos_step + 1e-6f, uv_tol = 0.5f * uv_step + 1e-6f, nrm_tol = 1.5f * 2.0f / 1023.0f;
    float worst_pos = 0.0f, worst_nrm = 0.0f, worst_uv = 0.0f, worst_col = 0.0f;
    static int used[NT];
    memset(used, 0, sizeof used);
    for (uint32_t t = 0; t < m->n_triangles; t++) {
        const uint32_t *lt = &m->indices[3 * t];
        float c[3], best = 1e30f;
        int bi = -1;
        centroid(m->positions, lt, c);
        for (int o = 0; o < NT; o++) {
            float oc[3];
            centroid(pos, &idx[3 * o], oc);
            float d = (c[0] - oc[0]) * (c[0] - oc[0]) + (c[1] - oc[1]) * (c[1] - oc[1]) + (c[2] - oc[2]) * (c[2] - oc[2]);
            if (d < best)
                best = d, bi = o;
        }
        assert_true(bi >= 0);
        used[bi]++;
        /* the same triangle, the same winding: some rotation of its corners matches */
        int rot = -1;
        for (int r = 0; r < 3 && rot < 0; r++) {
            float d = 0.0f;
            for (int k = 0; k < 3; k++)
                for (int a = 0; a < 3; a++)
                    d = fmaxf(d, fabsf(m->positions[3 * lt[k] + a] - pos[3 * idx[3 * bi + (k + r) % 3] + a]));
            if (d <= pos_tol)
                rot = r;
        }
        if (rot < 0)
            print_error("triangle %u matches no rotation of source triangle %d\n", t, bi);
        assert_true(rot >= 0);
        for (int k = 0; k < 3; k++) {
            uint32_t lv = lt[k], sv = idx[3 * bi + (k + rot) % 3];
            for (int a = 0; a < 3; a++) {
                worst_pos = fmaxf(worst_pos, fabsf(m->positions[3 * lv + a] - pos[3 * sv + a]));
                worst_nrm = fmaxf(worst_nrm, fabsf(m->normals[3 * lv + a] - nrm[3 * sv + a]));
            }
            for (int a = 0; a < 2; a++)
                worst_uv = fmaxf(worst_uv, fabsf(m->uvs[2 * lv + a] - uv[2 * sv + a]));
            for (int a = 0; a < 4; a++)
                worst_col = fmaxf(worst_col, fabsf(m->colors[4 * lv + a] - rgba[4 * sv + a] / 255.0f));
        }
    }
    printf("# largest differences: position %.2e m (step %.2e), normal %.2e, uv %.2e, colour %.2e\n", worst_pos,
           pos_step, worst_nrm, worst_uv, worst_col);
    for (int o = 0; o < NT; o++)
        assert_int_equal(used[o], 1); /* every source triangle exactly once */
    assert_true(worst_pos <= pos_tol);
    assert_true(worst_nrm <= nrm_tol);
    assert_true(worst_uv <= uv_tol);
    assert_true(worst_col <= 1e-6f);
    gk_scene_free(s);
}

static void expect_refused(variant v, const char *what)
{
    gk_err e = {0};
    gk_scene *s = load(v, &e);
    if (s)
        gk_scene_free(s);
    assert_null(s);
    assert_int_equal(e.code, GK_EINPUT);
    if (strncmp(e.msg, "draco.gltf: ", 12) != 0 || !strstr(e.msg, what))
        print_error("message: %s\nwanted the file and '%s'\n", e.msg, what);
    assert_int_equal(strncmp(e.msg, "draco.gltf: ", 12), 0);
    assert_non_null(strstr(e.msg, what));
}

static void test_round_trip(void **state)
{
    as_glb = false;
    test_round_trip_body(state);
}

static void test_glb(void **state)
{
    as_glb = true;
    test_round_trip_body(state);
    as_glb = false;
}

static void test_count_mismatch(void **state)
{
    (void)state;
    expect_refused((variant){0, NV + 1, -1}, "attribute POSITION: accessor 0 has count 290, the stream 289 points");
}

static void test_truncated_stream(void **state)
{
    (void)state;
    expect_refused((variant){stream_size / 2, 0, -1}, "the Draco stream does not decode");
}

static void test_unknown_attribute_id(void **state)
{
    (void)state;
    expect_refused((variant){0, 0, 17}, "attribute POSITION: the stream has no attribute with id 17");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_glb),
        cmocka_unit_test(test_count_mismatch),
        cmocka_unit_test(test_truncated_stream),
        cmocka_unit_test(test_unknown_attribute_id),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
