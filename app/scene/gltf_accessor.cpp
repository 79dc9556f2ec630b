// Accessors (glTF 2.0 §3.6.2): each resolved to bytes that lie inside its bufferView and buffer,
// then read as floats or indices.
#include "gltf_internal.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace gkgltf {

bool finite_all(const std::vector<double> &v)
{
    for (double x : v)
        if (!std::isfinite(x))
            return false;
    return true;
}

namespace {

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


} // namespace

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
} // namespace gkgltf
