// Internal to the glTF loader: the JSON patches applied before tinygltf parses a file that uses a
// compression extension. Debian's tinygltf is built without either extension and refuses, for
// files valid under them:
//  - KHR_draco_mesh_compression: an indices accessor without a bufferView (what the extension
//    writes); it is given the Draco stream's bufferView as a placeholder, replaced by decode_draco.
//  - EXT_meshopt_compression: a fallback buffer without a uri (what gltfpack writes: its bytes
//    exist only compressed); it becomes a 3-byte data: URI, never read: decode_meshopt points every
//    bufferView of it at decoded bytes of its own.
#ifndef GK_GLTF_PATCH_HPP
#define GK_GLTF_PATCH_HPP

#include <nlohmann/json.hpp>

namespace gkgltf {

// Each returns true when it changed the document.
bool draco_placeholders(nlohmann::json &j);  // gltf_draco.cpp
bool meshopt_placeholders(nlohmann::json &j); // gltf_meshopt.cpp

} // namespace gkgltf

#endif
