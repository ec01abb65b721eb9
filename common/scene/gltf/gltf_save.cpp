// glTF 2.0 export through tinygltf: the same extensions the loader reads, written to a temporary file and renamed.
#include "gltf_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <system_error>

#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "gltf_common.h"
#include "common/scene/whole_file.h"

namespace rt {

namespace {

namespace fs = std::filesystem;
using namespace gltf_detail;

struct Writer {
    tinygltf::Model model;
    std::vector<std::string> extensions;

    void use_extension(const std::string& name) {
        if (std::find(extensions.begin(), extensions.end(), name) == extensions.end()) extensions.push_back(name);
    }

    // Appends raw bytes to buffer 0 (4-byte aligned) as a new buffer view; returns its index.
    int add_view(const void* bytes, std::size_t size, int target) {
        std::vector<unsigned char>& data = model.buffers[0].data;
        while (data.size() % 4) data.push_back(0);
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = data.size();
        view.byteLength = size;
        view.target = target;
        const auto* p = static_cast<const unsigned char*>(bytes);
        data.insert(data.end(), p, p + size);
        model.bufferViews.push_back(view);
        return int(model.bufferViews.size() - 1);
    }

    // A tightly packed float accessor of `comps` components per element, with min/max.
    int add_floats(const float* values, std::size_t count, int comps, int type, int target) {
        tinygltf::Accessor a;
        a.bufferView = add_view(values, count * std::size_t(comps) * sizeof(float), target);
        a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        a.count = count;
        a.type = type;
        a.minValues.assign(std::size_t(comps), std::numeric_limits<double>::infinity());
        a.maxValues.assign(std::size_t(comps), -std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < count; ++i)
            for (std::size_t j = 0; j < std::size_t(comps); ++j) {
                a.minValues[j] = std::min(a.minValues[j], double(values[i * std::size_t(comps) + j]));
                a.maxValues[j] = std::max(a.maxValues[j], double(values[i * std::size_t(comps) + j]));
            }
        model.accessors.push_back(a);
        return int(model.accessors.size() - 1);
    }

