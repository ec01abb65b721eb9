// Small builders the built-in scene files share (builtin_builders.cpp): a scene is written the way a glTF exporter
// would lay it out, material by material and mesh by mesh. Internal to rt_scene.
#pragma once

#include <string>

#include <glm/gtc/quaternion.hpp>

#include "common/scene/scene.h"

namespace rt {

// Materials: a white-lit Lambertian surface of `color` (metallic 0, roughness 1), a perfect mirror tinted `color`
// (metallic 1, roughness 0), and clear glass (transmission 1, ior 1.5).
Material diffuse(const std::string& name, glm::vec3 color);
Material mirror(const std::string& name, glm::vec3 color);
Material glass(const std::string& name);
// A matte white surface that emits `radiance` from its front face: brighter than white, an area light
// (docs/shading.md, "Area lights").
Material emitter(const std::string& name, glm::vec3 radiance);

// A mesh of one primitive; returns the mesh index.
int add_mesh(SceneAsset& a, const std::string& name, Primitive p);

// Appends a node (a root when `root`); returns its index.
int add_node(SceneAsset& a, Node n, bool root = true);

// Rotation that turns a glTF camera (looking down -Z, +Y up) to look from eye at target.
glm::quat look_rotation(const glm::vec3& eye, const glm::vec3& target);

// A perspective camera (yfov in degrees) at eye looking at target, and a point light (candela), each on a root node.
void add_camera(SceneAsset& a, const glm::vec3& eye, const glm::vec3& target, float yfov_degrees);
void add_point_light(SceneAsset& a, const glm::vec3& position, float intensity);

// Appends a material; returns its index.
int add_material(SceneAsset& a, const Material& m);

// A mesh of one primitive under a new root node of the same name; returns the node index.
int add_mesh_node(SceneAsset& a, const std::string& name, Primitive p);

// A quad centred at c spanning c +- u +- v, facing cross(u, v), indexed; uv (0, 0) at c - u + v (top left, v down) to
// (uv_scale, uv_scale) at c + u - v.
Primitive make_quad(const glm::vec3& c, const glm::vec3& u, const glm::vec3& v, float uv_scale, int material);

}  // namespace rt
