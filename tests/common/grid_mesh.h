/* Test helpers for the compressed-glTF tests: a displaced grid to encode, and base64 for data:
 * URIs. */
#ifndef GK_TEST_GRID_MESH_H
#define GK_TEST_GRID_MESH_H

#include <stddef.h>
#include <stdint.h>

/* A (grid + 1)^2-vertex, 2 grid^2-triangle height field z = 0.2 sin(3x) cos(2y) over [0, 2] x [0, 1]:
 * positions (3 floats a vertex), unit normals from its gradient (nrm_stride floats a vertex, a 4th
 * component set to 1), UVs (i / grid * u_scale, v_offset + j / grid), triangles (a, b, d), (a, d, c)
 * per cell, counter-clockwise seen from +z. */
void gk_test_grid(int grid, float *positions, float *normals, int nrm_stride, float *uvs, float u_scale,
                  float v_offset, uint32_t *indices);

/* malloc'ed base64 of n bytes (RFC 4648, padded). */
char *gk_test_base64(const unsigned char *p, size_t n);

#endif
