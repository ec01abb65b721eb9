// Reading what tinygltf parsed: its generic JSON values (extensions, extras) and accessors (glTF 2.0, 3.6.2), each
// checked against the buffers it points into. Used by the loader (gltf_loader.h).
#include <algorithm>
#include <cstdio>
#include <cstring>

#include <tiny_gltf.h>

#include "gltf_common.h"
#include "gltf_loader.h"

namespace rt::gltf_detail {

// ---------------------------------------------------------------------------------------------------------------
// Reading tinygltf's generic JSON values (extensions).

const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key) {
    if (!object.IsObject() || !object.Has(key)) return nullptr;
    return &object.Get(key);
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const std::string& name) {
    auto it = map.find(name);
    return it == map.end() ? nullptr : &it->second;
}

double number(const tinygltf::Value* object, const std::string& key, double fallback) {
    if (!object) return fallback;
    const tinygltf::Value* v = member(*object, key);
    return v && v->IsNumber() ? v->GetNumberAsDouble() : fallback;
}

// An array of numbers, or the fallback when it is missing or not all numbers.
std::vector<double> numbers(const tinygltf::Value* object, const std::string& key, std::vector<double> fallback) {
    if (!object) return fallback;
    const tinygltf::Value* v = member(*object, key);
    if (!v || !v->IsArray()) return fallback;
    std::vector<double> out;
    for (int i = 0; i < int(v->ArrayLen()); ++i) {
        const tinygltf::Value& e = v->Get(i);
        if (!e.IsNumber()) return fallback;
        out.push_back(e.GetNumberAsDouble());
    }
    return out;
}

// A number for a message: short, never 309 digits.
std::string describe(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return text;
}

namespace {

// ---------------------------------------------------------------------------------------------------------------
// Accessors (glTF 2.0, 3.6.2 "Accessors").

int components(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
    }
}

int component_size(int component_type) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

// The bytes of an accessor's elements, checked against the buffer view and the buffer. data is null for an accessor
// without a buffer view: its elements are zeros (glTF 2.0, 3.6.2.1), unless its sparse part replaces some.
struct AccessorView {
    const unsigned char* data = nullptr;
    std::size_t count = 0;
    std::size_t stride = 0;
    int component_type = 0;
    int components = 0;
    bool normalized = false;
};

// Points `v` (count, component type and components set) at byte `offset` of buffer view `view`, checking that every
// byte read lies inside the view and the view inside its buffer. `strided`: the view's byteStride applies (an
// accessor's elements); else they are tightly packed (a sparse part's indices and values).
void view_bytes(const tinygltf::Model& model, AccessorView& v, int view, long long offset, bool strided,
                const std::string& name) {
    if (view < 0 || std::size_t(view) >= model.bufferViews.size()) invalid(name + ": missing or invalid bufferView");
    if (offset < 0) invalid(name + ": negative byteOffset");
    const tinygltf::BufferView& bv = model.bufferViews[std::size_t(view)];
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= model.buffers.size()) invalid(name + ": invalid buffer");
    const std::vector<unsigned char>& buffer = model.buffers[std::size_t(bv.buffer)].data;
    const std::size_t element = std::size_t(component_size(v.component_type)) * std::size_t(v.components);
    v.stride = strided && bv.byteStride ? bv.byteStride : element;
    if (v.stride < element) invalid(name + ": byteStride smaller than an element");
    if (v.count == 0) return;
    // Done in 64-bit with the count bounded first, so nothing overflows.
    if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
        invalid(name + ": bufferView exceeds its buffer");
    if (v.count > bv.byteLength) invalid(name + ": count exceeds its bufferView");
    const std::uint64_t end = std::uint64_t(offset) + std::uint64_t(v.count - 1) * v.stride + element;
    if (end > bv.byteLength) invalid(name + ": data exceeds its bufferView");
    v.data = buffer.data() + bv.byteOffset + std::size_t(offset);
}

AccessorView view_accessor(const tinygltf::Model& model, int index, const std::string& what) {
    if (index < 0 || std::size_t(index) >= model.accessors.size())
        invalid(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    AccessorView v;
    v.count = a.count;
    v.component_type = a.componentType;
    v.components = components(a.type);
    v.normalized = a.normalized;
    if (v.components == 0 || component_size(a.componentType) == 0) invalid(name + ": unsupported type");
    if (a.bufferView >= 0) view_bytes(model, v, a.bufferView, (long long)a.byteOffset, true, name);
    return v;
}

// Component j of element i as a float; normalized integers map to [0, 1] or [-1, 1] (glTF 2.0, 3.11), others
// (KHR_mesh_quantization) keep their value.
float read_component(const AccessorView& v, std::size_t i, int j) {
    if (!v.data) return 0.0f;
    const unsigned char* p = v.data + i * v.stride + std::size_t(j) * std::size_t(component_size(v.component_type));
    const bool n = v.normalized;
    switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return n ? float(*p) / 255.0f : float(*p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t s;
        std::memcpy(&s, p, 2);
        return n ? float(s) / 65535.0f : float(s);
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        std::int8_t b;
        std::memcpy(&b, p, 1);
        return n ? std::max(float(b) / 127.0f, -1.0f) : float(b);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t s;
        std::memcpy(&s, p, 2);
        return n ? std::max(float(s) / 32767.0f, -1.0f) : float(s);
    }
    default: return 0.0f;
    }
}

