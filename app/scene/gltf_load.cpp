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

namespace {

using tinygltf::Model;
using tinygltf::Value;

// Files larger than this are not scene data we would ever ship; refusing them keeps a hostile file
// from making the loader allocate gigabytes.
const size_t kMaxFileBytes = size_t(1) << 30;

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

// Images are read by texture.c through OpenImageIO; tinygltf must not decode them itself.
bool image_noop(tinygltf::Image *, const int, std::string *, std::string *, int, int, const unsigned char *, int,
                void *)
{
    return true;
}

const Value *gikiosk_extras(const Value &extras)
{
    if (!extras.IsObject() || !extras.Has("gikiosk"))
        return nullptr;
    const Value &g = extras.Get("gikiosk");
    return g.IsObject() ? &g : nullptr;
}

const Value *member(const Value *obj, const char *key)
{
    if (!obj || !obj->IsObject() || !obj->Has(key))
        return nullptr;
    return &obj->Get(key);
}

bool finite_all(const std::vector<double> &v)
{
    for (double x : v)
        if (!std::isfinite(x))
            return false;
    return true;
}

void copy_name(char *dst, size_t cap, const std::string &src)
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

const char *type_name(int t)
{
    switch (t) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "other";
    }
}

bool resolve(Loader &L, const Model &m, int ai, const char *what, int want_type, std::initializer_list<int> ctypes,
             View *v)
{
    if (ai < 0 || (size_t)ai >= m.accessors.size())
        return L.fail("%s: accessor %d does not exist (%zu accessors)", what, ai, m.accessors.size());
    const tinygltf::Accessor &a = m.accessors[(size_t)ai];
    if (a.sparse.isSparse)
        return L.fail("accessor %d (%s): sparse accessors are not supported", ai, what);
    if (a.type != want_type)
        return L.fail("accessor %d (%s): type %s, expected %s", ai, what, type_name(a.type), type_name(want_type));
    bool ok = false;
    for (int c : ctypes)
        ok = ok || c == a.componentType;
    if (!ok)
        return L.fail("accessor %d (%s): component type %d is not allowed here", ai, what, a.componentType);
    if (a.bufferView < 0 || (size_t)a.bufferView >= m.bufferViews.size())
        return L.fail("accessor %d (%s): bufferView %d does not exist (accessors without data are not supported)",
                      ai, what, a.bufferView);
    const tinygltf::BufferView &bv = m.bufferViews[(size_t)a.bufferView];
    if (bv.buffer < 0 || (size_t)bv.buffer >= m.buffers.size())
        return L.fail("bufferView %d: buffer %d does not exist", a.bufferView, bv.buffer);
    const tinygltf::Buffer &buf = m.buffers[(size_t)bv.buffer];
    if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
        return L.fail("bufferView %d reads past buffer %d (offset %zu + length %zu > %zu bytes)", a.bufferView,
                      bv.buffer, bv.byteOffset, bv.byteLength, buf.data.size());
    int csize = tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType);
    int comps = tinygltf::GetNumComponentsInType((uint32_t)a.type);
    size_t elem = (size_t)csize * (size_t)comps;
    size_t stride = bv.byteStride ? bv.byteStride : elem;
    if (stride < elem || stride > 252 + elem)
        return L.fail("accessor %d (%s): byteStride %zu of bufferView %d is invalid for %zu-byte elements", ai,
                      what, stride, a.bufferView, elem);
    size_t count = a.count;
    if (count > 0) {
        // offset + (count - 1) * stride + elem <= byteLength, without overflow.
        bool past = a.byteOffset > bv.byteLength || count - 1 > (bv.byteLength - a.byteOffset) / stride;
        if (!past)
            past = a.byteOffset + (count - 1) * stride + elem > bv.byteLength;
        if (past)
            return L.fail("accessor %d (%s) reads past bufferView %d of buffer %d (offset %zu + %zu elements x "
                          "stride %zu > %zu bytes)",
                          ai, what, a.bufferView, bv.buffer, a.byteOffset, count, stride, bv.byteLength);
    }
    v->base = buf.data.data() + bv.byteOffset + a.byteOffset;
    v->stride = stride;
    v->count = count;
    v->comps = comps;
    v->ctype = a.componentType;
    v->normalized = a.normalized;
    return true;
}

