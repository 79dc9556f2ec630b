/* Test helpers (grid_mesh.h). */
#include "grid_mesh.h"

#include <math.h>
#include <stdlib.h>

void gk_test_grid(int grid, float *positions, float *normals, int nrm_stride, float *uvs, float u_scale,
                  float v_offset, uint32_t *indices)
{
    for (int j = 0; j <= grid; j++)
        for (int i = 0; i <= grid; i++) {
            int v = j * (grid + 1) + i;
            float x = 2.0f * (float)i / (float)grid, y = (float)j / (float)grid;
            float dzdx = 0.6f * cosf(3.0f * x) * cosf(2.0f * y), dzdy = -0.4f * sinf(3.0f * x) * sinf(2.0f * y);
            float l = sqrtf(dzdx * dzdx + dzdy * dzdy + 1.0f);
            positions[3 * v] = x, positions[3 * v + 1] = y, positions[3 * v + 2] = 0.2f * sinf(3.0f * x) * cosf(2.0f * y);
            float *n = &normals[nrm_stride * v];
            n[0] = -dzdx / l, n[1] = -dzdy / l, n[2] = 1.0f / l;
            if (nrm_stride > 3)
                n[3] = 1.0f;
            uvs[2 * v] = u_scale * (float)i / (float)grid, uvs[2 * v + 1] = v_offset + (float)j / (float)grid;
        }
    int t = 0;
    for (int j = 0; j < grid; j++)
        for (int i = 0; i < grid; i++) {
            uint32_t a = (uint32_t)(j * (grid + 1) + i), b = a + 1, c = a + (uint32_t)grid + 1, d = c + 1;
            uint32_t tri[6] = {a, b, d, a, d, c};
            for (int k = 0; k < 6; k++)
                indices[3 * t + k] = tri[k];
            t += 2;
        }
}

char *gk_test_base64(const unsigned char *p, size_t n)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *out = malloc(4 * ((n + 2) / 3) + 1), *o = out;
    if (!out)
        return NULL;
    for (size_t i = 0; i < n; i += 3) {
        uint32_t w = (uint32_t)p[i] << 16 | (i + 1 < n ? (uint32_t)p[i + 1] << 8 : 0) | (i + 2 < n ? p[i + 2] : 0);
        *o++ = tab[w >> 18 & 63];
        *o++ = tab[w >> 12 & 63];
        *o++ = i + 1 < n ? tab[w >> 6 & 63] : '=';
        *o++ = i + 2 < n ? tab[w & 63] : '=';
    }
    *o = '\0';
    return out;
}
