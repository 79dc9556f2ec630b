// Test helper (draco_encode.h): builds a draco::Mesh point by point (identity mapping, so point i
// is vertex i) and encodes it with the library's default edgebreaker settings.
#include "draco_encode.h"

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

int add(draco::Mesh &mesh, draco::GeometryAttribute::Type type, int comps, draco::DataType dt, bool normalized,
        int bytes_per_comp, const void *data, uint32_t n)
{
    draco::GeometryAttribute ga;
    ga.Init(type, nullptr, (int8_t)comps, dt, normalized, (int64_t)comps * bytes_per_comp, 0);
    int id = mesh.AddAttribute(ga, true, n);
    draco::PointAttribute *pa = mesh.attribute(id);
    for (uint32_t i = 0; i < n; i++)
        pa->SetAttributeValue(draco::AttributeValueIndex(i), (const uint8_t *)data + (size_t)i * comps * bytes_per_comp);
    return (int)pa->unique_id();
}

} // namespace

extern "C" int gk_test_draco_encode(const float *positions, const float *normals, const float *uvs,
                                    const uint8_t *colors, uint32_t n_vertices, const uint32_t *indices,
                                    uint32_t n_triangles, int position_bits, unsigned char **out, size_t *out_size,
                                    gk_draco_ids *ids)
{
    draco::Mesh mesh;
    mesh.set_num_points(n_vertices);
    for (uint32_t f = 0; f < n_triangles; f++) {
        draco::Mesh::Face face;
        for (int k = 0; k < 3; k++)
            face[k] = draco::PointIndex(indices[3 * f + k]);
        mesh.AddFace(face);
    }
    *ids = gk_draco_ids{-1, -1, -1, -1};
    ids->position = add(mesh, draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32, false, 4, positions, n_vertices);
    if (normals)
        ids->normal = add(mesh, draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32, false, 4, normals, n_vertices);
    if (uvs)
        ids->uv = add(mesh, draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32, false, 4, uvs, n_vertices);
    if (colors)
        ids->color = add(mesh, draco::GeometryAttribute::COLOR, 4, draco::DT_UINT8, true, 1, colors, n_vertices);
    draco::Encoder enc;
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, position_bits);
    enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    draco::EncoderBuffer buf;
    draco::Status st = enc.EncodeMeshToBuffer(mesh, &buf);
    if (!st.ok()) {
        fprintf(stderr, "draco encode: %s\n", st.error_msg());
        return -1;
    }
    *out_size = buf.size();
    *out = (unsigned char *)malloc(buf.size() ? buf.size() : 1);
    if (!*out)
        return -1;
    memcpy(*out, buf.data(), buf.size());
    return 0;
}
