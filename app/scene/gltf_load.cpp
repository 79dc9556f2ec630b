// The tinygltf shim behind gk_scene_load (scene.h): parses glTF/GLB with Debian's shared
// libtinygltf and translates it into the plain C structs, checking only what it must read to do so
// safely: every index into a glTF array, every accessor's byte range inside its bufferView and
// buffer, component types, primitive modes. Numeric validation, normals, textures, features and
// bounds are done by the C side (gk_scene_finish). Every message starts with the file's path.
#include <tiny_gltf.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include "base/confine.h"
#include "base/log.h"
#include "scene_internal.h"
}

#include "gltf_internal.hpp"

using namespace gkgltf;

namespace {

// Files larger than this are not scene data we would ever ship; refusing them keeps a hostile file
// from making the loader allocate gigabytes.
const size_t kMaxFileBytes = size_t(1) << 30;


// File access for tinygltf: only regular files under the scene's directory (no wordexp expansion,
// no devices or FIFOs that could block), and nothing at all for documents loaded from memory.
// A buffer's uri is confined to the scene's folder like an image's (texture.c): the file it names,
// symlinks and `..` resolved, must lie inside base_dir, else it is not read at all (so no byte of
// a file outside can reach an error message; base/confine.h). The scene file itself (gk_scene_load)
// has no base.
struct FsContext {
    bool allow_files;
    const char *base_dir; // nullptr: any regular file (the scene file named on the command line)
};

bool fs_exists(const std::string &abs, void *user)
{
    const FsContext *ctx = static_cast<const FsContext *>(user);
    struct stat st;
    return ctx->allow_files && stat(abs.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
           (!ctx->base_dir || gk_path_inside_dir(abs.c_str(), ctx->base_dir));
}

std::string fs_expand(const std::string &p, void *) { return p; }

bool fs_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    if (!fs_exists(path, user)) {
        if (err)
            *err += "cannot open " + path + "\n";
        return false;
    }
    FILE *f = fopen(path.c_str(), "rb");
    if (!f) {
        if (err)
            *err += "cannot open " + path + "\n";
        return false;
    }
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || (size_t)st.st_size > kMaxFileBytes) {
        fclose(f);
        if (err)
            *err += path + " is too large\n";
        return false;
    }
    out->resize((size_t)st.st_size);
    size_t got = out->empty() ? 0 : fread(out->data(), 1, out->size(), f);
    fclose(f);
    if (got != out->size()) {
        if (err)
            *err += "short read on " + path + "\n";
        return false;
    }
    return true;
}

bool fs_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err)
        *err += "the loader writes no files\n";
    return false;
}

// Images are decoded by texture.c through OpenImageIO, never by tinygltf. An image file (uri set)
// is read there, confined to the scene's folder; an embedded one (a GLB chunk or a base64 data:
// uri, no uri left) only reaches us here, so its encoded bytes are kept in image->image.
bool image_keep_embedded(tinygltf::Image *image, const int, std::string *, std::string *, int, int,
                         const unsigned char *bytes, int size, void *)
{
    if (image->uri.empty() && bytes && size > 0)
        image->image.assign(bytes, bytes + size);
    return true;
}

const char *path_stem(const char *path, char *out, size_t cap)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(out, cap, "%s", base);
    char *dot = strrchr(out, '.');
    if (dot && dot != out)
        *dot = '\0';
    return out;
}

gk_scene *convert(Loader &L, const Model &m, const char *base_dir)
{
    gk_scene *s = (gk_scene *)calloc(1, sizeof(gk_scene));
    if (!s) {
        L.fail("out of memory");
        return nullptr;
    }
    snprintf(s->path, sizeof s->path, "%s", L.path);
    path_stem(L.path, s->name, sizeof s->name);
    s->camera_node = -1;
    read_scene_extras(m, s);
    std::vector<int> tex_usage(m.textures.size() + 1, 0);
    bool ok = read_medium(L, scene_gikiosk_extras(m), s) && read_environment(L, scene_gikiosk_extras(m), s) &&
              read_textures(L, m, s) &&
              read_materials(L, m, s, tex_usage) && read_lights(L, m, s) &&
              read_cameras(L, m, s);
    std::vector<int> mesh_first(m.meshes.size()), mesh_count(m.meshes.size());
    if (ok) {
        size_t total = 0;
        for (const auto &mesh : m.meshes)
            total += mesh.primitives.size();
        s->meshes = (gk_mesh *)calloc(total + 1, sizeof(gk_mesh));
        ok = s->meshes != nullptr || L.fail("out of memory");
        for (size_t mi = 0; ok && mi < m.meshes.size(); mi++) {
            mesh_first[mi] = s->n_meshes;
            mesh_count[mi] = (int)m.meshes[mi].primitives.size();
            for (size_t pi = 0; ok && pi < m.meshes[mi].primitives.size(); pi++)
                ok = read_primitive(L, m, (int)mi, (int)pi, m.meshes[mi].primitives[pi], s->n_materials - 1,
                                    &s->meshes[s->n_meshes++]);
        }
    }
    ok = ok && read_nodes(L, m, s, mesh_first, mesh_count) && read_animations(L, m, s);
    s->gltf = L.use;
    if (ok && gk_scene_finish(s, base_dir, tex_usage.data(), L.e) != 0)
        ok = false;
    if (!ok) {
        gk_scene_free(s);
        return nullptr;
    }
    return s;
}