    int add_indices(const std::vector<std::uint32_t>& indices) {
        tinygltf::Accessor a;
        a.bufferView = add_view(indices.data(), indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        a.count = indices.size();
        a.type = TINYGLTF_TYPE_SCALAR;
        model.accessors.push_back(a);
        return int(model.accessors.size() - 1);
    }

    tinygltf::Mesh mesh(const Mesh& m) {
        tinygltf::Mesh out;
        out.name = m.name;
        for (const Primitive& p : m.primitives) {
            if (p.positions.empty()) continue;   // an accessor may not be empty (glTF 2.0, 5.1.2)
            tinygltf::Primitive prim;
            prim.mode = TINYGLTF_MODE_TRIANGLES;
            prim.material = p.material >= 0 && std::size_t(p.material) < model.materials.size() ? p.material : -1;
            prim.attributes["POSITION"] = add_floats(&p.positions[0].x, p.positions.size(), 3, TINYGLTF_TYPE_VEC3,
                                                     TINYGLTF_TARGET_ARRAY_BUFFER);
            if (p.normals.size() == p.positions.size())
                prim.attributes["NORMAL"] = add_floats(&p.normals[0].x, p.normals.size(), 3, TINYGLTF_TYPE_VEC3,
                                                       TINYGLTF_TARGET_ARRAY_BUFFER);
            if (p.uvs.size() == p.positions.size())
                prim.attributes["TEXCOORD_0"] =
                    add_floats(&p.uvs[0].x, p.uvs.size(), 2, TINYGLTF_TYPE_VEC2, TINYGLTF_TARGET_ARRAY_BUFFER);
            if (p.tangents.size() == p.positions.size())
                prim.attributes["TANGENT"] = add_floats(&p.tangents[0].x, p.tangents.size(), 4, TINYGLTF_TYPE_VEC4,
                                                        TINYGLTF_TARGET_ARRAY_BUFFER);
            if (p.colors.size() == p.positions.size())
                prim.attributes["COLOR_0"] = add_floats(&p.colors[0].x, p.colors.size(), 4, TINYGLTF_TYPE_VEC4,
                                                        TINYGLTF_TARGET_ARRAY_BUFFER);
            if (!p.indices.empty()) prim.indices = add_indices(p.indices);
            out.primitives.push_back(prim);
        }
        return out;
    }

    tinygltf::Material material(const Material& m) {
        tinygltf::Material out;
        out.name = m.name;
        out.pbrMetallicRoughness.baseColorFactor = {m.base_color.r, m.base_color.g, m.base_color.b, m.base_color.a};
        out.pbrMetallicRoughness.metallicFactor = m.metallic;
        out.pbrMetallicRoughness.roughnessFactor = m.roughness;
        if (m.base_color_texture >= 0) {
            out.pbrMetallicRoughness.baseColorTexture.index = m.base_color_texture;
            texture_transform(m.base_color_transform, out.pbrMetallicRoughness.baseColorTexture.extensions);
        }
        if (m.normal_texture >= 0) {
            out.normalTexture.index = m.normal_texture;
            out.normalTexture.scale = m.normal_scale;
            texture_transform(m.normal_transform, out.normalTexture.extensions);
        }
        if (m.thickness != 0.0f || m.attenuation_color != glm::vec3(1.0f) || std::isfinite(m.attenuation_distance)) {
            tinygltf::Value::Object volume{{"thicknessFactor", tinygltf::Value(double(m.thickness))},
                                           {"attenuationColor", numbers(glm::value_ptr(m.attenuation_color), 3)}};
            if (std::isfinite(m.attenuation_distance))   // absent means infinite
                volume["attenuationDistance"] = tinygltf::Value(double(m.attenuation_distance));
            out.extensions["KHR_materials_volume"] = tinygltf::Value(volume);
            use_extension("KHR_materials_volume");
        }
        if (m.metallic_roughness_texture >= 0)
            out.pbrMetallicRoughness.metallicRoughnessTexture.index = m.metallic_roughness_texture;
        if (m.emissive_texture >= 0) out.emissiveTexture.index = m.emissive_texture;
        // emissiveFactor is limited to [0, 1]; larger values go through KHR_materials_emissive_strength.
        const float strength = std::max({m.emissive.r, m.emissive.g, m.emissive.b});
        if (strength > 1.0f) {
            const glm::vec3 e = m.emissive / strength;
            out.emissiveFactor = {e.r, e.g, e.b};
            out.extensions["KHR_materials_emissive_strength"] =
                object({{"emissiveStrength", tinygltf::Value(double(strength))}});
            use_extension("KHR_materials_emissive_strength");
        } else {
            out.emissiveFactor = {m.emissive.r, m.emissive.g, m.emissive.b};
        }
        if (m.alpha_mode != AlphaMode::Opaque) out.alphaMode = m.alpha_mode == AlphaMode::Mask ? "MASK" : "BLEND";
        out.alphaCutoff = m.alpha_cutoff;
        out.doubleSided = m.double_sided;   // which faces of an area light emit
        if (m.transmission != 0.0f) {
            tinygltf::Value::Object transmission{{"transmissionFactor", tinygltf::Value(double(m.transmission))}};
            if (m.transmission_texture >= 0)
                transmission["transmissionTexture"] = object({{"index", tinygltf::Value(m.transmission_texture)}});
            out.extensions["KHR_materials_transmission"] = tinygltf::Value(transmission);
            use_extension("KHR_materials_transmission");
        }
        if (m.ior != 1.5f) {
            out.extensions["KHR_materials_ior"] = object({{"ior", tinygltf::Value(double(m.ior))}});
            use_extension("KHR_materials_ior");
        }
        if (m.specular != 1.0f || m.specular_color != glm::vec3(1.0f)) {
            tinygltf::Value::Array color{tinygltf::Value(double(m.specular_color.r)),
                                         tinygltf::Value(double(m.specular_color.g)),
                                         tinygltf::Value(double(m.specular_color.b))};
            out.extensions["KHR_materials_specular"] = object({{"specularFactor", tinygltf::Value(double(m.specular))},
                                                               {"specularColorFactor", tinygltf::Value(color)}});
            use_extension("KHR_materials_specular");
        }
        return out;
    }

    static tinygltf::Value numbers(const float* v, int n) {
        tinygltf::Value::Array a;
        for (int i = 0; i < n; ++i) a.push_back(tinygltf::Value(double(v[i])));
        return tinygltf::Value(a);
    }

    // KHR_texture_transform on a texture reference, when the transform is not the identity.
    void texture_transform(const TextureTransform& t, tinygltf::ExtensionMap& on) {
        if (t.is_identity()) return;
        on["KHR_texture_transform"] = object({{"offset", numbers(glm::value_ptr(t.offset), 2)},
                                                      {"rotation", tinygltf::Value(double(t.rotation))},
                                                      {"scale", numbers(glm::value_ptr(t.scale), 2)}});
        use_extension("KHR_texture_transform");
    }

    static tinygltf::Value object(std::initializer_list<std::pair<const std::string, tinygltf::Value>> members) {
        return tinygltf::Value(tinygltf::Value::Object(members));
    }

    void texture(const Texture& t, std::size_t index) {
        if (t.width <= 0 || t.height <= 0 || t.rgba8.size() != std::size_t(t.width) * std::size_t(t.height) * 4)
            invalid("texture " + std::to_string(index) + " has inconsistent size and pixel data");
        tinygltf::Image img;
        img.width = t.width;
        img.height = t.height;
        img.component = 4;
        img.bits = 8;
        img.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
        img.image = t.rgba8;
        img.mimeType = "image/png";   // tinygltf encodes it as an embedded PNG data URI
        model.images.push_back(img);
        tinygltf::Sampler s;
        s.magFilter = t.nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
        s.minFilter = t.nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
        auto wrap = [](Wrap w) {
            return w == Wrap::ClampToEdge      ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE
                   : w == Wrap::MirroredRepeat ? TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT
                                               : TINYGLTF_TEXTURE_WRAP_REPEAT;
        };
        s.wrapS = wrap(t.wrap_s);
        s.wrapT = wrap(t.wrap_t);
        model.samplers.push_back(s);
        tinygltf::Texture tex;
        tex.name = t.name;
        tex.source = int(model.images.size() - 1);
        tex.sampler = int(model.samplers.size() - 1);
        model.textures.push_back(tex);
    }

    static tinygltf::Camera camera(const Camera& c) {
        tinygltf::Camera out;
        out.name = c.name;
        if (c.projection == Projection::Orthographic) {
            out.type = "orthographic";
            out.orthographic.xmag = c.xmag;
            out.orthographic.ymag = c.ymag;
            out.orthographic.znear = c.znear;
            out.orthographic.zfar = c.zfar;
        } else {
            out.type = "perspective";
            out.perspective.yfov = c.yfov;
            out.perspective.aspectRatio = c.aspect;
            out.perspective.znear = c.znear;
            out.perspective.zfar = c.zfar;
        }
        return out;
    }

    static tinygltf::Light light(const Light& l) {
        tinygltf::Light out;
        out.name = l.name;
        out.type = l.type == LightType::Spot ? "spot" : l.type == LightType::Directional ? "directional" : "point";
        out.color = {l.color.r, l.color.g, l.color.b};
        out.intensity = l.intensity;
        out.range = l.range;
        out.spot.innerConeAngle = l.inner_cone;
        out.spot.outerConeAngle = l.outer_cone;
        return out;
    }

    tinygltf::Node node(const Node& n, std::size_t node_count) {
        tinygltf::Node out;
        out.name = n.name;
        if (n.matrix) {
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) out.matrix.push_back((*n.matrix)[c][r]);
        } else {
            if (n.translation != glm::vec3(0.0f)) out.translation = {n.translation.x, n.translation.y, n.translation.z};
            if (n.rotation != glm::quat(1, 0, 0, 0))
                out.rotation = {n.rotation.x, n.rotation.y, n.rotation.z, n.rotation.w};
            if (n.scale != glm::vec3(1.0f)) out.scale = {n.scale.x, n.scale.y, n.scale.z};
        }
        out.mesh = n.mesh >= 0 && std::size_t(n.mesh) < model.meshes.size() ? n.mesh : -1;
        out.camera = n.camera >= 0 && std::size_t(n.camera) < model.cameras.size() ? n.camera : -1;
        if (n.light >= 0 && std::size_t(n.light) < model.lights.size())
            out.extensions["KHR_lights_punctual"] = object({{"light", tinygltf::Value(n.light)}});
        for (int child : n.children)
            if (child >= 0 && std::size_t(child) < node_count) out.children.push_back(child);
        return out;
    }