float component(const View &v, size_t i, int c)
{
    const unsigned char *p = v.base + i * v.stride;
    switch (v.ctype) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; memcpy(&f, p + 4 * c, 4); return f; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[c] / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_BYTE: return fmaxf((signed char)p[c] / 127.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t s; memcpy(&s, p + 2 * c, 2); return s / 65535.0f; }
    case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t s; memcpy(&s, p + 2 * c, 2); return fmaxf(s / 32767.0f, -1.0f); }
    default: return 0.0f;
    }
}

// Reads a float (or normalized integer) accessor into a malloc'ed array of count * comps floats.
float *read_floats(Loader &L, const Model &m, int ai, const char *what, int type, bool allow_normalized,
                   size_t *count_out)
{
    View v;
    bool ok = allow_normalized
                  ? resolve(L, m, ai, what, type,
                            {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_BYTE,
                             TINYGLTF_COMPONENT_TYPE_SHORT},
                            &v)
                  : resolve(L, m, ai, what, type, {TINYGLTF_COMPONENT_TYPE_FLOAT}, &v);
    if (!ok)
        return nullptr;
    if (v.ctype != TINYGLTF_COMPONENT_TYPE_FLOAT && !v.normalized) {
        L.fail("accessor %d (%s): integer components must be normalized", ai, what);
        return nullptr;
    }
    float *out = (float *)malloc((v.count ? v.count : 1) * (size_t)v.comps * sizeof(float));
    if (!out) {
        L.fail("accessor %d (%s): out of memory", ai, what);
        return nullptr;
    }
    for (size_t i = 0; i < v.count; i++)
        for (int c = 0; c < v.comps; c++)
            out[i * (size_t)v.comps + (size_t)c] = component(v, i, c);
    *count_out = v.count;
    return out;
}

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
// (3 numbers >= 0, default 1), specularTexture (A: weight, data) and specularColorTexture (RGB,
// sRGB colour). A malformed value is refused with the material named, never guessed.
template <typename TexRef>
bool read_specular(Loader &L, const tinygltf::Material &src, int mi, gk_material *d, TexRef &tex_ref)
{
    d->specular = 1.0f;
    d->specular_color[0] = d->specular_color[1] = d->specular_color[2] = 1.0f;
    d->specular_tex = d->specular_color_tex = -1;
    auto it = src.extensions.find("KHR_materials_specular");
    if (it == src.extensions.end())
        return true;
    const Value *ext = &it->second;
    if (!ext->IsObject())
        return L.fail("material %d ('%s'): KHR_materials_specular must be an object", mi, src.name.c_str());
    if (const Value *f = member(ext, "specularFactor")) {
        double v = f->IsNumber() ? f->GetNumberAsDouble() : -1.0;
        if (!std::isfinite(v) || v < 0 || v > 1)
            return L.fail("material %d ('%s'): specularFactor must be a number in [0, 1]", mi, src.name.c_str());
        d->specular = (float)v;
    }
    if (const Value *c = member(ext, "specularColorFactor")) {
        bool ok = c->IsArray() && c->ArrayLen() == 3;
        for (int k = 0; ok && k < 3; k++) {
            const Value &x = c->Get(k);
            double v = x.IsNumber() ? x.GetNumberAsDouble() : -1.0;
            ok = std::isfinite(v) && v >= 0;
            if (ok)
                d->specular_color[k] = (float)v;
        }
        if (!ok)
            return L.fail("material %d ('%s'): specularColorFactor must be 3 finite numbers >= 0", mi,
                          src.name.c_str());
    }
    struct { const char *key, *slot; int flag; int *out; } texs[] = {
        {"specularTexture", "specular", GK_TEX_USED_AS_DATA, &d->specular_tex},
        {"specularColorTexture", "specular colour", GK_TEX_USED_AS_COLOR, &d->specular_color_tex},
    };
    for (auto &t : texs) {
        const Value *info = member(ext, t.key);
        if (!info)
            continue;
        const Value *index = member(info, "index");
        if (!index || !index->IsInt() || index->Get<int>() < 0)
            return L.fail("material %d ('%s'): %s needs an index >= 0", mi, src.name.c_str(), t.key);
        if (!tex_ref(index->Get<int>(), t.flag, mi, t.slot, t.out))
            return false;
    }
    return true;
}

