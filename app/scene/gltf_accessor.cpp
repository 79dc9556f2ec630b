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


const char *component_name(int c)
{
    switch (c) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "unknown";
    }
}

// `count` elements of `elem` bytes at `offset` inside bufferView bvi, with the view's stride (or
// tightly packed when it has none, or when `packed` — sparse indices and values are always
// packed). Every byte lies inside the view and its buffer.
bool view_range(Loader &L, const Model &m, int ai, const char *what, int bvi, size_t offset, size_t count,
                size_t elem, bool packed, const unsigned char **base, size_t *stride_out)
{
    if (bvi < 0 || (size_t)bvi >= m.bufferViews.size())
        return L.fail("accessor %d (%s): bufferView %d does not exist", ai, what, bvi);
    const tinygltf::BufferView &bv = m.bufferViews[(size_t)bvi];
    if (bv.buffer < 0 || (size_t)bv.buffer >= m.buffers.size())
        return L.fail("bufferView %d: buffer %d does not exist", bvi, bv.buffer);
    const tinygltf::Buffer &buf = m.buffers[(size_t)bv.buffer];
    if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
        return L.fail("bufferView %d reads past buffer %d (offset %zu + length %zu > %zu bytes)", bvi, bv.buffer,
                      bv.byteOffset, bv.byteLength, buf.data.size());
    size_t stride = bv.byteStride && !packed ? bv.byteStride : elem;
    if (stride < elem || stride > 252 + elem)
        return L.fail("accessor %d (%s): byteStride %zu of bufferView %d is invalid for %zu-byte elements", ai, what,
                      stride, bvi, elem);
    if (count > 0) {
        // offset + (count - 1) * stride + elem <= byteLength, without overflow.
        bool past = offset > bv.byteLength || count - 1 > (bv.byteLength - offset) / stride;
        if (!past)
            past = offset + (count - 1) * stride + elem > bv.byteLength;
        if (past)
            return L.fail("accessor %d (%s) reads past bufferView %d of buffer %d (offset %zu + %zu elements x "
                          "stride %zu > %zu bytes)",
                          ai, what, bvi, bv.buffer, offset, count, stride, bv.byteLength);
    }
    *base = buf.data.data() + bv.byteOffset + offset;
    *stride_out = stride;
    return true;
}

// A sparse accessor (§3.6.2.3) made dense in v->dense: the base data (or zeros without a
// bufferView), then each of the `count` values written at its index. Indices must be strictly
// increasing and inside the accessor, as the specification requires.
bool densify(Loader &L, const Model &m, int ai, const char *what, const tinygltf::Accessor &a, size_t elem, View *v)
{
    const auto &sp = a.sparse;
    if (a.count > (size_t(1) << 28))
        return L.fail("accessor %d (%s): %zu elements is too many for a sparse accessor", ai, what, a.count);
    size_t n = (size_t)sp.count;
    if (sp.count < 1 || n > a.count)
        return L.fail("accessor %d (%s): sparse count %d must lie in [1, %zu]", ai, what, sp.count, a.count);
    v->dense.assign(a.count * elem + 1, 0);
    if (a.bufferView >= 0) {
        const unsigned char *base;
        size_t stride;
        if (!view_range(L, m, ai, what, a.bufferView, a.byteOffset, a.count, elem, false, &base, &stride))
            return false;
        for (size_t i = 0; i < a.count; i++)
            memcpy(&v->dense[i * elem], base + i * stride, elem);
    }
    int ictype = sp.indices.componentType;
    if (ictype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ictype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ictype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        return L.fail("accessor %d (%s): sparse indices have component type %d (%s); unsigned byte, short or int "
                      "expected",
                      ai, what, ictype, component_name(ictype));
    size_t isize = (size_t)tinygltf::GetComponentSizeInBytes((uint32_t)ictype);
    const unsigned char *ibase, *vbase;
    size_t istride, vstride;
    if (!view_range(L, m, ai, what, sp.indices.bufferView, (size_t)sp.indices.byteOffset, n, isize, true, &ibase,
                    &istride) ||
        !view_range(L, m, ai, what, sp.values.bufferView, (size_t)sp.values.byteOffset, n, elem, true, &vbase,
                    &vstride))
        return false;
    for (size_t k = 0; k < n; k++) {
        uint32_t at = read_index(ibase + k * istride, ictype);
        uint32_t prev = k ? read_index(ibase + (k - 1) * istride, ictype) : 0;
        if (at >= a.count || (k > 0 && at <= prev))
            return L.fail("accessor %d (%s): sparse index %u (entry %zu) is out of range or not increasing", ai,
                          what, at, k);
        memcpy(&v->dense[(size_t)at * elem], vbase + k * vstride, elem);
    }
    v->base = v->dense.data();
    v->stride = elem;
    return true;
}

} // namespace

