// Materials (core metallic-roughness, KHR_materials_specular, emissive strength, transmission,
// ior) and the images textures refer to.
#include "gltf_internal.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace gkgltf {

namespace {

// A number array of n finite numbers at key of obj (absent: keep out).
bool read_numbers(const Value *obj, const char *key, int n, float *out)
{
    const Value *a = member(obj, key);
    if (!a)
        return true;
    if (!a->IsArray() || (int)a->ArrayLen() != n)
        return false;
    for (int k = 0; k < n; k++) {
        const Value &x = a->Get(k);
        double v = x.IsNumber() ? x.GetNumberAsDouble() : NAN;
        if (!std::isfinite(v))
            return false;
        out[k] = (float)v;
    }
    return true;
}

// Where a texture slot reads its UVs (gk_tex_uv): texCoord 0 or 1 (glTF's textureInfo.texCoord) and
// KHR_texture_transform (offset, rotation, scale, and its own texCoord, which overrides). A set
// past TEXCOORD_1 or a malformed transform is refused naming the material and the slot.
bool read_tex_uv(Loader &L, int mi, const char *slot, int texcoord, const Value *transform, gk_tex_uv *out)
{
    *out = gk_tex_uv{};
    if (transform) {
        float offset[2] = {0, 0}, scale[2] = {1, 1}, rotation = 0;
        const Value *rot = member(transform, "rotation");
        double r = rot ? (rot->IsNumber() ? rot->GetNumberAsDouble() : NAN) : 0.0;
        if (!transform->IsObject() || !read_numbers(transform, "offset", 2, offset) ||
            !read_numbers(transform, "scale", 2, scale) || !std::isfinite(r))
            return L.fail("material %d: %s texture: KHR_texture_transform needs offset [2 numbers], rotation (a "
                          "number) and scale [2 numbers], all finite",
                          mi, slot);
        rotation = (float)r;
        const Value *tc = member(transform, "texCoord");
        if (tc) {
            if (!tc->IsInt())
                return L.fail("material %d: %s texture: KHR_texture_transform texCoord must be an integer", mi, slot);
            texcoord = tc->Get<int>();
        }
        float c = cosf(rotation), sn = sinf(rotation);
        const float m[6] = {c * scale[0], sn * scale[1], offset[0], -sn * scale[0], c * scale[1], offset[1]};
        memcpy(out->m, m, sizeof m);
        out->transformed = true;
        L.use.texture_transforms++;
    }
    if (texcoord < 0 || texcoord > 1)
        return L.fail("material %d: %s texture reads TEXCOORD_%d: only TEXCOORD_0 and TEXCOORD_1 are read", mi, slot,
                      texcoord);
    out->texcoord = texcoord;
    if (texcoord == 1)
        L.use.second_uv_slots++;
    return true;
}

// The KHR_texture_transform object of a textureInfo's extensions, or null.
const Value *texture_transform(const tinygltf::ExtensionMap &ext)
{
    auto it = ext.find("KHR_texture_transform");
    return it == ext.end() ? nullptr : &it->second;
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
    struct { const char *key, *slot; int flag; int *out; gk_tex_uv *uv; } texs[] = {
        {"specularTexture", "specular", GK_TEX_USED_AS_DATA, &d->specular_tex, &d->tex_uv[GK_SLOT_SPECULAR]},
        {"specularColorTexture", "specular colour", GK_TEX_USED_AS_COLOR, &d->specular_color_tex,
         &d->tex_uv[GK_SLOT_SPECULAR_COLOR]},
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
        const Value *tc = member(info, "texCoord");
        const Value *exts = member(info, "extensions");
        if (tc && !tc->IsInt())
            return L.fail("material %d ('%s'): %s texCoord must be an integer", mi, src.name.c_str(), t.key);
        if (!read_tex_uv(L, mi, t.slot, tc ? tc->Get<int>() : 0, member(exts, "KHR_texture_transform"), t.uv))
            return false;
    }
    return true;
}


// One number of a material extension (`name`.`key`), when present: a non-number or a value outside
// [lo, hi] is refused naming the material, the extension and the key.
bool read_number_ext(Loader &L, const tinygltf::Material &src, int mi, const char *name, const char *key, double lo,
                     double hi, const char *wanted, double *v)
{
    auto it = src.extensions.find(name);
    if (it == src.extensions.end())
        return true;
    if (!it->second.IsObject())
        return L.fail("material %d ('%s'): %s must be an object", mi, src.name.c_str(), name);
    const Value *x = member(&it->second, key);
    if (!x)
        return true;
    double d = x->IsNumber() ? x->GetNumberAsDouble() : NAN;
    if (!std::isfinite(d) || d < lo || d > hi)
        return L.fail("material %d ('%s'): %s %s must be %s", mi, src.name.c_str(), name, key, wanted);
    *v = d;
    return true;
}

// Glass (DESIGN §4): KHR_materials_transmission's transmissionFactor in [0, 1] (default 0) and
// KHR_materials_ior's ior, >= 1 or exactly 0 (the extension's "no refraction, pure reflection"
// value; default 1.5). transmissionTexture is not read (logged): glass here is uniform.
bool read_glass(Loader &L, const tinygltf::Material &src, int mi, double *transmission, double *ior)
{
    if (!read_number_ext(L, src, mi, "KHR_materials_transmission", "transmissionFactor", 0.0, 1.0, "a number in [0, 1]",
                         transmission) ||
        !read_number_ext(L, src, mi, "KHR_materials_ior", "ior", 0.0, HUGE_VAL, "0 or a finite number >= 1", ior))
        return false;
    if (*ior > 0 && *ior < 1)
        return L.fail("material %d ('%s'): KHR_materials_ior ior must be 0 or a finite number >= 1", mi,
                      src.name.c_str());
    auto it = src.extensions.find("KHR_materials_transmission");
    if (it != src.extensions.end() && member(&it->second, "transmissionTexture"))
        gk_log("%s: material %d ('%s'): transmissionTexture is ignored (transmissionFactor only)", L.path, mi,
               src.name.c_str());
    return true;
}

// The texture's sampler (glTF §5.26): wrapS/wrapT REPEAT (10497, the default), CLAMP_TO_EDGE
// (33071) or MIRRORED_REPEAT (33648); magFilter NEAREST (9728) gives nearest texels, LINEAR (9729)
// or none bilinear. minFilter's mipmap modes are read as their base filter (no mipmaps here), so it
// is only validated. Any other value is refused naming the sampler and the key.
bool read_sampler(Loader &L, const Model &m, int ti, gk_texture *t)
{
    int si = m.textures[(size_t)ti].sampler;
    if (si < 0)
        return true;
    if ((size_t)si >= m.samplers.size())
        return L.fail("texture %d: sampler %d does not exist", ti, si);
    const tinygltf::Sampler &smp = m.samplers[(size_t)si];
    struct { const char *key; int value; enum gk_wrap *out; } wraps[] = {
        {"wrapS", smp.wrapS, &t->wrap_s}, {"wrapT", smp.wrapT, &t->wrap_t}};
    for (auto &w : wraps) {
        if (w.value == TINYGLTF_TEXTURE_WRAP_REPEAT)
            *w.out = GK_WRAP_REPEAT;
        else if (w.value == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE)
            *w.out = GK_WRAP_CLAMP;
        else if (w.value == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
            *w.out = GK_WRAP_MIRROR;
        else
            return L.fail("sampler %d: %s %d is not REPEAT (10497), CLAMP_TO_EDGE (33071) or MIRRORED_REPEAT (33648)",
                          si, w.key, w.value);
    }
    if (smp.magFilter != -1 && smp.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
        smp.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR)
        return L.fail("sampler %d: magFilter %d is not NEAREST (9728) or LINEAR (9729)", si, smp.magFilter);
    static const int min_ok[] = {-1, 9728, 9729, 9984, 9985, 9986, 9987};
    bool ok = false;
    for (int v : min_ok)
        ok = ok || smp.minFilter == v;
    if (!ok)
        return L.fail("sampler %d: minFilter %d is not a glTF filter (9728, 9729, 9984 to 9987)", si, smp.minFilter);
    t->nearest = smp.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    if (t->nearest || t->wrap_s != GK_WRAP_REPEAT || t->wrap_t != GK_WRAP_REPEAT)
        L.use.samplers++;
    return true;
}

} // namespace

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
    def->emissive_tex = def->normal_tex = def->occlusion_tex = -1;
    def->normal_scale = 1.0f;
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
                     &d->metallic_roughness_tex) ||
            !tex_ref(src.emissiveTexture.index, GK_TEX_USED_AS_COLOR, mi, "emissive", &d->emissive_tex) ||
            !tex_ref(src.normalTexture.index, GK_TEX_USED_AS_DATA, mi, "normal", &d->normal_tex) ||
            !tex_ref(src.occlusionTexture.index, GK_TEX_USED_AS_DATA, mi, "occlusion", &d->occlusion_tex))
            return false;
        const struct { const char *slot; int texcoord; const tinygltf::ExtensionMap *ext; enum gk_tex_slot k; } uvs[] = {
            {"base colour", pbr.baseColorTexture.texCoord, &pbr.baseColorTexture.extensions, GK_SLOT_BASE},
            {"metallic-roughness", pbr.metallicRoughnessTexture.texCoord, &pbr.metallicRoughnessTexture.extensions,
             GK_SLOT_MR},
            {"emissive", src.emissiveTexture.texCoord, &src.emissiveTexture.extensions, GK_SLOT_EMISSIVE},
            {"normal", src.normalTexture.texCoord, &src.normalTexture.extensions, GK_SLOT_NORMAL},
            {"occlusion", src.occlusionTexture.texCoord, &src.occlusionTexture.extensions, GK_SLOT_OCCLUSION},
        };
        const int slot_tex[] = {d->base_color_tex, d->metallic_roughness_tex, d->emissive_tex, d->normal_tex,
                                d->occlusion_tex};
        static_assert(sizeof slot_tex / sizeof slot_tex[0] == sizeof uvs / sizeof uvs[0], "one texture per slot");
        for (size_t k = 0; k < sizeof uvs / sizeof uvs[0]; k++)
            if (slot_tex[k] >= 0 && !read_tex_uv(L, mi, uvs[k].slot, uvs[k].texcoord, texture_transform(*uvs[k].ext),
                                                 &d->tex_uv[uvs[k].k]))
                return false;
        // alphaMode (glTF 3.9.4): OPAQUE (default), MASK with alphaCutoff (default 0.5, >= 0), BLEND.
        if (src.alphaMode == "MASK") {
            if (!std::isfinite(src.alphaCutoff) || src.alphaCutoff < 0)
                return L.fail("material %d ('%s'): alphaCutoff must be a finite number >= 0", mi, src.name.c_str());
            d->alpha_mask = true;
            d->alpha_cutoff = (float)src.alphaCutoff;
            L.use.alpha_masked++;
        } else if (src.alphaMode == "BLEND") {
            d->alpha_blend = true;
            L.use.alpha_blended++;
        } else if (!src.alphaMode.empty() && src.alphaMode != "OPAQUE") {
            return L.fail("material %d ('%s'): alphaMode '%s' is not OPAQUE, MASK or BLEND", mi, src.name.c_str(),
                          src.alphaMode.c_str());
        }
        double strength = 1.0, transmission = 0.0, ior = 1.5;
        if (!read_number_ext(L, src, mi, "KHR_materials_emissive_strength", "emissiveStrength", 0.0, HUGE_VAL,
                             "a finite number >= 0", &strength) ||
            !read_glass(L, src, mi, &transmission, &ior))
            return false;
        for (int c = 0; c < 3; c++)
            d->emissive[c] = (float)(src.emissiveFactor[(size_t)c] * strength);
        d->transmission = (float)transmission;
        d->ior = (float)ior;
        d->double_sided = src.doubleSided;
        if (d->double_sided)
            L.use.double_sided++;
        d->normal_scale = (float)src.normalTexture.scale;
        // occlusionTexture.strength (glTF 5.20): a number in [0, 1], 1 by default
        d->occlusion_strength = (float)src.occlusionTexture.strength;
        if (!(d->occlusion_strength >= 0.0f && d->occlusion_strength <= 1.0f))
            return L.fail("material %d ('%s'): occlusionTexture.strength must be a number in [0, 1]", mi,
                          src.name.c_str());
        if (d->occlusion_tex >= 0)
            L.use.occlusion_textures++;
        if (!std::isfinite(d->normal_scale))
            return L.fail("material %d ('%s'): normalTexture.scale must be finite", mi, src.name.c_str());
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
        gk_texture *t = &s->textures[i];
        if (!read_sampler(L, m, (int)i, t))
            return false;
        copy_name(t->mime, sizeof t->mime, img.mimeType);
        if (img.uri.empty()) { // embedded: its bytes were kept by the image callback (gltf_load.cpp)
            if (img.image.empty())
                return L.fail("image %d: embedded image has no bytes (bufferView %d)", src, img.bufferView);
            t->embedded = (unsigned char *)malloc(img.image.size());
            if (!t->embedded)
                return L.fail("image %d: out of memory", src);
            memcpy(t->embedded, img.image.data(), img.image.size());
            t->embedded_size = img.image.size();
            L.use.embedded_images++;
            continue;
        }
        if (img.uri.size() >= sizeof s->textures[i].uri)
            return L.fail("image %d: uri is too long", src);
        copy_name(s->textures[i].uri, sizeof s->textures[i].uri, img.uri);
    }
    return true;
}

} // namespace gkgltf
