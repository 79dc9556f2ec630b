// Internal to the glTF loader (gltf_*.cpp): the tinygltf model is translated into the plain C
// structs of scene.h by a few files, one per part of the document (accessors, meshes, materials,
// nodes); this header is what they share. Every message goes through Loader::fail, which names
// the file, so each error reads "path: what is wrong".
#ifndef GK_GLTF_INTERNAL_HPP
#define GK_GLTF_INTERNAL_HPP

#include <tiny_gltf.h>

#include <cstdarg>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

extern "C" {
#include "base/log.h"
#include "scene_internal.h"
}

namespace gkgltf {

using tinygltf::Model;
using tinygltf::Value;

struct Loader {
    const char *path;
    gk_err *e;
    bool failed = false;
    bool quantization = false; // the file uses KHR_mesh_quantization (integer positions, normals, UVs)
    gk_scene_gltf_use use{};   // counted while reading, copied into the scene

    bool fail(const char *fmt, ...) __attribute__((format(printf, 2, 3)))
    {
        char buf[900];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(buf, sizeof buf, fmt, ap);
        va_end(ap);
        if (!failed)
            gk_fail(e, GK_EINPUT, "%s: %s", path, buf);
        failed = true;
        return false;
    }
};

inline const Value *gikiosk_extras(const Value &extras)
{
    if (!extras.IsObject() || !extras.Has("gikiosk"))
        return nullptr;
    const Value &g = extras.Get("gikiosk");
    return g.IsObject() ? &g : nullptr;
}

inline const Value *member(const Value *obj, const char *key)
{
    if (!obj || !obj->IsObject() || !obj->Has(key))
        return nullptr;
    return &obj->Get(key);
}

bool finite_all(const std::vector<double> &v);

inline void copy_name(char *dst, size_t cap, const std::string &src)
{
    snprintf(dst, cap, "%s", src.c_str());
}

// One accessor, resolved to bytes: every byte it reads lies inside its bufferView and buffer, or
// inside `dense`, the accessor's own copy when it is sparse (§3.6.2.3: the base data, or zeros,
// with the sparse values substituted). Not copyable: base may point into dense.
struct View {
    const unsigned char *base = nullptr;
    size_t stride = 0, count = 0;
    int comps = 0, ctype = 0;
    bool normalized = false;
    std::vector<unsigned char> dense;
    View() = default;
    View(const View &) = delete;
    View &operator=(const View &) = delete;
};

// Which component types read_floats accepts. Float always; the integer kinds are those glTF 2.0
// allows for the attribute (§3.7.2.1), widened by KHR_mesh_quantization when the file uses it.
enum class Ints {
    none,            // float only (positions and normals without quantization, animation times)
    normalized,      // normalized UNSIGNED_BYTE/SHORT and BYTE/SHORT (texture coordinates, rotations)
    normalized_or_not // any 8/16-bit integer, normalized or not (KHR_mesh_quantization positions, UVs)
};

// gltf_accessor.cpp
bool resolve(Loader &L, const Model &m, int ai, const char *what, int want_type, std::initializer_list<int> ctypes,
             View *v);
float component(const View &v, size_t i, int c);
float *read_floats(Loader &L, const Model &m, int ai, const char *what, int type, Ints ints, size_t *count_out);

// An index of UNSIGNED_BYTE, _SHORT or _INT at q.
uint32_t read_index(const unsigned char *q, int ctype);

// gltf_draco.cpp: KHR_draco_mesh_compression primitives decoded into new buffers, their accessors
// pointed at them (before the meshes are read).
bool decode_draco(Loader &L, Model &m);
// gltf_meshopt.cpp: EXT_meshopt_compression bufferViews decoded into new buffers (before anything
// reads a bufferView).
bool decode_meshopt(Loader &L, Model &m);
// gltf_patch.cpp: what Debian's tinygltf would refuse in a file using the two compression
// extensions, patched in its JSON (text or a GLB's JSON chunk) before tinygltf parses it
// (gltf_patch.hpp says what). True, with the patched file in `patched`, when something was.
bool patch_for_tinygltf(const unsigned char *data, size_t size, std::vector<unsigned char> &patched);

// gltf_mesh.cpp
bool read_primitive(Loader &L, const Model &m, int mi, int pi, const tinygltf::Primitive &p, int default_material,
                    gk_mesh *out);

// gltf_material.cpp
bool read_materials(Loader &L, const Model &m, gk_scene *s, std::vector<int> &tex_usage);
bool read_textures(Loader &L, const Model &m, gk_scene *s);

// gltf_nodes.cpp
bool read_lights(Loader &L, const Model &m, gk_scene *s);
bool read_cameras(Loader &L, const Model &m, gk_scene *s);
bool read_nodes(Loader &L, const Model &m, gk_scene *s, const std::vector<int> &mesh_first,
                const std::vector<int> &mesh_count);
bool read_animations(Loader &L, const Model &m, gk_scene *s);
void read_scene_extras(const Model &m, gk_scene *s);
// The scene's "gikiosk" extras (the default scene's, else the document's), or nullptr.
const Value *scene_gikiosk_extras(const Model &m);
// The scene medium, extras "gikiosk": {"medium": {...}} (scene.h, gk_medium).
bool read_medium(Loader &L, const Value *g, gk_scene *s);
// The scene environment, "extras": {"gikiosk": {"environment": {...}}} (gltf_environment.cpp).
bool read_environment(Loader &L, const Value *g, gk_scene *s);

} // namespace gkgltf

#endif