    tinygltf::Animation animation(const Animation& a, std::size_t node_count) {
        tinygltf::Animation out;
        out.name = a.name;
        for (const AnimationChannel& c : a.channels) {
            const std::size_t per_key = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
            if (c.times.empty() || c.values.size() != per_key * c.times.size()) continue;
            if (c.node < 0 || std::size_t(c.node) >= node_count) continue;
            tinygltf::AnimationSampler s;
            s.input = add_floats(c.times.data(), c.times.size(), 1, TINYGLTF_TYPE_SCALAR, 0);
            const bool rotation = c.path == AnimationPath::Rotation;
            std::vector<float> values;
            for (const glm::vec4& v : c.values)
                for (int j = 0; j < (rotation ? 4 : 3); ++j) values.push_back(v[j]);
            s.output = add_floats(values.data(), c.values.size(), rotation ? 4 : 3,
                                  rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, 0);
            s.interpolation = c.interpolation == Interpolation::Step          ? "STEP"
                              : c.interpolation == Interpolation::CubicSpline ? "CUBICSPLINE"
                                                                              : "LINEAR";
            out.samplers.push_back(s);
            tinygltf::AnimationChannel ch;
            ch.sampler = int(out.samplers.size() - 1);
            ch.target_node = c.node;
            ch.target_path = c.path == AnimationPath::Translation ? "translation" : rotation ? "rotation" : "scale";
            out.channels.push_back(ch);
        }
        return out;
    }

