#include "scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "area_lights.h"
#include "effects.h"
#include "tangents.h"

namespace rt {

glm::mat4 Node::local_transform() const {
    if (matrix) return *matrix;
    // glTF 2.0, 3.5.3 "Transformations": M = T * R * S.
    return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) * glm::scale(glm::mat4(1.0f), scale);
}

float Animation::duration() const {
    float end = 0.0f;
    for (const AnimationChannel& c : channels)
        if (!c.times.empty() && std::isfinite(c.times.back())) end = std::max(end, c.times.back());
    return end;
}

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::quat to_quat(const glm::vec4& xyzw) { return glm::quat(xyzw.w, xyzw.x, xyzw.y, xyzw.z); }

// Samples one channel at time t (clamped to the channel's key range). glTF 2.0, Appendix C "Animation Sampler
// Interpolation Modes". Returns false for a channel whose arrays do not match (nothing is applied then).
bool sample_channel(const AnimationChannel& c, float t, glm::vec4& out) {
    const std::size_t n = c.times.size();
    const bool cubic = c.interpolation == Interpolation::CubicSpline;
    if (n == 0 || c.values.size() != (cubic ? 3 * n : n)) return false;
    // Value of key k (CUBICSPLINE stores in-tangent, value, out-tangent per key).
    auto value = [&](std::size_t k) { return cubic ? c.values[3 * k + 1] : c.values[k]; };
    const bool rotation = c.path == AnimationPath::Rotation;

    if (!(t > c.times.front())) { out = value(0); return true; }   // also catches NaN t
    if (t >= c.times.back()) { out = value(n - 1); return true; }
    // Key interval [k, k+1] with times[k] <= t < times[k+1].
    const std::size_t k = std::size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
    const float t0 = c.times[k], t1 = c.times[k + 1];
    const float dt = t1 - t0;
    if (!(dt > 0.0f)) { out = value(k); return true; }
    const float s = (t - t0) / dt;

    switch (c.interpolation) {
    case Interpolation::Step:
        out = value(k);
        return true;
    case Interpolation::Linear:
        if (rotation) {
            // Spherical linear interpolation along the shorter arc (glm::slerp flips the sign when needed).
            const glm::quat q = glm::slerp(to_quat(value(k)), to_quat(value(k + 1)), s);
            out = glm::vec4(q.x, q.y, q.z, q.w);
        } else {
            out = glm::mix(value(k), value(k + 1), s);
        }
        return true;
    case Interpolation::CubicSpline: {
        // Cubic Hermite spline, with b_k the out-tangent of key k and a_k+1 the in-tangent of key k+1:
        //   p(s) = (2s^3 - 3s^2 + 1) v_k + dt (s^3 - 2s^2 + s) b_k + (-2s^3 + 3s^2) v_k+1 + dt (s^3 - s^2) a_k+1
        const float s2 = s * s, s3 = s2 * s;
        const glm::vec4 v0 = c.values[3 * k + 1], b0 = c.values[3 * k + 2];
        const glm::vec4 v1 = c.values[3 * (k + 1) + 1], a1 = c.values[3 * (k + 1)];
        out = (2 * s3 - 3 * s2 + 1) * v0 + dt * (s3 - 2 * s2 + s) * b0 + (-2 * s3 + 3 * s2) * v1 + dt * (s3 - s2) * a1;
        if (rotation) {
            const float len = glm::length(out);
            if (len > 0.0f) out /= len;
        }
        return true;
    }
    }
    return false;
}

// The nodes with every animation applied at time t. Channels on nodes that carry a matrix are ignored (glTF forbids
// animating such nodes).
std::vector<Node> animated_nodes(const SceneAsset& asset, float t) {
    std::vector<Node> nodes = asset.nodes;
    for (const Animation& a : asset.animations) {
        for (const AnimationChannel& c : a.channels) {
            if (c.node < 0 || std::size_t(c.node) >= nodes.size()) continue;
            Node& node = nodes[std::size_t(c.node)];
            if (node.matrix) continue;
            glm::vec4 v;
            if (!sample_channel(c, t, v)) continue;
            switch (c.path) {
            case AnimationPath::Translation: node.translation = glm::vec3(v); break;
            case AnimationPath::Scale: node.scale = glm::vec3(v); break;
            case AnimationPath::Rotation: {
                const glm::quat q = to_quat(v);
                const float len = glm::length(q);
                if (len > 0.0f && std::isfinite(len)) node.rotation = q / len;
                break;
            }
            }
        }
    }
    return nodes;
}

