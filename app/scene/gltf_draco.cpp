// KHR_draco_mesh_compression: a primitive whose geometry is a Draco bit stream in a bufferView.
// Decoded with Debian's libdraco before the meshes are read: each attribute the extension names
// (and the triangle indices) is written into a buffer of its own and the primitive's accessor is
// pointed at it, so read_primitive and every check after it read Draco meshes like any others.
// The accessors keep what the file declares (type, component type, normalized, count): the
// extension's spec says the decoded data must match them, so a mismatch is refused, not guessed.
#include <draco/compression/decode.h>

#include <map>
#include <memory>

#include "gltf_internal.hpp"
#include "gltf_patch.hpp"

namespace gkgltf {

namespace {

const char kDraco[] = "KHR_draco_mesh_compression";

// A Draco stream is a few bytes a triangle; more than this many points or faces is a bomb, not a
// mesh for a kiosk board (the loader's own file cap is 256 MiB).
const uint32_t kMaxDracoPoints = 1u << 24, kMaxDracoFaces = 1u << 25;

// One new buffer and tight bufferView holding `bytes`; returns the view's index.
int add_view(Model &m, std::vector<unsigned char> &&bytes)
{
    tinygltf::Buffer b;
    b.data = std::move(bytes);
    m.buffers.push_back(std::move(b));
    tinygltf::BufferView v;
    v.buffer = (int)m.buffers.size() - 1;
    v.byteOffset = 0;
    v.byteLength = m.buffers.back().data.size();
    v.byteStride = 0;
    m.bufferViews.push_back(std::move(v));
    return (int)m.bufferViews.size() - 1;
}

template <typename T>
bool convert_points(const draco::Mesh &mesh, const draco::PointAttribute &a, int comps, unsigned char *dst)
{
    T *out = (T *)dst;
    for (draco::PointIndex i(0); i < mesh.num_points(); ++i, out += comps)
        if (!a.ConvertValue<T>(a.mapped_index(i), (int8_t)comps, out))
            return false;
    return true;
}

// The decoded values of one attribute in the accessor's own component type (normalization stays
// the accessor's to apply, as for uncompressed data).
bool convert_attribute(const draco::Mesh &mesh, const draco::PointAttribute &a, int ctype, int comps,
                       unsigned char *dst)
{
    switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return convert_points<float>(mesh, a, comps, dst);
    case TINYGLTF_COMPONENT_TYPE_BYTE: return convert_points<int8_t>(mesh, a, comps, dst);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return convert_points<uint8_t>(mesh, a, comps, dst);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return convert_points<int16_t>(mesh, a, comps, dst);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return convert_points<uint16_t>(mesh, a, comps, dst);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return convert_points<uint32_t>(mesh, a, comps, dst);
    default: return false;
    }
}

// done: accessor -> the bufferView of the stream it was decoded from
bool decode_primitive(Loader &L, Model &m, int mi, int pi, std::map<int, int> &done)
{
    tinygltf::Primitive &p = m.meshes[(size_t)mi].primitives[(size_t)pi];
    const Value &x = p.extensions.find(kDraco)->second;
    const std::string &mname = m.meshes[(size_t)mi].name;
    char at[160];
    snprintf(at, sizeof at, "mesh %d ('%s') primitive %d: %s", mi, mname.c_str(), pi, kDraco);
    if (!x.IsObject() || !x.Has("bufferView") || !x.Get("bufferView").IsInt() || !x.Has("attributes") ||
        !x.Get("attributes").IsObject())
        return L.fail("%s: needs an integer \"bufferView\" and an \"attributes\" object", at);
    int mode = p.mode == -1 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP)
        return L.fail("%s: mode %d (the extension compresses triangles only)", at, mode);
    int vi = x.Get("bufferView").GetNumberAsInt();
    if (vi < 0 || (size_t)vi >= m.bufferViews.size())
        return L.fail("%s: bufferView %d does not exist", at, vi);
    const tinygltf::BufferView &view = m.bufferViews[(size_t)vi];
    if (view.buffer < 0 || (size_t)view.buffer >= m.buffers.size())
        return L.fail("%s: bufferView %d's buffer %d does not exist", at, vi, view.buffer);
    const std::vector<unsigned char> &bytes = m.buffers[(size_t)view.buffer].data;
    if (view.byteOffset > bytes.size() || view.byteLength > bytes.size() - view.byteOffset)
        return L.fail("%s: bufferView %d (%zu bytes at %zu) lies outside its buffer (%zu bytes)", at, vi,
                      view.byteLength, view.byteOffset, bytes.size());

