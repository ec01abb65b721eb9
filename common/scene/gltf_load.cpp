// glTF 2.0 import through tinygltf. Everything read from a file is validated before use (accessor ranges, indices,
// references between objects), so a malformed file gives a SceneError, never a crash.
#include "gltf_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string_view>
#include <system_error>

#include <tiny_gltf.h>

#include "gltf_common.h"
#include "gltf_files.h"
#include "gltf_validate.h"

namespace rt {

namespace {

namespace fs = std::filesystem;
using namespace gltf_detail;

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

// The bytes of an accessor's elements, checked against the buffer view and the buffer.
struct AccessorView {
    const unsigned char* data = nullptr;
    std::size_t count = 0;
    std::size_t stride = 0;
    int component_type = 0;
    int components = 0;
    bool normalized = false;
};

AccessorView view_accessor(const tinygltf::Model& model, int index, const std::string& what) {
    if (index < 0 || std::size_t(index) >= model.accessors.size())
        invalid(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    if (a.sparse.isSparse) invalid(name + ": sparse accessors are not supported");
    AccessorView v;
    v.count = a.count;
    v.component_type = a.componentType;
    v.components = components(a.type);
    v.normalized = a.normalized;
    const int csize = component_size(a.componentType);
    if (v.components == 0 || csize == 0) invalid(name + ": unsupported type");
    if (a.bufferView < 0 || std::size_t(a.bufferView) >= model.bufferViews.size())
        invalid(name + ": missing or invalid bufferView");
    const tinygltf::BufferView& bv = model.bufferViews[std::size_t(a.bufferView)];
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= model.buffers.size()) invalid(name + ": invalid buffer");
    const std::vector<unsigned char>& buffer = model.buffers[std::size_t(bv.buffer)].data;
    const std::size_t element = std::size_t(csize) * std::size_t(v.components);
    v.stride = bv.byteStride ? bv.byteStride : element;
    if (v.stride < element) invalid(name + ": byteStride smaller than an element");
    if (v.count == 0) return v;
    // Every byte read must lie inside the buffer view, and the view inside the buffer. Done in 64-bit with the count
    // bounded first, so nothing overflows.
    if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
        invalid(name + ": bufferView exceeds its buffer");
    if (v.count > bv.byteLength) invalid(name + ": count exceeds its bufferView");
    const std::uint64_t end = std::uint64_t(a.byteOffset) + std::uint64_t(v.count - 1) * v.stride + element;
    if (end > bv.byteLength) invalid(name + ": data exceeds its bufferView");
    v.data = buffer.data() + bv.byteOffset + a.byteOffset;
    return v;
}

// Component j of element i as a float; normalized integers map to [0, 1] or [-1, 1] (glTF 2.0, 3.11).
float read_component(const AccessorView& v, std::size_t i, int j) {
    const unsigned char* p = v.data + i * v.stride + std::size_t(j) * std::size_t(component_size(v.component_type));
    switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return float(*p) / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t s; std::memcpy(&s, p, 2); return float(s) / 65535.0f; }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        std::int8_t b;
        std::memcpy(&b, p, 1);
        return std::max(float(b) / 127.0f, -1.0f);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t s;
        std::memcpy(&s, p, 2);
        return std::max(float(s) / 32767.0f, -1.0f);
    }
    default: return 0.0f;
    }
}

