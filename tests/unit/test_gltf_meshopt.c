/* EXT_meshopt_compression (gltf_meshopt.cpp): a displaced 16 x 16 grid is compressed here with
 * libmeshoptimizer's encoders the way gltfpack lays a file out -- the compressed streams in buffer
 * 0, the views over a fallback buffer 1 that has no uri (its bytes exist only compressed) -- and
 * loaded from memory: positions (ATTRIBUTES, no filter) come back bit for bit, normals through the
 * OCTAHEDRAL filter (16-bit, KHR_mesh_quantization SHORT normals), UVs through the EXPONENTIAL
 * filter, indices as TRIANGLES or as an INDICES sequence, each within what its filter's encoding
 * keeps. A corrupt stream, a view whose size disagrees with count x byteStride or whose own
 * byteStride disagrees with the extension's, and an unknown mode are refused naming the file and
 * the bufferView. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdbool.h>
#include <meshoptimizer.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/grid_mesh.h"
#include "scene/scene.h"

#define GRID 16
#define NV ((GRID + 1) * (GRID + 1))
#define NT (2 * GRID * GRID)
#define OCT_BITS 16
#define EXP_BITS 20

static float pos[NV * 3], nrm4[NV * 4], uv[NV * 2];
static uint32_t idx[NT * 3];

/* The shared grid (grid_mesh.h); U runs to 3 so the exponential filter's shared exponent is
   tested beyond 1, V starts off 0. */
static void make_grid(void)
{
    gk_test_grid(GRID, pos, nrm4, 4, uv, 3.0f, 0.001f, idx);
}

/* The compressed streams, one after another (4-aligned), in buffer 0. */
typedef struct stream {
    size_t at, len, count, stride;
} stream;

static unsigned char packed[1 << 16];
static size_t packed_len;

static stream put(const unsigned char *bytes, size_t len, size_t count, size_t stride)
{
    stream s = {packed_len, len, count, stride};
    memcpy(packed + packed_len, bytes, len);
    packed_len += (len + 3) & ~(size_t)3;
    return s;
}

static stream s_pos, s_nrm, s_uv, s_tri, s_seq;

static int setup(void **state)
{
    (void)state;
    make_grid();
    static unsigned char tmp[1 << 16];
    static short oct[NV * 4];
    static float expv[NV * 2];
    size_t n = meshopt_encodeVertexBuffer(tmp, sizeof tmp, pos, NV, 12);
    s_pos = put(tmp, n, NV, 12);
    meshopt_encodeFilterOct(oct, NV, 8, OCT_BITS, nrm4);
    n = meshopt_encodeVertexBuffer(tmp, sizeof tmp, oct, NV, 8);
    s_nrm = put(tmp, n, NV, 8);
    meshopt_encodeFilterExp(expv, NV, 8, EXP_BITS, uv);
    n = meshopt_encodeVertexBuffer(tmp, sizeof tmp, expv, NV, 8);
    s_uv = put(tmp, n, NV, 8);
    n = meshopt_encodeIndexBuffer(tmp, sizeof tmp, idx, 3 * NT);
    s_tri = put(tmp, n, 3 * NT, 4);
    n = meshopt_encodeIndexSequence(tmp, sizeof tmp, idx, 3 * NT);
    s_seq = put(tmp, n, 3 * NT, 4);
    return s_pos.len && s_nrm.len && s_uv.len && s_tri.len && s_seq.len ? 0 : -1;
}

typedef struct variant {
    bool sequence;          /* indices as an INDICES sequence, not TRIANGLES */
    bool corrupt;           /* the position stream's bytes overwritten */
    size_t pos_view_bytes;  /* 0: count x stride */
    int pos_view_stride;    /* the positions view's own byteStride; 0: 12, the extension's */
    const char *index_mode; /* NULL: as `sequence` says */
} variant;

