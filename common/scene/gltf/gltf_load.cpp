// glTF 2.0 import through tinygltf. Everything read from a file is validated before use (accessor ranges, indices,
// references between objects), so a malformed file gives a SceneError, never a crash. This file: load_gltf, and the
// Loader's geometry, cameras, lights, nodes, animations and scene (gltf_loader.h; materials and textures are in
// gltf_load_materials.cpp, JSON values and accessors in gltf_read.cpp).
#include "gltf_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numeric>
#include <string_view>
#include <system_error>

#include <tiny_gltf.h>

#include "gltf_common.h"
#include "gltf_files.h"
#include "gltf_loader.h"
#include "gltf_validate.h"

namespace rt {

namespace gltf_detail {

namespace {

// A triangle strip's or fan's vertices as the triangle list they stand for (glTF 2.0, 3.7.2.1, "Topology Types"):
// strip triangle i is {v_i, v_(i+1+i%2), v_(i+2-i%2)}, which keeps every triangle's winding; fan triangle i is
// {v_(i+1), v_(i+2), v_0}.
std::vector<std::uint32_t> triangle_list(const std::vector<std::uint32_t>& v, int mode) {
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i + 2 < v.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
            out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
        else
            out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
    }
    return out;
}

}  // namespace

Primitive Loader::primitive(const tinygltf::Primitive& p, int mode, const std::vector<double>& weights,
                            const std::string& name) {
    Primitive out;
    check_index(p.material, model.materials.size(), name + ": material");
    out.material = p.material;
    auto attribute = [&](const char* key) {
        auto it = p.attributes.find(key);
        return it == p.attributes.end() ? -1 : it->second;
    };
    // KHR_mesh_quantization: positions and texture coordinates of any integer type, normals and tangents of
    // normalized ones (its table of types; a node's transform usually scales them back).
    const bool quantized = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(),
                                     "KHR_mesh_quantization") != model.extensionsUsed.end();
    const Integers any = quantized ? Integers::Any : Integers::None;
    const Integers signed_normalized = quantized ? Integers::Normalized : Integers::None;
    const int position = attribute("POSITION");
    if (position < 0) invalid(name + ": no POSITION attribute");
    for (const glm::vec4& v : read_vectors(model, budget(position, name), 3, any, name + " POSITION"))
        out.positions.push_back(glm::vec3(v));
    const std::size_t nv = out.positions.size();
    // An attribute (of the primitive, or of a morph target: `where`) whose count is not the primitive's positions':
    // both named, with both counts.
    const auto counts_differ = [&](const std::string& where, const std::string& key, std::size_t count) {
        invalid(where + ": " + key + " has " + std::to_string(count) + " entries but " +
                (where == name ? "POSITION" : "the primitive's POSITION") + " has " + std::to_string(nv));
    };