// Reads float (or, when allowed, normalized integer) elements with the given number of components, as vec4s.
std::vector<glm::vec4> read_vectors(const tinygltf::Model& model, int index, int want_components, bool allow_normalized,
                                    const std::string& what) {
    const AccessorView v = view_accessor(model, index, what);
    if (v.components != want_components)
        invalid(what + " (accessor " + std::to_string(index) + "): expected " + std::to_string(want_components) +
                " components");
    const bool is_float = v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool is_normalized = v.normalized && v.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    if (!is_float && !(allow_normalized && is_normalized))
        invalid(what + " (accessor " + std::to_string(index) + "): unsupported component type");
    std::vector<glm::vec4> out(v.count, glm::vec4(0.0f));
    for (std::size_t i = 0; i < v.count; ++i)
        for (int j = 0; j < v.components; ++j) out[i][j] = read_component(v, i, j);
    return out;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index, const std::string& what) {
    const AccessorView v = view_accessor(model, index, what);
    if (v.components != 1) invalid(what + ": indices must be scalars");
    std::vector<std::uint32_t> out(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
        const unsigned char* p = v.data + i * v.stride;
        switch (v.component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = *p; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t s; std::memcpy(&s, p, 2); out[i] = s; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], p, 4); break;
        default: invalid(what + ": indices must be unsigned byte, short or int");
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Loading.

// Accessor elements the loader copies out of a file in all. Several primitives may share one accessor, so the
// copies are not bounded by the file's size; 2^28 elements (about 3 GiB as vec3) allow a 20-million-triangle mesh
// with normals and texture coordinates, unindexed (docs/shading.md, "Limits").
constexpr std::uint64_t kMaxLoadedElements = std::uint64_t(1) << 28;

struct Loader {
    const tinygltf::Model& model;
    std::string warnings;
    std::uint64_t loaded_elements = 0;

    // Counts an accessor's elements against kMaxLoadedElements before they are copied (a bad index is left for
    // view_accessor to report).
    int budget(int accessor, const std::string& what) {
        if (accessor < 0 || std::size_t(accessor) >= model.accessors.size()) return accessor;
        loaded_elements += model.accessors[std::size_t(accessor)].count;
        if (loaded_elements > kMaxLoadedElements)
            invalid(what + ": the file's accessors add up to more than " + std::to_string(kMaxLoadedElements) +
                    " elements");
        return accessor;
    }

    void warn(const std::string& message) { warnings += message + "\n"; }

    // Numbers from the file (docs/shading.md, "Values from files"): one that does not fit a float (NaN, infinite,
    // beyond 3.4e38) is refused; one outside [lo, hi] (glTF's range for it) is clamped with a warning.
    float value(double v, const std::string& what, float lo = -std::numeric_limits<float>::max(),
                float hi = std::numeric_limits<float>::max()) {
        if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
            invalid(what + " is " + describe(v) + ", which does not fit a float");
        const float f = float(v);
        if (f >= lo && f <= hi) return f;
        const float clamped = std::clamp(f, lo, hi);
        warn(what + " " + describe(v) + " is outside [" + describe(lo) + ", " + describe(hi) + "]; clamped to " +
             describe(clamped));
        return clamped;
    }

    // Exactly n numbers through value(), or the fallback when the file gives none.
    template <int N>
    glm::vec<N, float> values(const std::vector<double>& v, const std::string& what, glm::vec<N, float> fallback,
                              float lo = -std::numeric_limits<float>::max(),
                              float hi = std::numeric_limits<float>::max()) {
        if (v.empty()) return fallback;
        if (v.size() != std::size_t(N)) invalid(what + " must have " + std::to_string(N) + " numbers");
        glm::vec<N, float> out;
        for (int i = 0; i < N; ++i) out[i] = value(v[std::size_t(i)], what, lo, hi);
        return out;
    }

    void check_index(int i, std::size_t size, const std::string& what) const {
        if (i < -1 || (i >= 0 && std::size_t(i) >= size))
            invalid(what + " " + std::to_string(i) + " does not exist");
    }

    Primitive primitive(const tinygltf::Primitive& p, const std::string& name) {
        Primitive out;
        check_index(p.material, model.materials.size(), name + ": material");
        out.material = p.material;
        auto attribute = [&](const char* key) {
            auto it = p.attributes.find(key);
            return it == p.attributes.end() ? -1 : it->second;
        };
        const int position = attribute("POSITION");
        if (position < 0) invalid(name + ": no POSITION attribute");
        for (const glm::vec4& v : read_vectors(model, budget(position, name), 3, false, name + " POSITION"))
            out.positions.push_back(glm::vec3(v));
        const std::size_t nv = out.positions.size();

        if (const int normal = attribute("NORMAL"); normal >= 0) {
            for (const glm::vec4& v : read_vectors(model, budget(normal, name), 3, false, name + " NORMAL"))
                out.normals.push_back(glm::vec3(v));
            if (out.normals.size() != nv) invalid(name + ": NORMAL and POSITION counts differ");
        }
        if (const int uv = attribute("TEXCOORD_0"); uv >= 0) {
            for (const glm::vec4& v : read_vectors(model, budget(uv, name), 2, true, name + " TEXCOORD_0"))
                out.uvs.push_back(glm::vec2(v));
            if (out.uvs.size() != nv) invalid(name + ": TEXCOORD_0 and POSITION counts differ");
        }
        if (const int tangent = attribute("TANGENT"); tangent >= 0) {
            out.tangents = read_vectors(model, budget(tangent, name), 4, false, name + " TANGENT");
            if (out.tangents.size() != nv) invalid(name + ": TANGENT and POSITION counts differ");
        }
        if (p.indices >= 0) {
            out.indices = read_indices(model, budget(p.indices, name), name + " indices");
            for (std::uint32_t i : out.indices)
                if (i >= nv)
                    invalid(name + ": index " + std::to_string(i) + " out of range (" + std::to_string(nv) +
                            " vertices)");
            if (out.indices.size() % 3 != 0) {
                warn(name + ": index count is not a multiple of 3; the rest is ignored");
                out.indices.resize(out.indices.size() / 3 * 3);
            }
        } else if (nv % 3 != 0) {
            warn(name + ": vertex count is not a multiple of 3; the rest is ignored");
        }
        return out;
    }

    Mesh mesh(const tinygltf::Mesh& m, std::size_t index) {
        Mesh out;
        out.name = m.name;
        for (std::size_t i = 0; i < m.primitives.size(); ++i) {
            const tinygltf::Primitive& p = m.primitives[i];
            const std::string name = "mesh " + std::to_string(index) + " primitive " + std::to_string(i);
            const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
            if (mode != TINYGLTF_MODE_TRIANGLES) {
                warn(name + ": mode " + std::to_string(mode) + " is not TRIANGLES; skipped");
                continue;
            }
            out.primitives.push_back(primitive(p, name));
        }
        return out;
    }

    // A material's texture reference: its index, or -1 when it has none or uses a texture coordinate set other than
    // TEXCOORD_0 (the only one flattened; warned about).
    int texture_index(int index, int tex_coord, const std::string& what) {
        if (index < 0) return -1;
        check_index(index, model.textures.size(), what);
        if (tex_coord != 0) {
            warn(what + " uses TEXCOORD_" + std::to_string(tex_coord) + "; only TEXCOORD_0 is supported, texture ignored");
            return -1;
        }
        return index;
    }

    // A texture reference inside an extension object ({"index": i, "texCoord": n}), as texture_index.
    int extension_texture(const tinygltf::Value* object, const std::string& key, const std::string& material) {
        const tinygltf::Value* info = object ? member(*object, key) : nullptr;
        if (!info || !info->IsObject()) return -1;
        const std::string what = material + ": " + key;
        const auto integer = [&](const char* field, double fallback) {
            const double v = number(info, field, fallback);
            if (v != std::floor(v) || v < -1.0 || v > 2147483647.0)
                invalid(what + " " + field + " is " + describe(v) + ", not a valid index");
            return int(v);
        };
        return texture_index(integer("index", -1.0), integer("texCoord", 0.0), what);
    }

    Material material(const tinygltf::Material& m, std::size_t index) {
        Material out;
        out.name = m.name;
        const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        const std::string name = "material " + std::to_string(index);
        out.base_color = values<4>(pbr.baseColorFactor, name + ": baseColorFactor", glm::vec4(1.0f), 0.0f, 1.0f);
        out.metallic = value(pbr.metallicFactor, name + ": metallicFactor", 0.0f, 1.0f);
        out.roughness = value(pbr.roughnessFactor, name + ": roughnessFactor", 0.0f, 1.0f);
        if (pbr.baseColorTexture.index >= 0) {
            check_index(pbr.baseColorTexture.index, model.textures.size(), name + ": texture");
            if (texture_transform(pbr.baseColorTexture.extensions, pbr.baseColorTexture.texCoord,
                                  name + ": baseColorTexture", out.base_color_transform))
                out.base_color_texture = pbr.baseColorTexture.index;
        }
        if (m.normalTexture.index >= 0) {
            check_index(m.normalTexture.index, model.textures.size(), name + ": normalTexture");
            if (texture_transform(m.normalTexture.extensions, m.normalTexture.texCoord, name + ": normalTexture",
                                  out.normal_transform))
                out.normal_texture = m.normalTexture.index;
            out.normal_scale = value(m.normalTexture.scale, name + ": normalTexture scale");
        }
        // KHR_materials_volume: attenuationColor [0, 1], attenuationDistance > 0 (absent: infinite, no absorption),
        // thicknessFactor >= 0 (0: thin-walled). JSON cannot spell infinity, so a given distance is finite.
        if (const tinygltf::Value* volume = extension(m.extensions, "KHR_materials_volume")) {
            out.thickness = value(number(volume, "thicknessFactor", 0.0), name + ": thicknessFactor", 0.0f);
            out.attenuation_color = values<3>(numbers(volume, "attenuationColor", {}), name + ": attenuationColor",
                                              glm::vec3(1.0f), 0.0f, 1.0f);
            if (const tinygltf::Value* d = member(*volume, "attenuationDistance"); d && d->IsNumber())
                out.attenuation_distance = value(d->GetNumberAsDouble(), name + ": attenuationDistance",
                                                 std::numeric_limits<float>::min());
        }
        out.metallic_roughness_texture = texture_index(pbr.metallicRoughnessTexture.index,
                                                       pbr.metallicRoughnessTexture.texCoord,
                                                       name + ": metallicRoughnessTexture");
        out.emissive_texture = texture_index(m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                             name + ": emissiveTexture");
        if (pbr.metallicRoughnessTexture.extensions.count("KHR_texture_transform") ||
            m.emissiveTexture.extensions.count("KHR_texture_transform"))
            warn(name + ": KHR_texture_transform is read on baseColorTexture and normalTexture only; ignored on the "
                        "metallic-roughness and emissive textures");
        const float strength = value(number(extension(m.extensions, "KHR_materials_emissive_strength"),
                                            "emissiveStrength", 1.0),
                                     name + ": emissiveStrength", 0.0f);
        // factor <= 1, so the product fits a float too
        out.emissive = values<3>(m.emissiveFactor, name + ": emissiveFactor", glm::vec3(0.0f), 0.0f, 1.0f) * strength;
        const tinygltf::Value* transmission = extension(m.extensions, "KHR_materials_transmission");
        out.transmission = value(number(transmission, "transmissionFactor", 0.0), name + ": transmissionFactor", 0.0f, 1.0f);
        out.transmission_texture = extension_texture(transmission, "transmissionTexture", name);
        out.ior = value(number(extension(m.extensions, "KHR_materials_ior"), "ior", 1.5), name + ": ior", 1.0f);
        const tinygltf::Value* specular = extension(m.extensions, "KHR_materials_specular");
        out.specular = value(number(specular, "specularFactor", 1.0), name + ": specularFactor", 0.0f, 1.0f);
        out.specular_color = values<3>(numbers(specular, "specularColorFactor", {}), name + ": specularColorFactor",
                                       glm::vec3(1.0f), 0.0f);
        if (m.alphaMode == "MASK") out.alpha_mode = AlphaMode::Mask;
        else if (m.alphaMode == "BLEND") out.alpha_mode = AlphaMode::Blend;
        else if (m.alphaMode != "OPAQUE") warn(name + ": alphaMode '" + m.alphaMode + "' is unknown; OPAQUE used");
        out.alpha_cutoff = value(m.alphaCutoff, name + ": alphaCutoff", 0.0f);
        return out;
    }

    // A texture reference's KHR_texture_transform (offset, rotation, scale: any float) into `out`. Its texCoord
    // overrides the reference's; only TEXCOORD_0 is read, so another set is warned about and the texture ignored
    // (returns false).
    bool texture_transform(const tinygltf::ExtensionMap& extensions, int tex_coord, const std::string& what,
                           TextureTransform& out) {
        const tinygltf::Value* t = extension(extensions, "KHR_texture_transform");
        if (t) {
            out.offset = values<2>(numbers(t, "offset", {}), what + " offset", glm::vec2(0.0f));
            out.rotation = value(number(t, "rotation", 0.0), what + " rotation");
            out.scale = values<2>(numbers(t, "scale", {}), what + " scale", glm::vec2(1.0f));
            if (const tinygltf::Value* c = member(*t, "texCoord"); c && c->IsNumber()) tex_coord = c->GetNumberAsInt();
        }
        if (tex_coord == 0) return true;
        warn(what + " uses TEXCOORD_" + std::to_string(tex_coord) + "; only TEXCOORD_0 is supported, texture ignored");
        return false;
    }

    Texture texture(const tinygltf::Texture& t, std::size_t index) {
        Texture out;
        out.name = t.name;
        const std::string name = "texture " + std::to_string(index);
        check_index(t.sampler, model.samplers.size(), name + ": sampler");
        if (t.sampler >= 0)
            out.nearest = model.samplers[std::size_t(t.sampler)].magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        check_index(t.source, model.images.size(), name + ": image");
        if (t.source < 0) {
            warn(name + ": no image source; using white");
            out.width = out.height = 1;
            out.rgba8 = {255, 255, 255, 255};
            return out;
        }
        const tinygltf::Image& img = model.images[std::size_t(t.source)];
        if (out.name.empty()) out.name = img.name;
        const int comps = img.component;
        const int bytes = img.bits == 16 ? 2 : img.bits == 8 ? 1 : 0;
        if (img.width <= 0 || img.height <= 0 || comps < 1 || comps > 4 || bytes == 0)
            invalid(name + ": image " + std::to_string(t.source) + " could not be decoded");
        const std::size_t pixels = std::size_t(img.width) * std::size_t(img.height);
        if (img.image.size() < pixels * std::size_t(comps) * std::size_t(bytes))
            invalid(name + ": image " + std::to_string(t.source) + " has too little pixel data");
        out.width = img.width;
        out.height = img.height;
        out.rgba8.resize(pixels * 4);
        // Expand grey, grey+alpha and RGB to RGBA; 16-bit channels keep their high byte.
        auto channel = [&](std::size_t pixel, int c) -> std::uint8_t {
            const std::size_t at = (pixel * std::size_t(comps) + std::size_t(c)) * std::size_t(bytes);
            if (bytes == 1) return img.image[at];
            std::uint16_t v;
            std::memcpy(&v, &img.image[at], 2);
            return std::uint8_t(v >> 8);
        };
        for (std::size_t i = 0; i < pixels; ++i) {
            std::uint8_t* px = &out.rgba8[4 * i];
            if (comps <= 2) {
                px[0] = px[1] = px[2] = channel(i, 0);
                px[3] = comps == 2 ? channel(i, 1) : 255;
            } else {
                for (int c = 0; c < 3; ++c) px[c] = channel(i, c);
                px[3] = comps == 4 ? channel(i, 3) : 255;
            }
        }
        return out;
    }

    Camera camera(const tinygltf::Camera& c, std::size_t index) {
        Camera out;
        out.name = c.name;
        const std::string name = "camera " + std::to_string(index);
        if (c.type == "orthographic") {
            out.projection = Projection::Orthographic;
            out.xmag = value(c.orthographic.xmag, name + ": xmag");
            out.ymag = value(c.orthographic.ymag, name + ": ymag");
            out.znear = value(c.orthographic.znear, name + ": znear");
            out.zfar = value(c.orthographic.zfar, name + ": zfar");
            if (!(out.xmag != 0.0f && out.ymag != 0.0f && std::isfinite(out.xmag) && std::isfinite(out.ymag)))
                invalid(name + ": invalid xmag/ymag");
        } else if (c.type == "perspective") {
            out.projection = Projection::Perspective;
            out.yfov = value(c.perspective.yfov, name + ": yfov");
            out.aspect = value(c.perspective.aspectRatio, name + ": aspectRatio");
            out.znear = value(c.perspective.znear, name + ": znear");
            out.zfar = value(c.perspective.zfar, name + ": zfar");
            if (!(out.yfov > 0.0f && out.yfov < 3.14159f)) invalid(name + ": invalid yfov");
            if (!(out.aspect >= 0.0f) || !std::isfinite(out.aspect)) out.aspect = 0.0f;
        } else {
            invalid(name + ": unknown type '" + c.type + "'");
        }
        return out;
    }

    Light light(const tinygltf::Light& l, std::size_t index) {
        Light out;
        out.name = l.name;
        if (l.type == "point") out.type = LightType::Point;
        else if (l.type == "spot") out.type = LightType::Spot;
        else if (l.type == "directional") out.type = LightType::Directional;
        else {
            warn("light " + std::to_string(index) + ": unknown type '" + l.type + "'; it is turned off");
            out.intensity = 0.0f;
            return out;
        }
        const std::string name = "light " + std::to_string(index);
        out.color = values<3>(l.color, name + ": color", glm::vec3(1.0f), 0.0f, 1.0f);
        out.intensity = value(l.intensity, name + ": intensity", 0.0f);
        out.range = value(l.range, name + ": range", 0.0f);
        const float quarter_turn = 1.5707964f;
        out.inner_cone = value(l.spot.innerConeAngle, name + ": innerConeAngle", 0.0f, quarter_turn);
        out.outer_cone = value(l.spot.outerConeAngle, name + ": outerConeAngle", 0.0f, quarter_turn);
        return out;
    }

    Node node(const tinygltf::Node& n, std::size_t index) {
        Node out;
        out.name = n.name;
        const std::string name = "node " + std::to_string(index);
        if (n.matrix.size() == 16) {
            glm::mat4 m;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)   // column-major
                    m[c][r] = value(n.matrix[std::size_t(4 * c + r)], name + ": matrix");
            out.matrix = m;
        } else {
            out.translation = values<3>(n.translation, name + ": translation", glm::vec3(0.0f));
            out.scale = values<3>(n.scale, name + ": scale", glm::vec3(1.0f));
            if (n.rotation.size() == 4)   // glTF stores x, y, z, w
                out.rotation = glm::quat(value(n.rotation[3], name + ": rotation"),
                                         value(n.rotation[0], name + ": rotation"),
                                         value(n.rotation[1], name + ": rotation"),
                                         value(n.rotation[2], name + ": rotation"));
        }
        check_index(n.mesh, model.meshes.size(), name + ": mesh");
        check_index(n.camera, model.cameras.size(), name + ": camera");
        out.mesh = n.mesh;
        out.camera = n.camera;
        if (const tinygltf::Value* lights = extension(n.extensions, "KHR_lights_punctual")) {
            const tinygltf::Value* l = member(*lights, "light");
            if (!l || !l->IsNumber()) invalid(name + ": KHR_lights_punctual without a light index");
            out.light = l->GetNumberAsInt();
            check_index(out.light, model.lights.size(), name + ": light");
        }
        for (int child : n.children) {
            if (child < 0 || std::size_t(child) >= model.nodes.size())
                invalid(name + ": child node " + std::to_string(child) + " does not exist");
            out.children.push_back(child);
        }
        return out;
    }

    Animation animation(const tinygltf::Animation& a, std::size_t index, const std::vector<Node>& nodes) {
        Animation out;
        out.name = a.name;
        for (std::size_t i = 0; i < a.channels.size(); ++i) {
            const tinygltf::AnimationChannel& ch = a.channels[i];
            const std::string name = "animation " + std::to_string(index) + " channel " + std::to_string(i);
            AnimationChannel c;
            if (ch.target_path == "translation") c.path = AnimationPath::Translation;
            else if (ch.target_path == "rotation") c.path = AnimationPath::Rotation;
            else if (ch.target_path == "scale") c.path = AnimationPath::Scale;
            else {
                warn(name + ": path '" + ch.target_path + "' is not supported; ignored");
                continue;
            }
            if (ch.target_node < 0) {
                warn(name + ": no target node; ignored");
                continue;
            }
            if (std::size_t(ch.target_node) >= nodes.size())
                invalid(name + ": node " + std::to_string(ch.target_node) + " does not exist");
            if (nodes[std::size_t(ch.target_node)].matrix) warn(name + ": targets a node with a matrix; ignored");
            c.node = ch.target_node;
            if (ch.sampler < 0 || std::size_t(ch.sampler) >= a.samplers.size())
                invalid(name + ": sampler " + std::to_string(ch.sampler) + " does not exist");
            const tinygltf::AnimationSampler& s = a.samplers[std::size_t(ch.sampler)];
            if (s.interpolation == "STEP") c.interpolation = Interpolation::Step;
            else if (s.interpolation == "CUBICSPLINE") c.interpolation = Interpolation::CubicSpline;
            else if (s.interpolation == "LINEAR" || s.interpolation.empty()) c.interpolation = Interpolation::Linear;
            else invalid(name + ": unknown interpolation '" + s.interpolation + "'");

            for (const glm::vec4& t : read_vectors(model, budget(s.input, name), 1, false, name + " input"))
                c.times.push_back(t.x);
            for (std::size_t k = 0; k < c.times.size(); ++k)
                if (!std::isfinite(c.times[k]) || (k > 0 && c.times[k] < c.times[k - 1]))
                    invalid(name + ": key times must be finite and increasing");
            const int comps = c.path == AnimationPath::Rotation ? 4 : 3;
            c.values = read_vectors(model, budget(s.output, name), comps, c.path == AnimationPath::Rotation,
                                    name + " output");
            for (const glm::vec4& v : c.values)
                if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w))
                    invalid(name + ": output values must be finite");
            const std::size_t per_key = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
            if (c.values.size() != per_key * c.times.size()) invalid(name + ": input and output counts do not match");
            if (c.times.empty()) continue;
            out.channels.push_back(std::move(c));
        }
        return out;
    }

    SceneAsset asset() {
        SceneAsset out;
        for (std::size_t i = 0; i < model.meshes.size(); ++i) out.meshes.push_back(mesh(model.meshes[i], i));
        for (std::size_t i = 0; i < model.materials.size(); ++i)
            out.materials.push_back(material(model.materials[i], i));
        for (std::size_t i = 0; i < model.textures.size(); ++i) out.textures.push_back(texture(model.textures[i], i));
        for (std::size_t i = 0; i < model.cameras.size(); ++i) out.cameras.push_back(camera(model.cameras[i], i));
        for (std::size_t i = 0; i < model.lights.size(); ++i) out.lights.push_back(light(model.lights[i], i));
        for (std::size_t i = 0; i < model.nodes.size(); ++i) out.nodes.push_back(node(model.nodes[i], i));

        // The hierarchy must be a forest (glTF 2.0, 3.5.2): every node has at most one parent, and scene roots none.
        std::vector<int> parents(out.nodes.size(), 0);
        for (const Node& n : out.nodes)
            for (int child : n.children)
                if (++parents[std::size_t(child)] > 1)
                    invalid("node " + std::to_string(child) + " has more than one parent");

        // A glTF file says nothing of what rays leaving it see, nor of ambient light: unless it carries our own
        // extras (written by save_gltf), it gets the default world and the hemisphere ambient (docs/shading.md,
        // "Defaults"), as a glTF viewer shows a model in a neutral studio.
        out.has_world = false;
        out.ambient = AmbientModel::Hemisphere;
        if (!model.scenes.empty()) {
            int s = model.defaultScene;
            if (s < 0 || std::size_t(s) >= model.scenes.size()) s = 0;
            const tinygltf::Scene& scene = model.scenes[std::size_t(s)];
            for (int root : scene.nodes) {
                if (root < 0 || std::size_t(root) >= out.nodes.size())
                    invalid("scene " + std::to_string(s) + ": node " + std::to_string(root) + " does not exist");
                if (parents[std::size_t(root)] != 0)
                    invalid("scene " + std::to_string(s) + ": node " + std::to_string(root) + " is not a root");
                out.roots.push_back(root);
            }
            // Our own extra: the background colour (written by save_gltf).
            if (const tinygltf::Value* bg = member(scene.extras, "rt_background"); bg && bg->IsArray())
            {
                out.background = values<3>(numbers(&scene.extras, "rt_background", {}), "rt_background",
                                           glm::vec3(0.0f), 0.0f, kMaxRadiance);
                out.has_world = true;
            }
            if (const tinygltf::Value* a = member(scene.extras, "rt_ambient"); a) {
                bool known = false;
                for (AmbientModel m : {AmbientModel::None, AmbientModel::Constant, AmbientModel::Hemisphere})
                    if (a->IsString() && a->Get<std::string>() == ambient_name(m)) {
                        out.ambient = m;
                        known = true;
                    }
                if (!known) invalid("scene " + std::to_string(s) + ": extras.rt_ambient is not one of none, constant "
                                    "or hemisphere");
            }
        } else {
            for (std::size_t i = 0; i < out.nodes.size(); ++i)
                if (parents[i] == 0) out.roots.push_back(int(i));
        }
        // With one parent per node and parentless roots, a cycle cannot be reached from the roots.

        for (std::size_t i = 0; i < model.animations.size(); ++i)
            out.animations.push_back(animation(model.animations[i], i, out.nodes));
        return out;
    }
};

}  // namespace