    void build(const SceneAsset& asset) {
        model.asset.version = "2.0";
        model.asset.generator = "raytracing-course rt_scene";
        model.buffers.emplace_back();
        for (const Material& m : asset.materials) model.materials.push_back(material(m));
        for (std::size_t i = 0; i < asset.textures.size(); ++i) texture(asset.textures[i], i);
        for (tinygltf::Material& m : model.materials)
            if (m.pbrMetallicRoughness.baseColorTexture.index >= int(model.textures.size()))
                m.pbrMetallicRoughness.baseColorTexture.index = -1;
        for (const Mesh& m : asset.meshes) model.meshes.push_back(mesh(m));
        for (const Camera& c : asset.cameras) model.cameras.push_back(camera(c));
        for (const Light& l : asset.lights) model.lights.push_back(light(l));
        for (const Node& n : asset.nodes) model.nodes.push_back(node(n, asset.nodes.size()));
        for (const Animation& a : asset.animations) {
            tinygltf::Animation anim = animation(a, asset.nodes.size());
            if (!anim.channels.empty()) model.animations.push_back(std::move(anim));
        }
        tinygltf::Scene scene;
        scene.name = asset.name;
        for (int root : asset.roots)
            if (root >= 0 && std::size_t(root) < asset.nodes.size()) scene.nodes.push_back(root);
        // Our own extras: the background (only when the scene has one: a file without it gets the default world
        // again when read back) and the ambient model.
        tinygltf::Value::Object extras{{"rt_ambient", tinygltf::Value(std::string(ambient_name(asset.ambient)))}};
        if (asset.has_world)
            extras["rt_background"] = tinygltf::Value(tinygltf::Value::Array{
                tinygltf::Value(double(asset.background.r)), tinygltf::Value(double(asset.background.g)),
                tinygltf::Value(double(asset.background.b))});
        scene.extras = tinygltf::Value(std::move(extras));
        model.scenes.push_back(scene);
        model.defaultScene = 0;
        if (model.buffers[0].data.empty()) model.buffers.clear();
        model.extensionsUsed = extensions;   // tinygltf adds KHR_lights_punctual itself when there are lights
    }
};

}  // namespace

std::string gltf_file_bytes(const SceneAsset& asset, const std::string& path) {
    const std::string prefix = "cannot save scene " + path + ": ";
    const std::string ext = lower_extension(path);
    if (ext != ".gltf" && ext != ".glb")
        throw SceneError(prefix + "unknown extension '" + ext + "' (expected .gltf or .glb)");

    Writer writer;
    try {
        writer.build(asset);
    } catch (const Invalid& e) {
        throw SceneError(prefix + one_line(e.reason));
    }
    // Into memory (buffers and images embedded), so the bytes reach the disk through write_whole_file, which reports
    // a short write: tinygltf's own file writer does not (it once said "exported" with a third of the file written).
    std::ostringstream bytes;
    tinygltf::TinyGLTF gltf;
    bool ok = false;
    try {
        ok = gltf.WriteGltfSceneToStream(&writer.model, bytes, /*prettyPrint=*/true, /*writeBinary=*/ext == ".glb");
    } catch (const std::exception& e) {
        throw SceneError(prefix + one_line(e.what()));
    }
    if (!ok || !bytes || bytes.view().empty()) throw SceneError(prefix + "encoding failed");
    return std::move(bytes).str();
}

void save_gltf(const SceneAsset& asset, const std::string& path) {
    const std::string bytes = gltf_file_bytes(asset, path);
    // Write next to the destination, then rename: the destination is either the old file or the complete new one.
    const fs::path target(path);
    const fs::path temp = target.parent_path() / ("." + target.filename().string() + ".tmp");
    const std::string prefix = "cannot save scene " + path + ": ";
    std::error_code ec;
    try {
        write_whole_file(temp.string(), bytes);
    } catch (const std::runtime_error& e) {
        fs::remove(temp, ec);
        throw SceneError(prefix + e.what());
    }
    fs::rename(temp, target, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        throw SceneError(prefix + ec.message());
    }
}

}  // namespace rt