static char *make_gltf(variant v)
{
    static unsigned char bytes[1 << 16];
    memcpy(bytes, packed, packed_len);
    if (v.corrupt)
        memset(bytes + s_pos.at, 0xA5, s_pos.len);
    char *b64 = gk_test_base64(bytes, packed_len);
    const stream *si = v.sequence ? &s_seq : &s_tri;
    const char *mode = v.index_mode ? v.index_mode : v.sequence ? "INDICES" : "TRIANGLES";
    /* the fallback buffer's layout: positions, normals, uvs, indices, each count x stride */
    size_t f_pos = 0, f_nrm = f_pos + NV * 12, f_uv = f_nrm + NV * 8, f_idx = f_uv + NV * 8, f_end = f_idx + 3 * NT * 4;
    size_t cap = strlen(b64) + 8192;
    char *j = malloc(cap);
    snprintf(j, cap,
             "{\"asset\":{\"version\":\"2.0\"},"
             "\"extensionsUsed\":[\"EXT_meshopt_compression\",\"KHR_mesh_quantization\"],"
             "\"extensionsRequired\":[\"EXT_meshopt_compression\",\"KHR_mesh_quantization\"],"
             "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"},"
             "{\"byteLength\":%zu,\"extensions\":{\"EXT_meshopt_compression\":{\"fallback\":true}}}],"
             "\"bufferViews\":["
             "{\"buffer\":1,\"byteOffset\":%zu,\"byteLength\":%zu,\"byteStride\":%d,\"extensions\":{\"EXT_meshopt_compression\":"
             "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"byteStride\":12,\"count\":%d,\"mode\":\"ATTRIBUTES\"}}},"
             "{\"buffer\":1,\"byteOffset\":%zu,\"byteLength\":%d,\"byteStride\":8,\"extensions\":{\"EXT_meshopt_compression\":"
             "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"byteStride\":8,\"count\":%d,\"mode\":\"ATTRIBUTES\","
             "\"filter\":\"OCTAHEDRAL\"}}},"
             "{\"buffer\":1,\"byteOffset\":%zu,\"byteLength\":%d,\"byteStride\":8,\"extensions\":{\"EXT_meshopt_compression\":"
             "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"byteStride\":8,\"count\":%d,\"mode\":\"ATTRIBUTES\","
             "\"filter\":\"EXPONENTIAL\"}}},"
             "{\"buffer\":1,\"byteOffset\":%zu,\"byteLength\":%d,\"extensions\":{\"EXT_meshopt_compression\":"
             "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"byteStride\":4,\"count\":%d,\"mode\":\"%s\"}}}],"
             "\"accessors\":["
             "{\"bufferView\":0,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\",\"min\":[0,0,-0.2],\"max\":[2,1,0.2]},"
             "{\"bufferView\":1,\"componentType\":5122,\"normalized\":true,\"count\":%d,\"type\":\"VEC3\"},"
             "{\"bufferView\":2,\"componentType\":5126,\"count\":%d,\"type\":\"VEC2\"},"
             "{\"bufferView\":3,\"componentType\":5125,\"count\":%d,\"type\":\"SCALAR\"}],"
             "\"meshes\":[{\"name\":\"grid\",\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
             "\"TEXCOORD_0\":2},\"indices\":3}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
             packed_len, b64, f_end,                                                        /* buffers */
             f_pos, v.pos_view_bytes ? v.pos_view_bytes : (size_t)NV * 12, v.pos_view_stride ? v.pos_view_stride : 12,
             s_pos.at, s_pos.len, NV, /* positions */
             f_nrm, NV * 8, s_nrm.at, s_nrm.len, NV,                                       /* normals */
             f_uv, NV * 8, s_uv.at, s_uv.len, NV,                                          /* uvs */
             f_idx, 3 * NT * 4, si->at, si->len, 3 * NT, mode,                             /* indices */
             NV, NV, NV, 3 * NT);
    free(b64);
    return j;
}

static gk_scene *load(variant v, gk_err *e)
{
    char *json = make_gltf(v);
    gk_scene *s = gk_scene_load_memory(json, strlen(json), "meshopt.gltf", NULL, e);
    free(json);
    return s;
}