bool read_materials(Loader &L, const Model &m, gk_scene *s, std::vector<int> &tex_usage)
{
    s->n_materials = (int)m.materials.size() + 1;
    s->materials = (gk_material *)calloc((size_t)s->n_materials, sizeof(gk_material));
    if (!s->materials)
        return L.fail("out of memory");
    // The glTF default material (spec §3.9.6): white, metallic 1, roughness 1, appended last.
    gk_material *def = &s->materials[s->n_materials - 1];
    snprintf(def->name, sizeof def->name, "default");
    for (int c = 0; c < 4; c++)
        def->base_color[c] = 1.0f;
    def->base_color_tex = def->metallic_roughness_tex = -1;
    def->metallic = def->roughness = 1.0f;
    def->ior = 1.5f;
    def->specular = 1.0f;
    def->specular_color[0] = def->specular_color[1] = def->specular_color[2] = 1.0f;
    def->specular_tex = def->specular_color_tex = -1;
    auto tex_ref = [&](int ti, int flag, int mi, const char *slot, int *out) {
        if (ti < 0) {
            *out = -1;
            return true;
        }
        if ((size_t)ti >= m.textures.size())
            return L.fail("material %d: %s texture %d does not exist", mi, slot, ti);
        tex_usage[(size_t)ti] |= flag;
        *out = ti;
        return true;
    };
    for (size_t i = 0; i < m.materials.size(); i++) {
        const tinygltf::Material &src = m.materials[i];
        gk_material *d = &s->materials[i];
        int mi = (int)i;
        copy_name(d->name, sizeof d->name, src.name);
        const auto &pbr = src.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() != 4 || !finite_all(pbr.baseColorFactor))
            return L.fail("material %d ('%s'): baseColorFactor must be 4 finite numbers", mi, src.name.c_str());
        if (src.emissiveFactor.size() != 3 || !finite_all(src.emissiveFactor))
            return L.fail("material %d ('%s'): emissiveFactor must be 3 finite numbers", mi, src.name.c_str());
        for (int c = 0; c < 4; c++)
            d->base_color[c] = (float)pbr.baseColorFactor[(size_t)c];
        d->metallic = (float)pbr.metallicFactor;
        d->roughness = (float)pbr.roughnessFactor;
        if (!tex_ref(pbr.baseColorTexture.index, GK_TEX_USED_AS_COLOR, mi, "base colour", &d->base_color_tex) ||
            !tex_ref(pbr.metallicRoughnessTexture.index, GK_TEX_USED_AS_DATA, mi, "metallic-roughness",
                     &d->metallic_roughness_tex))
            return false;
        double strength = 1.0, transmission = 0.0, ior = 1.5;
        auto ext = [&](const char *name, const char *key, double *v) {
            auto it = src.extensions.find(name);
            if (it == src.extensions.end())
                return;
            const Value *x = member(&it->second, key);
            if (x && x->IsNumber())
                *v = x->GetNumberAsDouble();
        };
        ext("KHR_materials_emissive_strength", "emissiveStrength", &strength);
        ext("KHR_materials_transmission", "transmissionFactor", &transmission);
        ext("KHR_materials_ior", "ior", &ior);
        if (!std::isfinite(strength) || strength < 0 || !std::isfinite(transmission) || transmission < 0 ||
            transmission > 1 || !std::isfinite(ior) || (ior != 0 && ior < 1))
            return L.fail("material %d ('%s'): emissive strength, transmission or ior out of range", mi,
                          src.name.c_str());
        for (int c = 0; c < 3; c++)
            d->emissive[c] = (float)(src.emissiveFactor[(size_t)c] * strength);
        d->transmission = (float)transmission;
        d->ior = (float)ior;
        d->double_sided = src.doubleSided;
        if (!read_specular(L, src, mi, d, tex_ref))
            return false;
        const Value *proxy = member(gikiosk_extras(src.extras), "light_proxy");
        d->light_proxy = proxy && proxy->IsBool() && proxy->Get<bool>();
        if (!std::isfinite(d->metallic) || !std::isfinite(d->roughness) || d->metallic < 0 || d->metallic > 1 ||
            d->roughness < 0 || d->roughness > 1)
            return L.fail("material %d ('%s'): metallic/roughness must lie in [0, 1]", mi, src.name.c_str());
    }
    return true;
}