    if (const int normal = attribute("NORMAL"); normal >= 0) {
        for (const glm::vec4& v : read_vectors(model, budget(normal, name), 3, signed_normalized, name + " NORMAL"))
            out.normals.push_back(glm::vec3(v));
        if (out.normals.size() != nv) counts_differ(name, "NORMAL", out.normals.size());
    }
    if (const int uv = attribute("TEXCOORD_0"); uv >= 0) {
        const Integers uv_integers = quantized ? Integers::Any : Integers::Normalized;
        for (const glm::vec4& v : read_vectors(model, budget(uv, name), 2, uv_integers, name + " TEXCOORD_0"))
            out.uvs.push_back(glm::vec2(v));
        if (out.uvs.size() != nv) counts_differ(name, "TEXCOORD_0", out.uvs.size());
    }
    if (const int tangent = attribute("TANGENT"); tangent >= 0) {
        out.tangents = read_vectors(model, budget(tangent, name), 4, signed_normalized, name + " TANGENT");
        if (out.tangents.size() != nv) counts_differ(name, "TANGENT", out.tangents.size());
    }
    // Morph targets at the mesh's default weights (glTF 2.0, 3.7.2.2): each target's POSITION, NORMAL and TANGENT
    // displacements, times its weight, add to the base (flatten normalizes the normals). A weight of 0, the default,
    // adds nothing; animated weights are not read (Loader::animation warns).
    for (std::size_t k = 0; k < p.targets.size(); ++k) {
        const std::string target = name + " target " + std::to_string(k);
        const float w = k < weights.size() ? value(weights[k], name + " weight " + std::to_string(k)) : 0.0f;
        if (w == 0.0f) continue;
        auto displace = [&](const char* key, int components, auto& base) {
            auto it = p.targets[k].find(key);
            if (it == p.targets[k].end() || base.empty()) return;
            const std::vector<glm::vec4> d = read_vectors(model, budget(it->second, target), components,
                                                          quantized ? Integers::Normalized : Integers::None,
                                                          target + " " + key);
            if (d.size() != nv) counts_differ(target, key, d.size());
            for (std::size_t i = 0; i < nv; ++i)
                for (int c = 0; c < 3; ++c) base[i][c] += w * d[i][c];
        };
        displace("POSITION", 3, out.positions);
        displace("NORMAL", 3, out.normals);
        displace("TANGENT", 3, out.tangents);   // xyz only: a target's tangents carry no handedness
    }
    if (const int color = attribute("COLOR_0"); color >= 0) {
        // Linear RGB or RGBA, float or normalized unsigned byte or short (glTF 2.0, 3.7.2.1); RGB has alpha 1.
        const tinygltf::Accessor* a = std::size_t(color) < model.accessors.size() ? &model.accessors[std::size_t(color)]
                                                                                  : nullptr;
        const int components = a && a->type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
        for (const glm::vec4& c : read_vectors(model, budget(color, name), components, Integers::Normalized,
                                               name + " COLOR_0"))
            out.colors.push_back(components == 3 ? glm::vec4(glm::vec3(c), 1.0f) : c);
        if (out.colors.size() != nv) counts_differ(name, "COLOR_0", out.colors.size());
        // Values from files (docs/shading.md): one that is not finite is refused, one outside [0, 1] clamped.
        bool clamped = false;
        for (glm::vec4& c : out.colors) {
            if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(c.w))
                invalid(name + ": COLOR_0 holds a value that is not finite");
            const glm::vec4 in = c;
            c = glm::clamp(c, 0.0f, 1.0f);
            clamped = clamped || c != in;
        }
        if (clamped) warn(name + ": COLOR_0 values outside [0, 1]; clamped");
    }
    if (p.indices >= 0) {
        out.indices = read_indices(model, budget(p.indices, name), name + " indices");
        for (std::uint32_t i : out.indices)
            if (i >= nv)
                invalid(name + ": index " + std::to_string(i) + " out of range (" + std::to_string(nv) +
                        " vertices)");
    }
    if (mode != TINYGLTF_MODE_TRIANGLES) {   // a strip or a fan, over its indices or its vertices in order
        if (p.indices < 0) {
            out.indices.resize(nv);
            std::iota(out.indices.begin(), out.indices.end(), 0u);
        }
        out.indices = triangle_list(out.indices, mode);
    } else if (p.indices >= 0) {
        if (out.indices.size() % 3 != 0) {
            warn(name + ": index count is not a multiple of 3; the rest is ignored");
            out.indices.resize(out.indices.size() / 3 * 3);
        }
    } else if (nv % 3 != 0) {
        warn(name + ": vertex count is not a multiple of 3; the rest is ignored");
    }
    // Indices that make no triangle (fewer than 3, or a strip or fan of fewer than 3 vertices): the primitive has
    // none. Empty indices would read as "not indexed", and flatten would make triangles of the vertices in order.
    if (out.indices.empty() && (p.indices >= 0 || mode != TINYGLTF_MODE_TRIANGLES)) {
        out.positions.clear();
        out.normals.clear();
        out.uvs.clear();
        out.tangents.clear();
        out.colors.clear();
    }
    return out;
}


Mesh Loader::mesh(const tinygltf::Mesh& m, std::size_t index) {
    Mesh out;
    out.name = m.name;
    for (std::size_t i = 0; i < m.primitives.size(); ++i) {
        const tinygltf::Primitive& p = m.primitives[i];
        const std::string name = "mesh " + std::to_string(index) + " primitive " + std::to_string(i);
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            warn(name + ": mode " + std::to_string(mode) +
                 (mode >= 0 && mode < TINYGLTF_MODE_TRIANGLES ? " is points or lines" : " is not a glTF mode") +
                 ", not triangles; skipped");
            continue;
        }
        out.primitives.push_back(primitive(p, mode, m.weights, name));
    }
    return out;
}


