// The JSON patches of gltf_patch.hpp, applied to a text glTF or to a GLB's JSON chunk (the GLB
// rebuilt around the new chunk, its BIN chunk copied as it was). Only files that name one of the
// two extensions are parsed here; the rest go to tinygltf untouched.
#include <cstring>

#include "gltf_internal.hpp"
#include "gltf_patch.hpp"

namespace gkgltf {

bool patch_for_tinygltf(const unsigned char *data, size_t size, std::vector<unsigned char> &patched)
{
    static const char kDraco[] = "KHR_draco_mesh_compression", kMeshopt[] = "EXT_meshopt_compression";
    if (!memmem(data, size, kDraco, sizeof kDraco - 1) && !memmem(data, size, kMeshopt, sizeof kMeshopt - 1))
        return false;
    // A GLB's JSON chunk (header 12 bytes, then chunk length, 'JSON', the text), else the file.
    bool glb = size >= 20 && memcmp(data, "glTF", 4) == 0;
    size_t json_at = 0, json_len = size;
    if (glb) {
        uint32_t len0;
        memcpy(&len0, data + 12, 4);
        if (memcmp(data + 16, "JSON", 4) != 0 || len0 > size - 20)
            return false; // tinygltf says what is wrong with it
        json_at = 20, json_len = len0;
    }
    nlohmann::json j = nlohmann::json::parse(data + json_at, data + json_at + json_len, nullptr, false);
    if (j.is_discarded() || !j.is_object())
        return false;
    bool changed = draco_placeholders(j);
    changed = meshopt_placeholders(j) || changed;
    if (!changed)
        return false;
    std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    if (!glb) {
        patched.assign(text.begin(), text.end());
        return true;
    }
    while (text.size() % 4)
        text.push_back(' ');
    size_t rest = size - json_at - json_len; // the BIN chunk and anything after it, as they were
    uint64_t total = 20 + text.size() + rest;
    if (total > UINT32_MAX)
        return false;
    patched.resize((size_t)total);
    memcpy(patched.data(), data, 12);
    uint32_t total32 = (uint32_t)total, len0 = (uint32_t)text.size();
    memcpy(patched.data() + 8, &total32, 4);
    memcpy(patched.data() + 12, &len0, 4);
    memcpy(patched.data() + 16, "JSON", 4);
    memcpy(patched.data() + 20, text.data(), text.size());
    memcpy(patched.data() + 20 + text.size(), data + json_at + json_len, rest);
    return true;
}

} // namespace gkgltf