// One visited node: its index and world matrix, in depth-first (pre-)order from the roots.
struct WorldNode {
    int index;
    glm::mat4 world;
};

// Iterative (an explicit stack, not recursion), so a chain of nodes any number of levels deep cannot overflow the
// call stack; children are pushed in reverse so they are visited in their listed order.
std::vector<WorldNode> walk_hierarchy(const SceneAsset& asset, const std::vector<Node>& nodes) {
    std::vector<WorldNode> out;
    std::vector<bool> visited(nodes.size(), false);   // guards against cycles and shared children in a bad asset
    std::vector<WorldNode> pending;                   // (node, parent's world matrix) still to visit
    for (auto root = asset.roots.rbegin(); root != asset.roots.rend(); ++root)
        pending.push_back({*root, glm::mat4(1.0f)});
    while (!pending.empty()) {
        const auto [i, parent] = pending.back();
        pending.pop_back();
        if (i < 0 || std::size_t(i) >= nodes.size() || visited[std::size_t(i)]) continue;
        visited[std::size_t(i)] = true;
        const Node& node = nodes[std::size_t(i)];
        const glm::mat4 world = parent * node.local_transform();
        out.push_back({i, world});
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
            pending.push_back({*child, world});
    }
    return out;
}

// Triangles a mesh contributes per instance (whole triangles only, as flatten reads them).
std::uint64_t mesh_triangles(const Mesh& mesh) {
    std::uint64_t n = 0;
    for (const Primitive& p : mesh.primitives) n += (p.indices.empty() ? p.positions.size() : p.indices.size()) / 3;
    return n;
}

// Triangles of the whole frame (instances x mesh triangles), counted before anything is allocated for them.
std::uint64_t count_triangles(const SceneAsset& asset, const std::vector<Node>& nodes,
                              const std::vector<WorldNode>& order) {
    std::vector<std::uint64_t> per_mesh(asset.meshes.size());
    for (std::size_t m = 0; m < asset.meshes.size(); ++m) per_mesh[m] = mesh_triangles(asset.meshes[m]);
    std::uint64_t total = 0;
    for (const WorldNode& wn : order) {
        const int mesh = nodes[std::size_t(wn.index)].mesh;
        if (mesh >= 0 && std::size_t(mesh) < per_mesh.size()) total += per_mesh[std::size_t(mesh)];
    }
    return total;
}

// Unit vector or the fallback when v is zero or not finite.
glm::vec3 safe_normalize(const glm::vec3& v, const glm::vec3& fallback) {
    const float len = glm::length(v);
    if (!(len > 0.0f) || !std::isfinite(len)) return fallback;
    const glm::vec3 n = v / len;
    return finite(n) ? n : fallback;
}

// How an error names the scene: by its file (a glTF file's first input file), else by its name (a built-in scene).
std::string scene_label(const SceneAsset& asset) {
    return "scene " + (asset.input_files.empty() ? asset.name : asset.input_files.front());
}