// The extensions the loader reads: a file may require these; any other required one is refused by
// name, and any other one a file merely uses is logged by name (its effect is not shown).
const char *const kSupportedExtensions[] = {"EXT_meshopt_compression",     "KHR_draco_mesh_compression",
                                            "KHR_lights_punctual",        "KHR_materials_emissive_strength",
                                            "KHR_materials_transmission", "KHR_materials_ior",
                                            "KHR_materials_specular",     "KHR_mesh_quantization",
                                            "KHR_texture_transform"};

bool extension_supported(const std::string &name)
{
    for (const char *x : kSupportedExtensions)
        if (name == x)
            return true;
    return false;
}

std::string supported_extensions_list()
{
    std::string all;
    for (const char *x : kSupportedExtensions)
        all += (all.empty() ? "" : ", ") + std::string(x);
    return all;
}

gk_scene *load_bytes(const unsigned char *data, size_t size, const char *path, const char *base_dir, gk_err *e)
{
    Loader L{path, e};
    try {
        if (size > kMaxFileBytes || size > UINT32_MAX) {
            L.fail("file is too large (%zu bytes)", size);
            return nullptr;
        }
        tinygltf::TinyGLTF loader;
        FsContext ctx{base_dir != nullptr, base_dir};
        loader.SetFsCallbacks(tinygltf::FsCallbacks{fs_exists, fs_expand, fs_read, fs_write, &ctx});
        loader.SetImageLoader(image_keep_embedded, nullptr);
        Model model;
        std::string err, warn;
        std::vector<unsigned char> patched;
        if (patch_for_tinygltf(data, size, patched)) {
            data = patched.data();
            size = patched.size();
        }
        bool glb = size >= 4 && memcmp(data, "glTF", 4) == 0;
        std::string dir = base_dir ? base_dir : "";
        bool ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, (unsigned)size, dir)
                      : loader.LoadASCIIFromString(&model, &err, &warn, (const char *)data, (unsigned)size, dir);
        if (!warn.empty()) {
            while (!warn.empty() && warn.back() == '\n')
                warn.pop_back();
            for (size_t at; (at = warn.find('\n')) != std::string::npos;)
                warn.replace(at, 1, "; ");
            gk_log("%s: tinygltf: %s", path, warn.c_str());
        }
        if (!ok) {
            while (!err.empty() && err.back() == '\n')
                err.pop_back();
            for (char &c : err)
                if (c == '\n')
                    c = ' ';
            L.fail("tinygltf: %s", err.empty() ? "cannot parse the file" : err.c_str());
            return nullptr;
        }
        // glTF 2.0 §3.12: a file that requires an extension the loader does not implement must
        // not be shown as if it had none.
        for (const std::string &x : model.extensionsRequired)
            if (!extension_supported(x)) {
                L.fail("requires extension '%s', which gikiosk does not support (supported: %s)", x.c_str(),
                       supported_extensions_list().c_str());
                return nullptr;
            }
        auto append = [](char *list, size_t cap, const std::string &x) {
            size_t n = strlen(list);
            snprintf(list + n, cap - n, "%s%s", n ? ", " : "", x.c_str());
        };
        for (const std::string &x : model.extensionsUsed) {
            if (x == "KHR_mesh_quantization")
                L.quantization = true;
            if (extension_supported(x)) {
                append(L.use.extensions_read, sizeof L.use.extensions_read, x);
            } else {
                gk_log("%s: extension '%s' is not supported and is ignored (the file does not require it)", path,
                       x.c_str());
                append(L.use.extensions_ignored, sizeof L.use.extensions_ignored, x);
            }
        }
        for (const std::string &x : model.extensionsRequired)
            if (x == "KHR_mesh_quantization")
                L.quantization = true;
        if (!decode_meshopt(L, model) || !decode_draco(L, model))
            return nullptr;
        return convert(L, model, base_dir);
    } catch (const std::exception &ex) {
        L.fail("cannot parse the file (%s)", ex.what());
    } catch (...) {
        L.fail("cannot parse the file");
    }
    return nullptr;
}

} // namespace

extern "C" gk_scene *gk_scene_load_memory(const void *data, size_t size, const char *path, const char *base_dir,
                                          gk_err *e)
{
    return load_bytes((const unsigned char *)data, size, path, base_dir, e);
}

extern "C" gk_scene *gk_scene_load(const char *path, gk_err *e)
{
    FsContext ctx{true, nullptr};
    std::vector<unsigned char> bytes;
    std::string err;
    if (!fs_read(&bytes, &err, path, &ctx)) {
        gk_fail(e, GK_EINPUT, "%s: cannot read the scene file (%s)", path,
                fs_exists(path, &ctx) ? "unreadable or too large" : "no such file");
        return nullptr;
    }
    std::string dir = path;
    size_t slash = dir.rfind('/');
    dir = slash == std::string::npos ? std::string(".") : dir.substr(0, slash == 0 ? 1 : slash);
    return load_bytes(bytes.data(), bytes.size(), path, dir.c_str(), e);
}