bool read_textures(Loader &L, const Model &m, gk_scene *s)
{
    s->n_textures = (int)m.textures.size();
    s->textures = (gk_texture *)calloc(m.textures.size() + 1, sizeof(gk_texture));
    if (!s->textures)
        return L.fail("out of memory");
    for (size_t i = 0; i < m.textures.size(); i++) {
        int src = m.textures[i].source;
        if (src < 0 || (size_t)src >= m.images.size())
            return L.fail("texture %zu: image %d does not exist", i, src);
        const tinygltf::Image &img = m.images[(size_t)src];
        if (img.uri.empty() || img.uri.compare(0, 5, "data:") == 0)
            return L.fail("image %d: embedded images are not supported; reference an image file by uri", src);
        if (img.uri.size() >= sizeof s->textures[i].uri)
            return L.fail("image %d: uri is too long", src);
        copy_name(s->textures[i].uri, sizeof s->textures[i].uri, img.uri);
    }
    return true;
}

bool read_lights(Loader &L, const Model &m, gk_scene *s)
{
    s->n_lights = (int)m.lights.size();
    s->lights = (gk_light *)calloc(m.lights.size() + 1, sizeof(gk_light));
    if (!s->lights)
        return L.fail("out of memory");
    for (size_t i = 0; i < m.lights.size(); i++) {
        const tinygltf::Light &src = m.lights[i];
        gk_light *d = &s->lights[i];
        copy_name(d->name, sizeof d->name, src.name);
        if (src.type == "point")
            d->type = GK_LIGHT_POINT;
        else if (src.type == "spot")
            d->type = GK_LIGHT_SPOT;
        else if (src.type == "directional")
            d->type = GK_LIGHT_DIRECTIONAL;
        else
            return L.fail("light %zu: unknown type '%s'", i, src.type.c_str());
        for (int c = 0; c < 3; c++)
            d->color[c] = src.color.size() == 3 ? (float)src.color[(size_t)c] : 1.0f;
        d->intensity = (float)src.intensity;
        d->range = (float)src.range;
        d->inner_cone = (float)src.spot.innerConeAngle;
        d->outer_cone = (float)src.spot.outerConeAngle;
        d->shape = GK_SHAPE_POINT;
        const Value *g = gikiosk_extras(src.extras);
        const Value *radius = member(g, "radius"), *size = member(g, "size");
        if (radius) {
            if (!radius->IsNumber())
                return L.fail("light %zu: extras gikiosk.radius must be a number", i);
            d->radius = (float)radius->GetNumberAsDouble();
            d->shape = d->type == GK_LIGHT_POINT ? GK_SHAPE_SPHERE : GK_SHAPE_DISC;
        }
        if (size) {
            if (d->type == GK_LIGHT_DIRECTIONAL || radius)
                return L.fail("light %zu: extras gikiosk.size applies to point and spot lights without a radius", i);
            if (!size->IsArray() || size->ArrayLen() != 2 || !size->Get(0).IsNumber() || !size->Get(1).IsNumber())
                return L.fail("light %zu: extras gikiosk.size must be [W, H]", i);
            d->size[0] = (float)size->Get(0).GetNumberAsDouble();
            d->size[1] = (float)size->Get(1).GetNumberAsDouble();
            d->shape = GK_SHAPE_RECT;
        }
    }
    return true;
}

bool read_cameras(Loader &L, const Model &m, gk_scene *s)
{
    s->n_cameras = (int)m.cameras.size();
    s->cameras = (gk_camera *)calloc(m.cameras.size() + 1, sizeof(gk_camera));
    if (!s->cameras)
        return L.fail("out of memory");
    for (size_t i = 0; i < m.cameras.size(); i++) {
        if (m.cameras[i].type != "perspective")
            return L.fail("camera %zu: type '%s' is not supported (perspective only)", i, m.cameras[i].type.c_str());
        const auto &p = m.cameras[i].perspective;
        s->cameras[i] = gk_camera{(float)p.yfov, (float)p.aspectRatio, (float)p.znear, (float)p.zfar};
    }
    return true;
}