// Camera frame from a node's world matrix: glTF cameras look down local -Z with +Y up (glTF 2.0, 3.10.1). Scale is
// removed by normalizing; a shear is removed by Gram-Schmidt (forward wins, then up).
void place_camera(Camera& cam, const glm::mat4& world) {
    cam.position = glm::vec3(world[3]);
    cam.forward = safe_normalize(-glm::vec3(world[2]), glm::vec3(0, 0, -1));
    glm::vec3 up = glm::vec3(world[1]);
    up = safe_normalize(up - glm::dot(up, cam.forward) * cam.forward, glm::vec3(0));
    if (up == glm::vec3(0)) {   // degenerate: pick any up orthogonal to forward
        const glm::vec3 helper = std::abs(cam.forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        up = glm::normalize(helper - glm::dot(helper, cam.forward) * cam.forward);
    }
    cam.up = up;
    cam.right = glm::normalize(glm::cross(cam.forward, cam.up));
}

// Whether a triangle of the frame uses a material with a normal map: only then are tangents flattened.
bool frame_uses_normal_maps(const SceneAsset& asset, const std::vector<Node>& nodes,
                            const std::vector<WorldNode>& order, const std::vector<Material>& materials,
                            std::size_t texture_count) {
    for (const WorldNode& wn : order) {
        const int mesh = nodes[std::size_t(wn.index)].mesh;
        if (mesh < 0 || std::size_t(mesh) >= asset.meshes.size()) continue;
        for (const Primitive& prim : asset.meshes[std::size_t(mesh)].primitives)
            if (prim.material >= 0 && std::size_t(prim.material) < materials.size() && !prim.positions.empty() &&
                material_has_normal_map(materials[std::size_t(prim.material)], texture_count))
                return true;
    }
    return false;
}

// A tangent carried to world space: its direction like an edge (the upper 3x3 of the matrix), its handedness
// flipped by a mirroring matrix (cross(M n', M t) changes sign with det M). Zero when the result is not usable.
glm::vec4 world_tangent(const glm::mat3& m, bool mirrors, const glm::vec4& t) {
    const glm::vec3 xyz = safe_normalize(m * glm::vec3(t), glm::vec3(0.0f));
    return glm::vec4(xyz, (t.w < 0.0f) != mirrors ? -1.0f : 1.0f);
}

}  // namespace

std::string working_range_problem(const Bounds& bounds) {
    if (bounds.empty()) return {};
    double extent = 0.0, reach = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double d = double(bounds.hi[k]) - double(bounds.lo[k]);
        extent += d * d;
        reach = std::max({reach, std::fabs(double(bounds.lo[k])), std::fabs(double(bounds.hi[k]))});
    }
    extent = std::sqrt(extent);
    char line[256];
    if (extent > kMaxSceneExtent || reach > kMaxSceneExtent)
        std::snprintf(line, sizeof line, "the scene reaches %.3g units from the origin and is %.3g across: beyond %.0e, "
                      "float ray/triangle tests overflow and geometry goes missing (README, \"Working range\")",
                      reach, extent, kMaxSceneExtent);
    else if (extent < kMinSceneExtent)
        std::snprintf(line, sizeof line, "the scene is %.3g units across: below %.0e, float ray/triangle tests "
                      "underflow and geometry goes missing (README, \"Working range\")", extent, kMinSceneExtent);
    else
        return {};
    return line;
}