static void round_trip(bool sequence)
{
    gk_err e = {0};
    gk_scene *s = load((variant){.sequence = sequence}, &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    assert_int_equal(s->gltf.meshopt_views, 4);
    assert_non_null(strstr(s->gltf.extensions_read, "EXT_meshopt_compression"));
    const gk_mesh *m = &s->meshes[0];
    assert_int_equal(m->n_vertices, NV);
    assert_int_equal(m->n_triangles, NT);
    assert_non_null(m->normals);
    assert_non_null(m->uvs);
    /* The vertex codec is lossless and keeps the order: positions bit for bit. */
    assert_memory_equal(m->positions, pos, sizeof pos);
    /* Octahedral, 16 bits: a step of 2 / 32767 in the octahedron's square, up to 1.5x that on the
       sphere, then stored as SHORT (1 / 32767 more): 1.2e-4. Exponential, 20-bit mantissa shared by
       the vector: 2^-19 of its largest component (3) = 5.7e-6. */
    const float nrm_tol = 1.5f * 2.0f / 32767.0f + 1.0f / 32767.0f, uv_tol = 3.0f * ldexpf(1.0f, -(EXP_BITS - 1));
    float worst_nrm = 0.0f, worst_uv = 0.0f;
    for (int v = 0; v < NV; v++) {
        for (int a = 0; a < 3; a++)
            worst_nrm = fmaxf(worst_nrm, fabsf(m->normals[3 * v + a] - nrm4[4 * v + a]));
        for (int a = 0; a < 2; a++)
            worst_uv = fmaxf(worst_uv, fabsf(m->uvs[2 * v + a] - uv[2 * v + a]));
    }
    /* TRIANGLES may rotate a triangle's corners (winding kept); INDICES keep the sequence. */
    int rotated = 0;
    for (int t = 0; t < NT; t++) {
        const uint32_t *lt = &m->indices[3 * t];
        int rot = -1;
        for (int r = 0; r < 3 && rot < 0; r++)
            if (lt[0] == idx[3 * t + r] && lt[1] == idx[3 * t + (r + 1) % 3] && lt[2] == idx[3 * t + (r + 2) % 3])
                rot = r;
        if (rot < 0)
            print_error("triangle %d (%u %u %u) is not a rotation of (%u %u %u)\n", t, lt[0], lt[1], lt[2],
                        idx[3 * t], idx[3 * t + 1], idx[3 * t + 2]);
        assert_true(rot >= 0);
        rotated += rot != 0;
    }
    printf("# %s: %zu compressed bytes for %d uncompressed; largest differences: normal %.2e (bound %.2e), uv "
           "%.2e (bound %.2e); %d of %d triangles rotated\n",
           sequence ? "INDICES" : "TRIANGLES", packed_len - (sequence ? s_tri.len : s_seq.len),
           NV * (12 + 8 + 8) + NT * 12, worst_nrm, nrm_tol, worst_uv, uv_tol, rotated, NT);
    if (sequence)
        assert_int_equal(rotated, 0);
    assert_true(worst_nrm <= nrm_tol);
    assert_true(worst_uv <= uv_tol);
    gk_scene_free(s);
}

static void test_triangles(void **state)
{
    (void)state;
    round_trip(false);
}

static void test_index_sequence(void **state)
{
    (void)state;
    round_trip(true);
}

static void expect_refused(variant v, const char *what)
{
    gk_err e = {0};
    gk_scene *s = load(v, &e);
    if (s)
        gk_scene_free(s);
    assert_null(s);
    assert_int_equal(e.code, GK_EINPUT);
    if (strncmp(e.msg, "meshopt.gltf: ", 14) != 0 || !strstr(e.msg, what))
        print_error("message: %s\nwanted the file and '%s'\n", e.msg, what);
    assert_int_equal(strncmp(e.msg, "meshopt.gltf: ", 14), 0);
    assert_non_null(strstr(e.msg, what));
}

static void test_corrupt_stream(void **state)
{
    (void)state;
    expect_refused((variant){.corrupt = true}, "bufferView 0: EXT_meshopt_compression: the ATTRIBUTES data does not decode");
}

static void test_view_size(void **state)
{
    (void)state;
    expect_refused((variant){.pos_view_bytes = NV * 12 - 12},
                   "bufferView 0: EXT_meshopt_compression: the view's byteLength 3456 is not count 289 x byteStride 12");
}

static void test_view_stride(void **state)
{
    (void)state;
    expect_refused((variant){.pos_view_stride = 16},
                   "bufferView 0: EXT_meshopt_compression: the view's byteStride 16 is not the extension's 12");
}

static void test_unknown_mode(void **state)
{
    (void)state;
    expect_refused((variant){.index_mode = "STRIPS"}, "bufferView 3: EXT_meshopt_compression: mode 'STRIPS'");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_triangles),
        cmocka_unit_test(test_index_sequence),
        cmocka_unit_test(test_corrupt_stream),
        cmocka_unit_test(test_view_size),
        cmocka_unit_test(test_view_stride),
        cmocka_unit_test(test_unknown_mode),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