// A node matrix (column-major) split into T, R, S; nodes with shear cannot be represented.
bool decompose(const std::vector<double> &mx, gk_node *n)
{
    double c[3][3];
    for (int j = 0; j < 3; j++)
        for (int r = 0; r < 3; r++)
            c[j][r] = mx[(size_t)(j * 4 + r)];
    double sx = std::sqrt(c[0][0] * c[0][0] + c[0][1] * c[0][1] + c[0][2] * c[0][2]);
    double sy = std::sqrt(c[1][0] * c[1][0] + c[1][1] * c[1][1] + c[1][2] * c[1][2]);
    double sz = std::sqrt(c[2][0] * c[2][0] + c[2][1] * c[2][1] + c[2][2] * c[2][2]);
    if (!(sx > 0 && sy > 0 && sz > 0))
        return false;
    double det = c[0][0] * (c[1][1] * c[2][2] - c[2][1] * c[1][2]) - c[1][0] * (c[0][1] * c[2][2] - c[2][1] * c[0][2]) +
                 c[2][0] * (c[0][1] * c[1][2] - c[1][1] * c[0][2]);
    if (det < 0)
        sx = -sx;
    double r[3][3]; // r[col][row]
    for (int rr = 0; rr < 3; rr++) {
        r[0][rr] = c[0][rr] / sx;
        r[1][rr] = c[1][rr] / sy;
        r[2][rr] = c[2][rr] / sz;
    }
    double m00 = r[0][0], m11 = r[1][1], m22 = r[2][2];
    double qw, qx, qy, qz, tr = m00 + m11 + m22;
    if (tr > 0) {
        double k = std::sqrt(tr + 1.0) * 2;
        qw = 0.25 * k; qx = (r[1][2] - r[2][1]) / k; qy = (r[2][0] - r[0][2]) / k; qz = (r[0][1] - r[1][0]) / k;
    } else if (m00 > m11 && m00 > m22) {
        double k = std::sqrt(1.0 + m00 - m11 - m22) * 2;
        qw = (r[1][2] - r[2][1]) / k; qx = 0.25 * k; qy = (r[1][0] + r[0][1]) / k; qz = (r[2][0] + r[0][2]) / k;
    } else if (m11 > m22) {
        double k = std::sqrt(1.0 + m11 - m00 - m22) * 2;
        qw = (r[2][0] - r[0][2]) / k; qx = (r[1][0] + r[0][1]) / k; qy = 0.25 * k; qz = (r[2][1] + r[1][2]) / k;
    } else {
        double k = std::sqrt(1.0 + m22 - m00 - m11) * 2;
        qw = (r[0][1] - r[1][0]) / k; qx = (r[2][0] + r[0][2]) / k; qy = (r[2][1] + r[1][2]) / k; qz = 0.25 * k;
    }
    n->translation = v3((float)mx[12], (float)mx[13], (float)mx[14]);
    n->scale = v3((float)sx, (float)sy, (float)sz);
    n->rotation = quat{(float)qx, (float)qy, (float)qz, (float)qw};
    return true;
}