// An unsigned integer element (indices): 0 where there is no buffer view.
std::uint32_t read_unsigned(const AccessorView& v, std::size_t i, const std::string& what) {
    if (!v.data) return 0;
    const unsigned char* p = v.data + i * v.stride;
    switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t s; std::memcpy(&s, p, 2); return s; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t u; std::memcpy(&u, p, 4); return u; }
    default: invalid(what + ": must be unsigned byte, short or int");
    }
}

// A sparse accessor's substitutions (glTF 2.0, 3.6.2.3): `count` element indices, strictly increasing and below the
// accessor's count, and as many values of the accessor's type, each replacing its element of the dense part (the
// buffer view's, or zeros). Calls replace(element, values, k) for the k-th substitution.
template <class Replace>
void for_each_substitution(const tinygltf::Model& model, int index, const std::string& what, Replace replace) {
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    if (!a.sparse.isSparse) return;
    const std::string name = what + " (accessor " + std::to_string(index) + ", sparse)";
    if (a.sparse.count < 1 || std::size_t(a.sparse.count) > a.count)
        invalid(name + ": count " + std::to_string(a.sparse.count) + " is not from 1 to the accessor's count");
    AccessorView indices;
    indices.count = std::size_t(a.sparse.count);
    indices.component_type = a.sparse.indices.componentType;
    indices.components = 1;
    if (indices.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        indices.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indices.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        invalid(name + ": indices must be unsigned byte, short or int");
    view_bytes(model, indices, a.sparse.indices.bufferView, a.sparse.indices.byteOffset, false, name + " indices");
    AccessorView values;
    values.count = indices.count;
    values.component_type = a.componentType;
    values.components = components(a.type);
    values.normalized = a.normalized;
    view_bytes(model, values, a.sparse.values.bufferView, a.sparse.values.byteOffset, false, name + " values");
    for (std::size_t k = 0; k < indices.count; ++k) {
        const std::uint32_t element = read_unsigned(indices, k, name + " indices");
        if (element >= a.count || (k > 0 && element <= read_unsigned(indices, k - 1, name)))
            invalid(name + ": index " + std::to_string(element) + " is not increasing and below the count");
        replace(element, values, k);
    }
}

}  // namespace

std::vector<glm::vec4> read_vectors(const tinygltf::Model& model, int index, int want_components, Integers integers,
                                    const std::string& what) {
    const AccessorView v = view_accessor(model, index, what);
    if (v.components != want_components)
        invalid(what + " (accessor " + std::to_string(index) + "): expected " + std::to_string(want_components) +
                " components");
    const bool is_float = v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool is_integer = !is_float && v.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    const bool allowed = is_float || (is_integer && integers == Integers::Any) ||
                         (is_integer && v.normalized && integers == Integers::Normalized);
    if (!allowed)
        invalid(what + " (accessor " + std::to_string(index) + "): unsupported component type");
    std::vector<glm::vec4> out(v.count, glm::vec4(0.0f));
    for (std::size_t i = 0; i < v.count; ++i)
        for (int j = 0; j < v.components; ++j) out[i][j] = read_component(v, i, j);
    for_each_substitution(model, index, what, [&](std::size_t i, const AccessorView& values, std::size_t k) {
        for (int j = 0; j < values.components; ++j) out[i][j] = read_component(values, k, j);
    });
    return out;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index, const std::string& what) {
    const AccessorView v = view_accessor(model, index, what);
    if (v.components != 1) invalid(what + ": indices must be scalars");
    if (v.component_type == TINYGLTF_COMPONENT_TYPE_BYTE || v.component_type == TINYGLTF_COMPONENT_TYPE_SHORT ||
        v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT)
        invalid(what + ": indices must be unsigned byte, short or int");
    std::vector<std::uint32_t> out(v.count);
    for (std::size_t i = 0; i < v.count; ++i) out[i] = read_unsigned(v, i, what);
    for_each_substitution(model, index, what, [&](std::size_t i, const AccessorView& values, std::size_t k) {
        out[i] = read_unsigned(values, k, what);
    });
    return out;
}

}  // namespace rt::gltf_detail
