// Inside the glTF loader (rt_scene): the Loader that turns tinygltf's model into a SceneAsset, validating everything
// it reads, and the readers it uses. Its methods live by concern: gltf_load.cpp (geometry, cameras, lights, nodes,
// animations, the scene, load_gltf), gltf_load_materials.cpp (materials and textures), gltf_read.cpp (JSON values
// and accessors). Every problem throws Invalid (gltf_common.h); load_gltf adds the file name.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "gltf_common.h"
#include "common/scene/scene.h"

namespace rt::gltf_detail {

// Generic JSON values (gltf_read.cpp). `extension` looks a name up in an extensions map.
const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key);
const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const std::string& name);
double number(const tinygltf::Value* object, const std::string& key, double fallback);
// An array of numbers, or the fallback when it is missing or not all numbers.
std::vector<double> numbers(const tinygltf::Value* object, const std::string& key, std::vector<double> fallback);
// A number for a message: short, never 309 digits.
std::string describe(double v);

// Which integer component types an accessor may have besides FLOAT: none, normalized ones (glTF 2.0, 3.7.2.1:
// texture coordinates; 3.11: rotations), or any but UNSIGNED_INT, normalized or not (KHR_mesh_quantization).
enum class Integers { None, Normalized, Any };

// Accessors (gltf_read.cpp): float (or, as allowed, integer) elements with the given number of components, as vec4s
// (normalized integers as [0, 1] or [-1, 1], others as their value); and triangle indices.
std::vector<glm::vec4> read_vectors(const tinygltf::Model& model, int index, int want_components, Integers integers,
                                    const std::string& what);
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index, const std::string& what);

// Accessor elements the loader copies out of a file in all. Several primitives may share one accessor, so the
// copies are not bounded by the file's size; 2^28 elements (about 3 GiB as vec3) allow a 20-million-triangle mesh
// with normals and texture coordinates, unindexed (docs/shading.md, "Limits").
constexpr std::uint64_t kMaxLoadedElements = std::uint64_t(1) << 28;
// Of them, those of accessors without a buffer view (zeros, but for a sparse accessor's substitutions): a few bytes of
// JSON would otherwise ask for gigabytes. 2^24 elements are 256 MiB as the loader's vec4s.
constexpr std::uint64_t kMaxZeroElements = std::uint64_t(1) << 24;

struct Loader {
    const tinygltf::Model& model;
    std::string warnings;
    std::uint64_t loaded_elements = 0;
    std::uint64_t zero_elements = 0;   // of them, without a buffer view

    // Counts an accessor's elements against kMaxLoadedElements before they are copied (a bad index is left for
    // view_accessor to report).
    int budget(int accessor, const std::string& what) {
        if (accessor < 0 || std::size_t(accessor) >= model.accessors.size()) return accessor;
        const tinygltf::Accessor& a = model.accessors[std::size_t(accessor)];
        loaded_elements += a.count;
        if (loaded_elements > kMaxLoadedElements)
            invalid(what + ": the file's accessors add up to more than " + std::to_string(kMaxLoadedElements) +
                    " elements");
        if (a.bufferView < 0) zero_elements += a.count;
        if (zero_elements > kMaxZeroElements)
            invalid(what + ": the file's accessors without a bufferView add up to more than " +
                    std::to_string(kMaxZeroElements) + " elements");
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

    // Each reads one object of the file, checked; `index` is its place in the file and `name` how messages call it.
    // Geometry, cameras, lights, nodes, animations and the scene are in gltf_load.cpp.
    // One TRIANGLES, strip or fan primitive, its morph targets applied at the mesh's default weights.
    Primitive primitive(const tinygltf::Primitive& p, int mode, const std::vector<double>& weights,
                        const std::string& name);

    Mesh mesh(const tinygltf::Mesh& m, std::size_t index);

    // Materials and textures: gltf_load_materials.cpp.
    // A material's texture reference: its index, or -1 when it has none or uses a texture coordinate set other than
    // TEXCOORD_0 (the only one flattened; warned about).
    int texture_index(int index, int tex_coord, const std::string& what);

    // A texture reference inside an extension object ({"index": i, "texCoord": n}), as texture_index.
    int extension_texture(const tinygltf::Value* object, const std::string& key, const std::string& material);

    Material material(const tinygltf::Material& m, std::size_t index);

    // A texture reference's KHR_texture_transform (offset, rotation, scale: any float) into `out`. Its texCoord
    // overrides the reference's; only TEXCOORD_0 is read, so another set is warned about and the texture ignored
    // (returns false).
    bool texture_transform(const tinygltf::ExtensionMap& extensions, int tex_coord, const std::string& what,
                           TextureTransform& out);

    Texture texture(const tinygltf::Texture& t, std::size_t index);

    Camera camera(const tinygltf::Camera& c, std::size_t index);

    Light light(const tinygltf::Light& l, std::size_t index);

    Node node(const tinygltf::Node& n, std::size_t index);

    Animation animation(const tinygltf::Animation& a, std::size_t index, const std::vector<Node>& nodes);

    SceneAsset asset();
};

}  // namespace rt::gltf_detail
