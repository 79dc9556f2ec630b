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

// One accessor, resolved to bytes: every byte it reads lies inside its bufferView and buffer.
struct View {
    const unsigned char *base = nullptr;
    size_t stride = 0, count = 0;
    int comps = 0, ctype = 0;
    bool normalized = false;
};

// gltf_accessor.cpp
bool resolve(Loader &L, const Model &m, int ai, const char *what, int want_type, std::initializer_list<int> ctypes,
             View *v);
float component(const View &v, size_t i, int c);
float *read_floats(Loader &L, const Model &m, int ai, const char *what, int type, bool allow_normalized,
                   size_t *count_out);

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

} // namespace gkgltf

#endif