Scene flatten(const SceneAsset& asset, const FlattenOptions& options, std::size_t* dropped_triangles) {
    Scene scene;
    scene.name = asset.name;
    scene.animated = !asset.animations.empty();
    scene.background = glm::clamp(asset.background, glm::vec3(0.0f), glm::vec3(kMaxRadiance));
    scene.ambient = asset.ambient;
    scene.materials = asset.materials;
    scene.textures = asset.textures;
    for (Material& m : scene.materials)
        for (int* t : {&m.base_color_texture, &m.metallic_roughness_texture, &m.emissive_texture,
                       &m.transmission_texture, &m.normal_texture})
            if (*t >= int(scene.textures.size())) *t = -1;
    std::size_t dropped = 0;
    int default_material = -1;   // index of the appended glTF default material, once needed

    const std::vector<Node> nodes = animated_nodes(asset, options.time);
    const std::vector<WorldNode> order = walk_hierarchy(asset, nodes);
    const std::uint64_t triangles = count_triangles(asset, nodes, order);
    if (triangles > options.max_triangles)
        throw SceneError(scene_label(asset) + " has " + std::to_string(triangles) +
                         " triangles (instances x mesh triangles), more than the limit of " +
                         std::to_string(options.max_triangles) + " (--max-triangles raises it)");
    scene.positions.reserve(3 * triangles);
    scene.normals.reserve(3 * triangles);
    scene.uvs.reserve(3 * triangles);
    scene.material_ids.reserve(triangles);
    const bool want_tangents = frame_uses_normal_maps(asset, nodes, order, scene.materials, scene.textures.size());
    if (want_tangents) scene.tangents.reserve(3 * triangles);
    bool want_colors = false;   // a primitive of the frame has COLOR_0
    for (const WorldNode& wn : order)
        if (const int mesh = nodes[std::size_t(wn.index)].mesh; mesh >= 0 && std::size_t(mesh) < asset.meshes.size())
            for (const Primitive& prim : asset.meshes[std::size_t(mesh)].primitives)
                want_colors = want_colors || (!prim.colors.empty() && prim.colors.size() == prim.positions.size());
    if (want_colors) scene.colors.reserve(3 * triangles);

    const Camera* chosen_camera = nullptr;
    glm::mat4 camera_world(1.0f);

    for (const WorldNode& wn : order) {
        const Node& node = nodes[std::size_t(wn.index)];
        const glm::mat4& world = wn.world;

        if (!chosen_camera && node.camera >= 0 && std::size_t(node.camera) < asset.cameras.size() &&
            (options.camera < 0 || node.camera == options.camera)) {
            chosen_camera = &asset.cameras[std::size_t(node.camera)];
            camera_world = world;
        }

        if (node.light >= 0 && std::size_t(node.light) < asset.lights.size()) {
            Light light = asset.lights[std::size_t(node.light)];
            light.position = glm::vec3(world[3]);
            light.direction = safe_normalize(-glm::vec3(world[2]), glm::vec3(0, 0, -1));
            // A light placed by transforms that overflow a float lights nothing (like a triangle there, dropped).
            if (finite(light.position)) scene.lights.push_back(light);
        }

        if (node.mesh < 0 || std::size_t(node.mesh) >= asset.meshes.size()) continue;
        // Normals transform with the inverse transpose (a mirroring matrix thereby also flips the winding's normal,
        // matching glTF 2.0, 3.7.2.1: a negative determinant reverses the front-face winding).
        const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(world)));
        const bool mirrors = glm::determinant(glm::mat3(world)) < 0.0f;

        const std::vector<Primitive>& primitives = asset.meshes[std::size_t(node.mesh)].primitives;
        for (std::size_t primitive = 0; primitive < primitives.size(); ++primitive) {
            const Primitive& prim = primitives[primitive];
            const std::size_t nv = prim.positions.size();
            const bool has_normals = prim.normals.size() == nv;
            const bool has_uvs = prim.uvs.size() == nv;
            const bool has_colors = prim.colors.size() == nv;
            const std::size_t ni = prim.indices.empty() ? nv : prim.indices.size();

            std::uint32_t material;
            if (prim.material >= 0 && std::size_t(prim.material) < scene.materials.size()) {
                material = std::uint32_t(prim.material);
            } else {
                if (default_material < 0) {
                    default_material = int(scene.materials.size());
                    Material m;
                    m.name = "default";
                    scene.materials.push_back(m);
                }
                material = std::uint32_t(default_material);
            }
            const auto first_triangle = std::uint32_t(scene.material_ids.size());
            std::vector<glm::vec4> tangents;   // the primitive's own, or generated; only for normal-mapped materials
            if (want_tangents && material_has_normal_map(scene.materials[material], scene.textures.size()))
                tangents = primitive_tangents(prim);

            for (std::size_t t = 0; t + 2 < ni; t += 3) {
                std::uint32_t idx[3];
                bool valid = true;
                for (int k = 0; k < 3; ++k) {
                    const std::size_t index_slot = t + std::size_t(k);
                    idx[k] = prim.indices.empty() ? std::uint32_t(index_slot) : prim.indices[index_slot];
                    if (idx[k] >= nv) valid = false;
                }
                if (!valid) { ++dropped; continue; }

                glm::vec3 p[3];
                for (int k = 0; k < 3; ++k) {
                    p[k] = glm::vec3(world * glm::vec4(prim.positions[idx[k]], 1.0f));
                    if (!finite(p[k])) valid = false;
                }
                if (!valid) { ++dropped; continue; }

                // Flat normal from the local-space face, carried to world space like any normal.
                const glm::vec3& l0 = prim.positions[idx[0]];
                const glm::vec3 face = safe_normalize(
                    normal_matrix * glm::cross(prim.positions[idx[1]] - l0, prim.positions[idx[2]] - l0),
                    safe_normalize(glm::cross(p[1] - p[0], p[2] - p[0]), glm::vec3(0, 0, 1)));

                for (int k = 0; k < 3; ++k) {
                    scene.positions.push_back(p[k]);
                    scene.normals.push_back(has_normals ? safe_normalize(normal_matrix * prim.normals[idx[k]], face)
                                                        : face);
                    scene.uvs.push_back(has_uvs ? prim.uvs[idx[k]] : glm::vec2(0.0f));
                    if (want_colors) scene.colors.push_back(has_colors ? prim.colors[idx[k]] : glm::vec4(1.0f));
                    if (want_tangents)
                        scene.tangents.push_back(tangents.empty() ? glm::vec4(0.0f)
                                                                  : world_tangent(glm::mat3(world), mirrors,
                                                                                  tangents[idx[k]]));
                    scene.bounds.add(p[k]);
                }
                scene.material_ids.push_back(material);
            }
            // An emitter the scene is lit by: this primitive's triangles on this node are one area light.
            if (material_is_area_light(scene.materials[material], options.area_lights))
                add_area_light(scene, first_triangle, std::uint32_t(scene.material_ids.size()) - first_triangle,
                               material, "node '" + node.name + "' primitive " + std::to_string(primitive));
        }
    }
    if (scene.light_count() > kMaxLights)
        throw SceneError(scene_label(asset) + " has " + std::to_string(scene.lights.size()) + " lights and " +
                         std::to_string(scene.area_lights.size()) + " area lights, more than the " +
                         std::to_string(kMaxLights) + " a shadow ray can name (--area-lights off leaves the emitters out)");

    if (scene.materials.empty()) {
        Material m;
        m.name = "default";
        scene.materials.push_back(m);
    }

    if (chosen_camera) {
        scene.camera = *chosen_camera;
        // Its node's -Z axis is where it looks; scaled to nothing (a scale of 0) it looks nowhere.
        if (!(glm::length(glm::dvec3(camera_world[2])) > 0.0))
            throw SceneError(scene_label(asset) +
                             ": the camera's node transforms have no -Z axis to look along (a scale of 0)");
        place_camera(scene.camera, camera_world);
        if (!finite(scene.camera.position))
            throw SceneError(scene_label(asset) +
                             ": the camera's transforms overflow a float (its position is not finite)");
    } else if (options.camera >= 0) {
        throw std::out_of_range("the scene has no camera " + std::to_string(options.camera) + " on a node (it has " +
                                std::to_string(asset.cameras.size()) + " cameras)");
    } else {
        scene.camera = default_camera(scene.bounds, options.aspect);
        scene.default_camera = true;
    }

    // No light in the file (most glTF files): the key light goes with the auto-framed camera, which it was placed
    // for (both look at the bounds from the front, above); a camera of the file's own may look from anywhere (from
    // below, into a box, from inside a building), where a light outside the bounds lights nothing it sees: the
    // headlight goes with it.
    if (scene.light_count() == 0 && options.add_default_light) {
        scene.default_headlight = !scene.default_camera;
        scene.lights.push_back(scene.default_headlight ? default_headlight(scene.bounds, scene.camera)
                                                       : default_light(scene.bounds));
        scene.default_light = true;
    }

    if (dropped_triangles) *dropped_triangles = dropped;
    return scene;
}

bool material_is_area_light(const Material& m, AreaLightMode mode) {
    if (mode == AreaLightMode::Off || m.alpha_mode != AlphaMode::Opaque) return false;
    const float radiance = std::max({m.emissive.r, m.emissive.g, m.emissive.b});
    return mode == AreaLightMode::All ? radiance > 0.0f : radiance > kAreaLightMinRadiance;
}

const char* ambient_name(AmbientModel model) {
    switch (model) {
    case AmbientModel::None: return "none";
    case AmbientModel::Constant: return "constant";
    case AmbientModel::Hemisphere: return "hemisphere";
    }
    return "constant";
}

}  // namespace rt