Camera Loader::camera(const tinygltf::Camera& c, std::size_t index) {
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


Light Loader::light(const tinygltf::Light& l, std::size_t index) {
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
    // KHR_lights_punctual: the inner cone lies inside the outer one. Not so, the falloff between them has no width;
    // the inner angle becomes the float just below the outer one (a hard edge at the outer cone, and a valid cone
    // when the scene is exported).
    if (out.type == LightType::Spot && out.inner_cone >= out.outer_cone && out.inner_cone > 0.0f) {
        warn(name + ": innerConeAngle " + describe(out.inner_cone) + " is not below outerConeAngle " +
             describe(out.outer_cone) + "; the spot's edge is hard at the outer cone");
        out.inner_cone = std::nextafter(out.outer_cone, 0.0f);
    }
    return out;
}


Node Loader::node(const tinygltf::Node& n, std::size_t index) {
    Node out;
    out.name = n.name;
    const std::string name = "node " + std::to_string(index);
    if (n.matrix.size() == 16) {
        glm::mat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)   // column-major
                m[c][r] = value(n.matrix[std::size_t(4 * c + r)], name + ": matrix");
        out.matrix = m;
        // glTF 2.0, 5.25: a matrix is a translation, rotation and scale, its last row 0, 0, 0, 1.
        if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f)
            warn(name + ": matrix's last row is not 0, 0, 0, 1 (a projection); read as if it were");
    } else {
        out.translation = values<3>(n.translation, name + ": translation", glm::vec3(0.0f));
        out.scale = values<3>(n.scale, name + ": scale", glm::vec3(1.0f));
        if (n.rotation.size() == 4) {   // glTF stores x, y, z, w
            const glm::quat q(value(n.rotation[3], name + ": rotation"), value(n.rotation[0], name + ": rotation"),
                              value(n.rotation[1], name + ": rotation"), value(n.rotation[2], name + ": rotation"));
            // glTF 2.0, 5.25: a unit quaternion. mat4_cast of any other turns and scales unevenly ([1, 0, 0, 1] made
            // the box a flat sliver), so one of another length is normalized (as animated rotations are); files
            // written with float rounding stay as they are, and a zero quaternion is no rotation at all.
            const glm::dvec4 xyzw(q.x, q.y, q.z, q.w);
            const double length = glm::length(xyzw);
            if (!(length > 0.0))
                invalid(name + ": rotation has length 0, not a unit quaternion");
            out.rotation = q;
            if (std::abs(length - 1.0) > 1e-3) {
                warn(name + ": rotation has length " + describe(length) + ", not 1; normalized");
                const glm::dvec4 unit = xyzw / length;
                out.rotation = glm::quat(float(unit.w), float(unit.x), float(unit.y), float(unit.z));
            }
        }
    }
    check_index(n.mesh, model.meshes.size(), name + ": mesh");
    check_index(n.camera, model.cameras.size(), name + ": camera");
    if (n.mesh >= 0 && !n.weights.empty() && n.weights != model.meshes[std::size_t(n.mesh)].weights)
        warn(name + ": its own morph target weights are not read; its mesh is shaped by the mesh's weights");
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


Animation Loader::animation(const tinygltf::Animation& a, std::size_t index, const std::vector<Node>& nodes) {
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

        for (const glm::vec4& t : read_vectors(model, budget(s.input, name), 1, Integers::None, name + " input"))
            c.times.push_back(t.x);
        for (std::size_t k = 0; k < c.times.size(); ++k)
            if (!std::isfinite(c.times[k]) || (k > 0 && c.times[k] < c.times[k - 1]))
                invalid(name + ": key times must be finite and increasing");
        const int comps = c.path == AnimationPath::Rotation ? 4 : 3;
        c.values = read_vectors(model, budget(s.output, name), comps,
                                c.path == AnimationPath::Rotation ? Integers::Normalized : Integers::None,
                                name + " output");
        for (const glm::vec4& v : c.values)
            if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w))
                invalid(name + ": output values must be finite");
        const std::size_t per_key = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
        if (c.values.size() != per_key * c.times.size()) invalid(name + ": input and output counts do not match");
        // A rotation key is normalized where it is sampled (scene.cpp), but a zero one is no rotation at all (as for a
        // node's rotation, above); a cubic spline's tangents (keys 3k and 3k + 2) may be zero.
        if (c.path == AnimationPath::Rotation)
            for (std::size_t k = 0; k < c.times.size(); ++k)
                if (c.values[per_key * k + (per_key == 3 ? 1 : 0)] == glm::vec4(0.0f))
                    invalid(name + ": rotation key " + std::to_string(k) + " has length 0, not a unit quaternion");
        if (c.times.empty()) continue;
        out.channels.push_back(std::move(c));
    }
    return out;
}


SceneAsset Loader::asset() {
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

}  // namespace gltf_detail

namespace fs = std::filesystem;
using namespace gltf_detail;

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
    const std::string base_dir = fs::path(path).parent_path().string();
    reads.base_dir = base_dir;
    tinygltf::TinyGLTF gltf;
    gltf.SetFsCallbacks(regular_file_callbacks(reads));
    gltf.SetImageLoader(load_image_within_limits, &reads);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
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
