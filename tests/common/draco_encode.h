/* Test helper: a triangle mesh Draco-encoded with Debian's libdraco (the encoder half of the library
 * the loader decodes with), so the loader's KHR_draco_mesh_compression path is tested on streams
 * made here rather than on a committed blob nobody can regenerate. */
#ifndef GK_TEST_DRACO_ENCODE_H
#define GK_TEST_DRACO_ENCODE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The attribute ids the stream gives POSITION, NORMAL, TEXCOORD_0 and COLOR_0 (-1: not encoded). */
typedef struct gk_draco_ids {
    int position, normal, uv, color;
} gk_draco_ids;

/* Encodes n_vertices points (positions required; normals, uvs, 8-bit RGBA colors optional: NULL)
 * and n_triangles faces with the given quantization bits (positions; normals and uvs use 10 and
 * 12). Returns 0 and a malloc'ed stream in *out, or -1 (message on stderr). */
int gk_test_draco_encode(const float *positions, const float *normals, const float *uvs, const uint8_t *colors,
                         uint32_t n_vertices, const uint32_t *indices, uint32_t n_triangles, int position_bits,
                         unsigned char **out, size_t *out_size, gk_draco_ids *ids);

#ifdef __cplusplus
}
#endif

#endif
