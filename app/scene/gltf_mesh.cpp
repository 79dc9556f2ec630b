// Mesh primitives: attributes and indices into gk_mesh.
#include "gltf_internal.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace gkgltf {

bool read_primitive(Loader &L, const Model &m, int mi, int pi, const tinygltf::Primitive &p, int default_material,
                    gk_mesh *out)
{
    const std::string &mname = m.meshes[(size_t)mi].name;
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1)
        return L.fail("mesh %d ('%s') primitive %d: mode %d is not supported (only triangles, mode 4)", mi,
                      mname.c_str(), pi, p.mode);
    auto attr = [&](const char *key) {
        auto it = p.attributes.find(key);
        return it == p.attributes.end() ? -1 : it->second;
    };
    char what[96];
    int pos = attr("POSITION");
    if (pos < 0)
        return L.fail("mesh %d ('%s') primitive %d has no POSITION", mi, mname.c_str(), pi);
    snprintf(what, sizeof what, "mesh %d POSITION", mi);
    size_t nv = 0;
    out->positions = read_floats(L, m, pos, what, TINYGLTF_TYPE_VEC3, false, &nv);
    if (!out->positions)
        return false;
    if (nv > UINT32_MAX / 4)
        return L.fail("mesh %d: too many vertices (%zu)", mi, nv);
    out->n_vertices = (uint32_t)nv;
    int nrm = attr("NORMAL");
    if (nrm >= 0) {
        size_t nn = 0;
        snprintf(what, sizeof what, "mesh %d NORMAL", mi);
        out->normals = read_floats(L, m, nrm, what, TINYGLTF_TYPE_VEC3, false, &nn);
        if (!out->normals)
            return false;
        if (nn != nv)
            return L.fail("mesh %d ('%s'): NORMAL has %zu elements, POSITION %zu", mi, mname.c_str(), nn, nv);
    }
    int uv = attr("TEXCOORD_0");
    if (uv >= 0) {
        size_t nu = 0;
        snprintf(what, sizeof what, "mesh %d TEXCOORD_0", mi);
        out->uvs = read_floats(L, m, uv, what, TINYGLTF_TYPE_VEC2, true, &nu);
        if (!out->uvs)
            return false;
        if (nu != nv)
            return L.fail("mesh %d ('%s'): TEXCOORD_0 has %zu elements, POSITION %zu", mi, mname.c_str(), nu, nv);
    }
    size_t ni = nv;
    View iv;
    if (p.indices >= 0) {
        snprintf(what, sizeof what, "mesh %d indices", mi);
        if (!resolve(L, m, p.indices, what, TINYGLTF_TYPE_SCALAR,
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                     &iv))
            return false;
        ni = iv.count;
    }
    if (ni % 3 != 0)
        return L.fail("mesh %d ('%s') primitive %d: %zu indices is not a whole number of triangles", mi,
                      mname.c_str(), pi, ni);
    if (ni / 3 > UINT32_MAX / 4)
        return L.fail("mesh %d: too many triangles", mi);
    out->n_triangles = (uint32_t)(ni / 3);
    out->indices = (uint32_t *)malloc((ni ? ni : 1) * sizeof(uint32_t));
    if (!out->indices)
        return L.fail("mesh %d: out of memory", mi);
    for (size_t i = 0; i < ni; i++) {
        if (p.indices < 0) {
            out->indices[i] = (uint32_t)i;
            continue;
        }
        const unsigned char *q = iv.base + i * iv.stride;
        if (iv.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            out->indices[i] = q[0];
        } else if (iv.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            uint16_t s;
            memcpy(&s, q, 2);
            out->indices[i] = s;
        } else {
            memcpy(&out->indices[i], q, 4);
        }
    }
    if (p.material >= default_material)
        return L.fail("mesh %d ('%s') primitive %d: material %d does not exist", mi, mname.c_str(), pi, p.material);
    out->material = p.material < 0 ? default_material : p.material;
    return true;
}

// KHR_materials_specular (brdf_spec.md): specularFactor (in [0, 1], default 1), specularColorFactor
} // namespace gkgltf