bool read_nodes(Loader &L, const Model &m, gk_scene *s, const std::vector<int> &mesh_first,
                const std::vector<int> &mesh_count)
{
    s->n_nodes = (int)m.nodes.size();
    s->nodes = (gk_node *)calloc(m.nodes.size() + 1, sizeof(gk_node));
    if (!s->nodes)
        return L.fail("out of memory");
    for (size_t i = 0; i < m.nodes.size(); i++)
        s->nodes[i].parent = -1;
    for (size_t i = 0; i < m.nodes.size(); i++) {
        const tinygltf::Node &src = m.nodes[i];
        gk_node *d = &s->nodes[i];
        copy_name(d->name, sizeof d->name, src.name);
        d->translation = v3(0, 0, 0);
        d->rotation = quat{0, 0, 0, 1};
        d->scale = v3(1, 1, 1);
        if (src.translation.size() == 3)
            d->translation = v3((float)src.translation[0], (float)src.translation[1], (float)src.translation[2]);
        else if (!src.translation.empty())
            return L.fail("node %zu: translation must have 3 numbers", i);
        if (src.rotation.size() == 4)
            d->rotation = quat{(float)src.rotation[0], (float)src.rotation[1], (float)src.rotation[2],
                               (float)src.rotation[3]};
        else if (!src.rotation.empty())
            return L.fail("node %zu: rotation must have 4 numbers", i);
        if (src.scale.size() == 3)
            d->scale = v3((float)src.scale[0], (float)src.scale[1], (float)src.scale[2]);
        else if (!src.scale.empty())
            return L.fail("node %zu: scale must have 3 numbers", i);
        if (src.matrix.size() == 16) {
            if (!finite_all(src.matrix) || !decompose(src.matrix, d))
                return L.fail("node %zu: matrix is not a finite, invertible TRS matrix", i);
        } else if (!src.matrix.empty()) {
            return L.fail("node %zu: matrix must have 16 numbers", i);
        }
        d->mesh_first = 0;
        d->mesh_count = 0;
        if (src.mesh >= 0) {
            if ((size_t)src.mesh >= m.meshes.size())
                return L.fail("node %zu: mesh %d does not exist", i, src.mesh);
            d->mesh_first = mesh_first[(size_t)src.mesh];
            d->mesh_count = mesh_count[(size_t)src.mesh];
        }
        d->camera = -1;
        if (src.camera >= 0) {
            if ((size_t)src.camera >= m.cameras.size())
                return L.fail("node %zu: camera %d does not exist", i, src.camera);
            d->camera = src.camera;
        }
        d->light = -1;
        auto it = src.extensions.find("KHR_lights_punctual");
        if (it != src.extensions.end()) {
            const Value *li = member(&it->second, "light");
            if (!li || !li->IsNumber() || li->GetNumberAsInt() < 0 || (size_t)li->GetNumberAsInt() >= m.lights.size())
                return L.fail("node %zu: KHR_lights_punctual light index is missing or out of range", i);
            d->light = li->GetNumberAsInt();
        }
        for (int child : src.children) {
            if (child < 0 || (size_t)child >= m.nodes.size() || (size_t)child == i)
                return L.fail("node %zu: child %d does not exist", i, child);
            if (s->nodes[child].parent >= 0)
                return L.fail("node %d has two parents (%d and %zu)", child, s->nodes[child].parent, i);
            s->nodes[child].parent = (int)i;
        }
        if (src.skin >= 0)
            gk_log("%s: node %zu: skins are ignored", L.path, i);
    }
    return true;
}

bool read_animations(Loader &L, const Model &m, gk_scene *s)
{
    size_t total = 0;
    for (const auto &a : m.animations)
        total += a.channels.size();
    s->channels = (gk_anim_channel *)calloc(total + 1, sizeof(gk_anim_channel));
    if (!s->channels)
        return L.fail("out of memory");
    for (size_t ai = 0; ai < m.animations.size(); ai++) {
        const tinygltf::Animation &an = m.animations[ai];
        for (size_t ci = 0; ci < an.channels.size(); ci++) {
            const tinygltf::AnimationChannel &ch = an.channels[ci];
            if (ch.sampler < 0 || (size_t)ch.sampler >= an.samplers.size())
                return L.fail("animation %zu channel %zu: sampler %d does not exist", ai, ci, ch.sampler);
            if (ch.target_node < 0 || (size_t)ch.target_node >= m.nodes.size())
                return L.fail("animation %zu channel %zu: node %d does not exist", ai, ci, ch.target_node);
            gk_anim_channel *d = &s->channels[s->n_channels];
            int comps = 3;
            if (ch.target_path == "translation")
                d->path = GK_ANIM_TRANSLATION;
            else if (ch.target_path == "scale")
                d->path = GK_ANIM_SCALE;
            else if (ch.target_path == "rotation")
                d->path = GK_ANIM_ROTATION, comps = 4;
            else {
                gk_log("%s: animation %zu channel %zu: path '%s' is ignored", L.path, ai, ci, ch.target_path.c_str());
                continue;
            }
            const tinygltf::AnimationSampler &sm = an.samplers[(size_t)ch.sampler];
            // CUBICSPLINE is converted to LINEAR through its key values (the tangents are dropped):
            // our animations are authored linear; a cubic file still plays, slightly differently.
            bool cubic = sm.interpolation == "CUBICSPLINE";
            if (sm.interpolation == "LINEAR" || cubic)
                d->interp = GK_INTERP_LINEAR;
            else if (sm.interpolation == "STEP")
                d->interp = GK_INTERP_STEP;
            else
                return L.fail("animation %zu sampler %d: unknown interpolation '%s'", ai, ch.sampler,
                              sm.interpolation.c_str());
            if (cubic)
                gk_log("%s: animation %zu: CUBICSPLINE converted to LINEAR (tangents ignored)", L.path, ai);
            d->node = ch.target_node;
            s->n_channels++; // owned by the scene from here on, so freed on failure
            char what[96];
            size_t nt = 0, nvals = 0;
            snprintf(what, sizeof what, "animation %zu input", ai);
            d->times = read_floats(L, m, sm.input, what, TINYGLTF_TYPE_SCALAR, false, &nt);
            if (!d->times)
                return false;
            snprintf(what, sizeof what, "animation %zu output", ai);
            float *vals = read_floats(L, m, sm.output, what, comps == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                      comps == 4, &nvals);
            if (!vals)
                return false;
            d->values = vals;
            if (nt == 0 || nvals != nt * (cubic ? 3 : 1))
                return L.fail("animation %zu sampler %d: %zu keys but %zu output values", ai, ch.sampler, nt, nvals);
            if (cubic) // keep the value of each (in-tangent, value, out-tangent) triple
                for (size_t k = 0; k < nt; k++)
                    memmove(vals + k * (size_t)comps, vals + (3 * k + 1) * (size_t)comps, (size_t)comps * sizeof(float));
            d->n_keys = (uint32_t)nt;
        }
    }
    return true;
}