SceneAsset load_gltf(const std::string& path, std::string* warnings) {
    const std::string prefix = "cannot load scene " + path + ": ";
    const std::string ext = lower_extension(path);
    if (ext != ".gltf" && ext != ".glb")
        throw SceneError(prefix + "unknown extension '" + ext + "' (expected .gltf or .glb)");
    const bool binary = ext == ".glb";

    // The file itself, then checks on its JSON before tinygltf parses it.
    std::vector<unsigned char> bytes;
    if (const std::string problem = read_regular_file(path, bytes); !problem.empty())
        throw SceneError(prefix + problem);
    std::vector<std::string> unsupported;   // extensions the file uses that the loader does not read
    try {
        const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        const std::string_view json = binary ? glb_json_chunk(bytes) : text;
        check_json_depth(json);
        unsupported = validate_gltf_json(json);
    } catch (const Invalid& e) {
        throw SceneError(prefix + one_line(e.reason));
    }

    // Buffers and images by URI: regular files only, each recorded.
    FileReads reads;
    tinygltf::TinyGLTF gltf;
    gltf.SetFsCallbacks(regular_file_callbacks(reads));
    gltf.SetImageLoader(load_image_within_limits, &reads);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    const std::string base_dir = fs::path(path).parent_path().string();
    try {
        ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir)
                    : gltf.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                               unsigned(bytes.size()), base_dir);
    } catch (const std::exception& e) {   // the JSON parser may throw on some inputs
        throw SceneError(prefix + one_line(e.what()));
    }
    if (!reads.error.empty()) throw SceneError(prefix + reads.error);
    if (!ok) throw SceneError(prefix + one_line(err.empty() ? warn : err));

    Loader loader{model, {}};
    if (!warn.empty()) loader.warn(one_line(warn));
    // One line per extension the renderer does not implement, so a missing feature is not mistaken for a bug (the
    // README's "glTF support" lists what is read).
    for (const std::string& name : unsupported)
        loader.warn("uses extension " + name + ", which this renderer does not implement; rendered without it");
    SceneAsset asset;
    try {
        asset = loader.asset();
    } catch (const Invalid& e) {
        throw SceneError(prefix + one_line(e.reason));
    }
    asset.name = fs::path(path).stem().string();
    asset.input_files = {path};
    asset.input_files.insert(asset.input_files.end(), reads.files.begin(), reads.files.end());
    if (warnings) *warnings += loader.warnings;
    return asset;
}

}  // namespace rt
