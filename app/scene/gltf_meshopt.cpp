// EXT_meshopt_compression: a bufferView whose bytes are stored compressed by meshoptimizer's codecs
// (vertex attributes, triangle indices, index sequences, with optional octahedral, quaternion or
// exponential filters). Decoded with Debian's libmeshoptimizer before anything reads a bufferView:
// each such view gets a buffer of its own holding the decoded bytes, so accessors, sparse data and
// animation samplers read it like any other view. The codec is lossless (the filters are the
// encoder's quantization, undone here as the spec defines).
#include <meshoptimizer.h>

#include "gltf_internal.hpp"
#include "gltf_patch.hpp"

namespace gkgltf {

namespace {

const char kMeshopt[] = "EXT_meshopt_compression";

// A decoded view larger than this is a bomb, not a scene for a kiosk board (the loader's own file
// cap is 256 MiB as well).
const size_t kMaxDecodedBytes = (size_t)1 << 28;

// A non-negative integer member; absent, the default (dflt < 0: the member is required).
bool get_int(const Value &x, const char *key, long long dflt, long long *out)
{
    if (!x.Has(key)) {
        *out = dflt;
        return dflt >= 0;
    }
    const Value &v = x.Get(key);
    if (!v.IsNumber())
        return false;
    double d = v.GetNumberAsDouble();
    if (!(d >= 0.0 && d <= 9.0e15) || d != (double)(long long)d)
        return false;
    *out = (long long)d;
    return true;
}

// A string member; absent, the default (nullptr: the member is required).
bool get_string(const Value &x, const char *key, const char *dflt, std::string *out)
{
    if (!x.Has(key)) {
        *out = dflt ? dflt : "";
        return dflt != nullptr;
    }
    if (!x.Get(key).IsString())
        return false;
    *out = x.Get(key).Get<std::string>();
    return true;
}

bool decode_view(Loader &L, Model &m, int vi)
{
    tinygltf::BufferView &view = m.bufferViews[(size_t)vi];
    const Value &x = view.extensions.find(kMeshopt)->second;
    char at[96];
    snprintf(at, sizeof at, "bufferView %d: %s", vi, kMeshopt);
    long long buffer, offset, length, stride, count;
    std::string mode, filter;
    if (!x.IsObject() || !get_int(x, "buffer", -1, &buffer) || !get_int(x, "byteOffset", 0, &offset) ||
        !get_int(x, "byteLength", -1, &length) || !get_int(x, "byteStride", -1, &stride) ||
        !get_int(x, "count", -1, &count) || !get_string(x, "mode", nullptr, &mode) ||
        !get_string(x, "filter", "NONE", &filter))
        return L.fail("%s: needs non-negative integers buffer, byteLength, byteStride, count (byteOffset "
                      "optional) and the strings mode (filter optional)",
                      at);
    if ((size_t)buffer >= m.buffers.size())
        return L.fail("%s: buffer %lld does not exist", at, buffer);
    const std::vector<unsigned char> &src = m.buffers[(size_t)buffer].data;
    if ((size_t)offset > src.size() || (size_t)length > src.size() - (size_t)offset)
        return L.fail("%s: %lld bytes at %lld lie outside buffer %lld (%zu bytes)", at, length, offset, buffer,
                      src.size());
    if (stride < 1 || stride > 256 || (unsigned long long)count > kMaxDecodedBytes / (unsigned long long)stride)
        return L.fail("%s: byteStride %lld and count %lld are not a view gikiosk decodes (stride 1..256, at most "
                      "%zu bytes)",
                      at, stride, count, kMaxDecodedBytes);
    size_t bytes = (size_t)count * (size_t)stride;
    if (view.byteLength != bytes)
        return L.fail("%s: the view's byteLength %zu is not count %lld x byteStride %lld", at, view.byteLength,
                      count, stride);
    std::vector<unsigned char> out(bytes ? bytes : 1);
    const unsigned char *in = src.data() + offset;
    int rc;
    if (mode == "ATTRIBUTES") {
        if (stride % 4)
            return L.fail("%s: ATTRIBUTES need a byteStride that is a multiple of 4 (%lld)", at, stride);
        // the decoded vertices lie byteStride apart: a view that says otherwise would be read askew
        if (view.byteStride != 0 && view.byteStride != (size_t)stride)
            return L.fail("%s: the view's byteStride %zu is not the extension's %lld", at, view.byteStride, stride);
        view.byteStride = (size_t)stride;
        rc = meshopt_decodeVertexBuffer(out.data(), (size_t)count, (size_t)stride, in, (size_t)length);
        if (rc == 0 && filter == "OCTAHEDRAL") {
            if (stride != 4 && stride != 8)
                return L.fail("%s: filter OCTAHEDRAL needs byteStride 4 or 8 (%lld)", at, stride);
            meshopt_decodeFilterOct(out.data(), (size_t)count, (size_t)stride);
        } else if (rc == 0 && filter == "QUATERNION") {
            if (stride != 8)
                return L.fail("%s: filter QUATERNION needs byteStride 8 (%lld)", at, stride);
            meshopt_decodeFilterQuat(out.data(), (size_t)count, (size_t)stride);
        } else if (rc == 0 && filter == "EXPONENTIAL") {
            meshopt_decodeFilterExp(out.data(), (size_t)count, (size_t)stride);
        } else if (filter != "NONE") {
            return L.fail("%s: filter '%s' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL", at, filter.c_str());
        }
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
        if (stride != 2 && stride != 4)
            return L.fail("%s: %s need byteStride 2 or 4 (%lld)", at, mode.c_str(), stride);
        if (filter != "NONE")
            return L.fail("%s: filter '%s' applies to ATTRIBUTES only", at, filter.c_str());
        if (mode == "TRIANGLES" && count % 3)
            return L.fail("%s: TRIANGLES with count %lld, not a whole number of triangles", at, count);
        rc = mode == "TRIANGLES"
                 ? meshopt_decodeIndexBuffer(out.data(), (size_t)count, (size_t)stride, in, (size_t)length)
                 : meshopt_decodeIndexSequence(out.data(), (size_t)count, (size_t)stride, in, (size_t)length);
    } else {
        return L.fail("%s: mode '%s' is not ATTRIBUTES, TRIANGLES or INDICES", at, mode.c_str());
    }
    if (rc != 0)
        return L.fail("%s: the %s data does not decode (meshoptimizer error %d)", at, mode.c_str(), rc);
    out.resize(bytes);
    tinygltf::Buffer b;
    b.data = std::move(out);
    m.buffers.push_back(std::move(b));
    view.buffer = (int)m.buffers.size() - 1;
    view.byteOffset = 0;
    L.use.meshopt_views++;
    return true;
}

} // namespace

bool meshopt_placeholders(nlohmann::json &j)
{
    if (!j.contains("buffers") || !j["buffers"].is_array())
        return false;
    bool changed = false;
    for (nlohmann::json &b : j["buffers"]) {
        if (!b.is_object() || b.contains("uri") || !b.contains("extensions") || !b["extensions"].is_object() ||
            !b["extensions"].contains(kMeshopt))
            continue;
        const nlohmann::json &x = b["extensions"][kMeshopt];
        if (!x.is_object() || !x.contains("fallback") || x["fallback"] != true)
            continue;
        b["uri"] = "data:application/octet-stream;base64,AAAA";
        b["byteLength"] = 3;
        changed = true;
    }
    return changed;
}

bool decode_meshopt(Loader &L, Model &m)
{
    size_t n = m.bufferViews.size(); // decode_view adds buffers, never views
    for (size_t vi = 0; vi < n; vi++)
        if (m.bufferViews[vi].extensions.count(kMeshopt) && !decode_view(L, m, (int)vi))
            return false;
    return true;
}

} // namespace gkgltf