// One medium coefficient: a number or [r, g, b], finite and >= 0 (scene.h, gk_medium).
bool read_medium_rgb(Loader &L, const Value *v, const char *key, float out[3])
{
    if (!v)
        return true;
    double c[3];
    if (v->IsNumber()) {
        c[0] = c[1] = c[2] = v->GetNumberAsDouble();
    } else if (v->IsArray() && v->ArrayLen() == 3 && v->Get(0).IsNumber() && v->Get(1).IsNumber() &&
               v->Get(2).IsNumber()) {
        for (int k = 0; k < 3; k++)
            c[k] = v->Get(k).GetNumberAsDouble();
    } else {
        return L.fail("scene extras gikiosk.medium.%s must be a number or [r, g, b]", key);
    }
    for (int k = 0; k < 3; k++) {
        if (!std::isfinite(c[k]) || c[k] < 0.0)
            return L.fail("scene extras gikiosk.medium.%s: %g is not a finite number >= 0 (1/m)", key, c[k]);
        out[k] = (float)c[k];
    }
    return true;
}

bool read_medium_point(Loader &L, const Value &v, const char *which, vec3 *out)
{
    if (!v.IsArray() || v.ArrayLen() != 3)
        return L.fail("scene extras gikiosk.medium.bounds: %s corner must be [x, y, z]", which);
    float c[3];
    for (int k = 0; k < 3; k++) {
        if (!v.Get(k).IsNumber() || !std::isfinite(v.Get(k).GetNumberAsDouble()))
            return L.fail("scene extras gikiosk.medium.bounds: %s corner must be 3 finite numbers", which);
        c[k] = (float)v.Get(k).GetNumberAsDouble();
    }
    *out = v3(c[0], c[1], c[2]);
    return true;
}

// The scene medium, "extras": {"gikiosk": {"medium": {...}}} (scene.h, gk_medium).
bool read_medium(Loader &L, const Value *g, gk_scene *s)
{
    const Value *med = member(g, "medium");
    if (!med)
        return true;
    if (!med->IsObject())
        return L.fail("scene extras gikiosk.medium must be an object {sigma_s, sigma_a, g, bounds}");
    for (const std::string &key : med->Keys())
        if (key != "sigma_s" && key != "sigma_a" && key != "g" && key != "bounds")
            return L.fail("scene extras gikiosk.medium: unknown key '%s' (sigma_s, sigma_a, g, bounds)", key.c_str());
    gk_medium *md = &s->medium;
    if (!read_medium_rgb(L, member(med, "sigma_s"), "sigma_s", md->sigma_s) ||
        !read_medium_rgb(L, member(med, "sigma_a"), "sigma_a", md->sigma_a))
        return false;
    const Value *gv = member(med, "g");
    if (gv) {
        double g_hg = gv->IsNumber() ? gv->GetNumberAsDouble() : NAN;
        if (!(g_hg > -1.0 && g_hg < 1.0))
            return L.fail("scene extras gikiosk.medium.g must be a number in (-1, 1) (Henyey-Greenstein)");
        md->g = (float)g_hg;
    }
    const Value *b = member(med, "bounds");
    if (b) {
        if (!b->IsArray() || b->ArrayLen() != 2)
            return L.fail("scene extras gikiosk.medium.bounds must be [[x0, y0, z0], [x1, y1, z1]]");
        if (!read_medium_point(L, b->Get(0), "min", &md->box_min) ||
            !read_medium_point(L, b->Get(1), "max", &md->box_max))
            return false;
        if (!(md->box_min.x < md->box_max.x && md->box_min.y < md->box_max.y && md->box_min.z < md->box_max.z))
            return L.fail("scene extras gikiosk.medium.bounds: min must be below max on every axis");
        md->bounded = true;
    }
    md->present = true;
    return true;
}

