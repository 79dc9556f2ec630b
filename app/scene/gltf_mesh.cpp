// Mesh primitives: attributes and indices into gk_mesh.
#include "gltf_internal.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace gkgltf {

namespace {

// The vertex sequence of a primitive (its indices, or 0..n-1 without) as triangle-list indices
// (§3.7.2.1): TRIANGLES as they are, TRIANGLE_STRIP with every odd triangle's first two vertices
// swapped so all keep the strip's winding, TRIANGLE_FAN around the first vertex. Returns the
// number of indices written to out (room for 3 * n).
size_t to_triangle_list(int mode, const uint32_t *seq, size_t n, uint32_t *out)
{
    size_t w = 0;
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < n; i++) {
            bool odd = i & 1;
            out[w++] = seq[odd ? i + 1 : i];
            out[w++] = seq[odd ? i : i + 1];
            out[w++] = seq[i + 2];
        }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t i = 1; i + 1 < n; i++) {
            out[w++] = seq[0];
            out[w++] = seq[i];
            out[w++] = seq[i + 1];
        }
    } else {
        memcpy(out, seq, n * sizeof *seq);
        w = n;
    }
    return w;
}

const char *mode_name(int mode)
{
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    default: return "unknown";
    }
}

} // namespace

bool read_primitive(Loader &L, const Model &m, int mi, int pi, const tinygltf::Primitive &p, int default_material,
                    gk_mesh *out)
{
    const std::string &mname = m.meshes[(size_t)mi].name;
    int mode = p.mode == -1 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (p.material >= default_material)
        return L.fail("mesh %d ('%s') primitive %d: material %d does not exist", mi, mname.c_str(), pi, p.material);
    out->material = p.material < 0 ? default_material : p.material;
    bool triangles = mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
                     mode == TINYGLTF_MODE_TRIANGLE_FAN;
    if (!triangles) {
        if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_LINE_STRIP)
            return L.fail("mesh %d ('%s') primitive %d: mode %d is not a glTF primitive mode", mi, mname.c_str(), pi,
                          p.mode);
        // Points and lines have no area to light or to shade; the rest of the file still shows.
        gk_log("%s: mesh %d ('%s') primitive %d: mode %s is not drawn (triangles only)", L.path, mi, mname.c_str(),
               pi, mode_name(mode));
        L.use.not_drawn++;
        out->positions = (float *)calloc(3, sizeof(float));
        out->indices = (uint32_t *)calloc(3, sizeof(uint32_t));
        return (out->positions && out->indices) || L.fail("mesh %d: out of memory", mi);
    }
    auto attr = [&](const char *key) {
        auto it = p.attributes.find(key);
        return it == p.attributes.end() ? -1 : it->second;
    };
    // KHR_mesh_quantization widens each attribute's component types (its table): positions and
    // UVs any 8/16-bit integer, normals normalized BYTE/SHORT.
    Ints pos_ints = L.quantization ? Ints::normalized_or_not : Ints::none;
    Ints nrm_ints = L.quantization ? Ints::normalized : Ints::none;
    Ints uv_ints = L.quantization ? Ints::normalized_or_not : Ints::normalized;
    char what[96];
    int pos = attr("POSITION");
    if (pos < 0)
        return L.fail("mesh %d ('%s') primitive %d has no POSITION", mi, mname.c_str(), pi);
    snprintf(what, sizeof what, "mesh %d POSITION", mi);
    size_t nv = 0;
    out->positions = read_floats(L, m, pos, what, TINYGLTF_TYPE_VEC3, pos_ints, &nv);
    if (!out->positions)
        return false;
    if (nv > UINT32_MAX / 4)
        return L.fail("mesh %d: too many vertices (%zu)", mi, nv);
    out->n_vertices = (uint32_t)nv;
    int nrm = attr("NORMAL");
    if (nrm >= 0) {
        size_t nn = 0;
        snprintf(what, sizeof what, "mesh %d NORMAL", mi);
        out->normals = read_floats(L, m, nrm, what, TINYGLTF_TYPE_VEC3, nrm_ints, &nn);
        if (!out->normals)
            return false;
        if (nn != nv)
            return L.fail("mesh %d ('%s'): NORMAL has %zu elements, POSITION %zu", mi, mname.c_str(), nn, nv);
    }
    int uv = attr("TEXCOORD_0");
    if (uv >= 0) {
        size_t nu = 0;
        snprintf(what, sizeof what, "mesh %d TEXCOORD_0", mi);
        out->uvs = read_floats(L, m, uv, what, TINYGLTF_TYPE_VEC2, uv_ints, &nu);
        if (!out->uvs)
            return false;
        if (nu != nv)
            return L.fail("mesh %d ('%s'): TEXCOORD_0 has %zu elements, POSITION %zu", mi, mname.c_str(), nu, nv);
    }
    int uv1 = attr("TEXCOORD_1");
    if (uv1 >= 0) { // the second UV set, for texture slots whose texCoord is 1
        size_t nu = 0;
        snprintf(what, sizeof what, "mesh %d TEXCOORD_1", mi);
        out->uvs1 = read_floats(L, m, uv1, what, TINYGLTF_TYPE_VEC2, uv_ints, &nu);
        if (!out->uvs1)
            return false;
        if (nu != nv)
            return L.fail("mesh %d ('%s'): TEXCOORD_1 has %zu elements, POSITION %zu", mi, mname.c_str(), nu, nv);
    }
    int col = attr("COLOR_0");
    if (col >= 0) {
        // Vertex colours (§3.7.2.1): VEC3 or VEC4, float or normalized unsigned byte/short,
        // linear; multiplied into the base colour. Kept as RGBA, A = 1 for RGB.
        if ((size_t)col >= m.accessors.size())
            return L.fail("mesh %d ('%s'): COLOR_0 accessor %d does not exist", mi, mname.c_str(), col);
        int type = m.accessors[(size_t)col].type == TINYGLTF_TYPE_VEC3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4;
        int comps = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
        size_t nc = 0;
        snprintf(what, sizeof what, "mesh %d COLOR_0", mi);
        float *c = read_floats(L, m, col, what, type, Ints::normalized, &nc);
        if (!c)
            return false;
        out->colors = (float *)malloc((nv ? nv : 1) * 4 * sizeof(float));
        if (!out->colors) {
            free(c);
            return L.fail("mesh %d: out of memory", mi);
        }
        for (size_t v = 0; v < nv && nc == nv; v++)
            for (int k = 0; k < 4; k++)
                out->colors[4 * v + (size_t)k] = k < comps ? c[(size_t)comps * v + (size_t)k] : 1.0f;
        free(c);
        if (nc != nv)
            return L.fail("mesh %d ('%s'): COLOR_0 has %zu elements, POSITION %zu", mi, mname.c_str(), nc, nv);
    }
    int tan = attr("TANGENT");
    if (tan >= 0) {
        size_t nt = 0;
        snprintf(what, sizeof what, "mesh %d TANGENT", mi);
        out->tangents = read_floats(L, m, tan, what, TINYGLTF_TYPE_VEC4, nrm_ints, &nt);
        if (!out->tangents)
            return false;
        if (nt != nv)
            return L.fail("mesh %d ('%s'): TANGENT has %zu elements, POSITION %zu", mi, mname.c_str(), nt, nv);
    }
    size_t ns = nv;
    View iv;
    if (p.indices >= 0) {
        snprintf(what, sizeof what, "mesh %d indices", mi);
        if (!resolve(L, m, p.indices, what, TINYGLTF_TYPE_SCALAR,
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                     &iv))
            return false;
        ns = iv.count;
    }
    if (mode == TINYGLTF_MODE_TRIANGLES && ns % 3 != 0)
        return L.fail("mesh %d ('%s') primitive %d: %zu indices is not a whole number of triangles", mi,
                      mname.c_str(), pi, ns);
    if (ns > UINT32_MAX / 12)
        return L.fail("mesh %d: too many triangles", mi);
    if (mode != TINYGLTF_MODE_TRIANGLES)
        L.use.strips_fans++;
    std::vector<uint32_t> seq(ns + 1);
    for (size_t i = 0; i < ns; i++)
        seq[i] = p.indices < 0 ? (uint32_t)i : read_index(iv.base + i * iv.stride, iv.ctype);
    out->indices = (uint32_t *)malloc((3 * ns + 3) * sizeof(uint32_t));
    if (!out->indices)
        return L.fail("mesh %d: out of memory", mi);
    out->n_triangles = (uint32_t)(to_triangle_list(mode, seq.data(), ns, out->indices) / 3);
    return true;
}

} // namespace gkgltf