    draco::DecoderBuffer in;
    in.Init((const char *)bytes.data() + view.byteOffset, view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok())
        return L.fail("%s: the Draco stream does not decode (%s)", at, decoded.status().error_msg());
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh || mesh->num_points() > kMaxDracoPoints || mesh->num_faces() > kMaxDracoFaces)
        return L.fail("%s: %u points, %u faces: more than a scene may hold", at, mesh ? mesh->num_points() : 0u,
                      mesh ? mesh->num_faces() : 0u);
    size_t n_points = mesh->num_points(), n_index = 3 * (size_t)mesh->num_faces();

    // Every accessor of the primitive is replaced; one shared with a primitive decoded from
    // another stream could only hold one of them.
    auto claim = [&](int ai, const char *what) {
        if (ai < 0 || (size_t)ai >= m.accessors.size())
            return L.fail("%s: the %s accessor %d does not exist", at, what, ai);
        auto it = done.find(ai);
        if (it != done.end() && it->second != vi)
            return L.fail("%s: accessor %d (%s) is decoded from two Draco streams", at, ai, what);
        return true;
    };

    // the triangles (the decoder always returns a triangle list; mode becomes TRIANGLES)
    if (p.indices < 0)
        return L.fail("%s: the primitive has no indices accessor (the extension requires one)", at);
    if (!claim(p.indices, "indices"))
        return false;
    tinygltf::Accessor &ia = m.accessors[(size_t)p.indices];
    if (ia.count != n_index)
        return L.fail("%s: indices accessor %d has count %zu, the stream %zu indices", at, p.indices, ia.count,
                      n_index);
    std::vector<unsigned char> idx(n_index * sizeof(uint32_t));
    uint32_t *q = (uint32_t *)idx.data();
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
        for (int k = 0; k < 3; k++)
            *q++ = mesh->face(f)[k].value();
    ia.bufferView = add_view(m, std::move(idx));
    ia.byteOffset = 0;
    ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    ia.sparse.isSparse = false;
    done[p.indices] = vi;
    p.mode = TINYGLTF_MODE_TRIANGLES;

    const Value &attrs = x.Get("attributes");
    for (const std::string &key : attrs.Keys()) {
        const Value &id = attrs.Get(key);
        auto pa = p.attributes.find(key);
        if (pa == p.attributes.end())
            return L.fail("%s: attribute %s is compressed but the primitive has no accessor for it", at, key.c_str());
        if (!id.IsInt())
            return L.fail("%s: attribute %s's Draco id is not an integer", at, key.c_str());
        if (!claim(pa->second, key.c_str()))
            return false;
        const draco::PointAttribute *a = mesh->GetAttributeByUniqueId((uint32_t)id.GetNumberAsInt());
        if (!a)
            return L.fail("%s: attribute %s: the stream has no attribute with id %d", at, key.c_str(),
                          id.GetNumberAsInt());
        tinygltf::Accessor &acc = m.accessors[(size_t)pa->second];
        int comps = tinygltf::GetNumComponentsInType((uint32_t)acc.type);
        int csize = tinygltf::GetComponentSizeInBytes((uint32_t)acc.componentType);
        if (comps <= 0 || csize <= 0 || comps > 4)
            return L.fail("%s: attribute %s: accessor %d has an unusable type", at, key.c_str(), pa->second);
        if (a->num_components() != comps)
            return L.fail("%s: attribute %s has %d components in the stream, its accessor %d", at, key.c_str(),
                          (int)a->num_components(), comps);
        if (acc.count != n_points)
            return L.fail("%s: attribute %s: accessor %d has count %zu, the stream %zu points", at, key.c_str(),
                          pa->second, acc.count, n_points);
        std::vector<unsigned char> data(n_points * (size_t)comps * (size_t)csize);
        if (!convert_attribute(*mesh, *a, acc.componentType, comps, data.data()))
            return L.fail("%s: attribute %s cannot be converted to its accessor's component type", at, key.c_str());
        acc.bufferView = add_view(m, std::move(data));
        acc.byteOffset = 0;
        acc.sparse.isSparse = false;
        done[pa->second] = vi;
    }
    L.use.draco_primitives++;
    return true;
}

} // namespace

bool draco_placeholders(nlohmann::json &j)
{
    if (!j.contains("meshes") || !j["meshes"].is_array() || !j.contains("accessors") || !j["accessors"].is_array())
        return false;
    nlohmann::json &acc = j["accessors"];
    bool changed = false;
    for (nlohmann::json &mesh : j["meshes"]) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
            continue;
        for (nlohmann::json &p : mesh["primitives"]) {
            if (!p.is_object() || !p.contains("indices") || !p["indices"].is_number_unsigned() ||
                !p.contains("extensions") || !p["extensions"].is_object() || !p["extensions"].contains(kDraco))
                continue;
            const nlohmann::json &x = p["extensions"][kDraco];
            size_t ai = p["indices"].get<size_t>();
            if (!x.is_object() || !x.contains("bufferView") || !x["bufferView"].is_number_unsigned() ||
                ai >= acc.size() || !acc[ai].is_object() || acc[ai].contains("bufferView"))
                continue;
            acc[ai]["bufferView"] = x["bufferView"];
            changed = true;
        }
    }
    return changed;
}

bool decode_draco(Loader &L, Model &m)
{
    std::map<int, int> done;
    for (size_t mi = 0; mi < m.meshes.size(); mi++)
        for (size_t pi = 0; pi < m.meshes[mi].primitives.size(); pi++)
            if (m.meshes[mi].primitives[pi].extensions.count(kDraco) &&
                !decode_primitive(L, m, (int)mi, (int)pi, done))
                return false;
    return true;
}

} // namespace gkgltf