const Value *scene_gikiosk_extras(const Model &m)
{
    const Value *g = nullptr;
    if (!m.scenes.empty()) {
        size_t si = m.defaultScene >= 0 && (size_t)m.defaultScene < m.scenes.size() ? (size_t)m.defaultScene : 0;
        g = gikiosk_extras(m.scenes[si].extras);
    }
    return g ? g : gikiosk_extras(m.extras);
}

void read_scene_extras(const Model &m, gk_scene *s)
{
    const Value *g = nullptr;
    if (!m.scenes.empty()) {
        size_t si = m.defaultScene >= 0 && (size_t)m.defaultScene < m.scenes.size() ? (size_t)m.defaultScene : 0;
        g = gikiosk_extras(m.scenes[si].extras);
    }
    if (!g)
        g = gikiosk_extras(m.extras);
    if (!g)
        return;
    const Value *desc = member(g, "description"), *methods = member(g, "methods"), *ev = member(g, "exposure");
    if (desc && desc->IsString())
        copy_name(s->description, sizeof s->description, desc->Get<std::string>());
    if (methods && methods->IsString()) {
        copy_name(s->methods, sizeof s->methods, methods->Get<std::string>());
    } else if (methods && methods->IsArray()) {
        std::string joined;
        for (size_t i = 0; i < methods->ArrayLen(); i++)
            if (methods->Get((int)i).IsString())
                joined += (joined.empty() ? "" : ",") + methods->Get((int)i).Get<std::string>();
        copy_name(s->methods, sizeof s->methods, joined);
    }
    if (ev && ev->IsNumber() && std::isfinite(ev->GetNumberAsDouble())) {
        s->exposure_ev = (float)ev->GetNumberAsDouble();
        s->has_exposure = true;
    }
    const Value *params = member(g, "params");
    if (params && params->IsObject())
        for (const std::string &key : params->Keys()) {
            if (s->n_params >= (int)(sizeof s->params / sizeof s->params[0]) || key.size() >= sizeof s->params[0].key)
                break;
            const Value &v = params->Get(key);
            auto *p = &s->params[s->n_params];
            p->n = 0;
            if (v.IsNumber())
                p->v[p->n++] = (float)v.GetNumberAsDouble();
            for (size_t k = 0; v.IsArray() && k < v.ArrayLen() && k < 4; k++)
                if (v.Get((int)k).IsNumber())
                    p->v[p->n++] = (float)v.Get((int)k).GetNumberAsDouble();
            if (p->n > 0) {
                copy_name(p->key, sizeof p->key, key);
                s->n_params++;
            }
        }
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
    bool ok = read_medium(L, scene_gikiosk_extras(m), s) && read_textures(L, m, s) && read_materials(L, m, s, tex_usage) && read_lights(L, m, s) &&
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
    if (ok && gk_scene_finish(s, base_dir, tex_usage.data(), L.e) != 0)
        ok = false;
    if (!ok) {
        gk_scene_free(s);
        return nullptr;
    }
    return s;
}

// The extensions the loader reads (lights, emissive strength, transmission, ior): a file may
// require these; any other required one is refused by name.
const char *const kSupportedExtensions[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                            "KHR_materials_transmission", "KHR_materials_ior"};

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
        loader.SetImageLoader(image_noop, nullptr);
        Model model;
        std::string err, warn;
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