uint32_t read_index(const unsigned char *q, int ctype)
{
    if (ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
        return q[0];
    if (ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t s;
        memcpy(&s, q, 2);
        return s;
    }
    uint32_t u;
    memcpy(&u, q, 4);
    return u;
}

bool resolve(Loader &L, const Model &m, int ai, const char *what, int want_type, std::initializer_list<int> ctypes,
             View *v)
{
    if (ai < 0 || (size_t)ai >= m.accessors.size())
        return L.fail("%s: accessor %d does not exist (%zu accessors)", what, ai, m.accessors.size());
    const tinygltf::Accessor &a = m.accessors[(size_t)ai];
    if (a.type != want_type)
        return L.fail("accessor %d (%s): type %s, expected %s", ai, what, type_name(a.type), type_name(want_type));
    bool ok = false;
    std::string allowed;
    for (int c : ctypes) {
        ok = ok || c == a.componentType;
        allowed += (allowed.empty() ? "" : ", ") + std::string(component_name(c));
    }
    if (!ok)
        return L.fail("accessor %d (%s): component type %d (%s) is not allowed here (allowed: %s%s)", ai, what,
                      a.componentType, component_name(a.componentType), allowed.c_str(),
                      L.quantization ? "" : "; integer attributes need KHR_mesh_quantization");
    int csize = tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType);
    int comps = tinygltf::GetNumComponentsInType((uint32_t)a.type);
    if (csize <= 0 || comps <= 0)
        return L.fail("accessor %d (%s): unknown component or element type", ai, what);
    size_t elem = (size_t)csize * (size_t)comps;
    v->count = a.count;
    v->comps = comps;
    v->ctype = a.componentType;
    v->normalized = a.normalized;
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && want_type != TINYGLTF_TYPE_SCALAR && L.quantization)
        L.use.quantized_accessors++;
    if (a.sparse.isSparse) {
        L.use.sparse_accessors++;
        return densify(L, m, ai, what, a, elem, v);
    }
    if (a.bufferView < 0)
        return L.fail("accessor %d (%s): no bufferView and not sparse (an all-zero accessor is not supported)", ai,
                      what);
    return view_range(L, m, ai, what, a.bufferView, a.byteOffset, a.count, elem, false, &v->base, &v->stride);
}

// One component as a float: normalized integers mapped to [0, 1] or [-1, 1] (§3.11), other
// integers (KHR_mesh_quantization) taken as their value.
float component(const View &v, size_t i, int c)
{
    const unsigned char *p = v.base + i * v.stride;
    bool n = v.normalized;
    switch (v.ctype) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; memcpy(&f, p + 4 * c, 4); return f; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return n ? p[c] / 255.0f : (float)p[c];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        signed char b = (signed char)p[c];
        return n ? fmaxf(b / 127.0f, -1.0f) : (float)b;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t s;
        memcpy(&s, p + 2 * c, 2);
        return n ? s / 65535.0f : (float)s;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t s;
        memcpy(&s, p + 2 * c, 2);
        return n ? fmaxf(s / 32767.0f, -1.0f) : (float)s;
    }
    default: return 0.0f;
    }
}

// Reads a float (or, as `ints` allows, integer) accessor into a malloc'ed array of count * comps
// floats.
float *read_floats(Loader &L, const Model &m, int ai, const char *what, int type, Ints ints, size_t *count_out)
{
    View v;
    bool ok = ints == Ints::none
                  ? resolve(L, m, ai, what, type, {TINYGLTF_COMPONENT_TYPE_FLOAT}, &v)
                  : resolve(L, m, ai, what, type,
                            {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_BYTE,
                             TINYGLTF_COMPONENT_TYPE_SHORT},
                            &v);
    if (!ok)
        return nullptr;
    if (v.ctype != TINYGLTF_COMPONENT_TYPE_FLOAT && !v.normalized && ints != Ints::normalized_or_not) {
        L.fail("accessor %d (%s): integer components must be normalized%s", ai, what,
               L.quantization ? "" : " (unnormalized ones need KHR_mesh_quantization)");
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
