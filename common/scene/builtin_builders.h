// Small builders the built-in scene files share (defined in builtin_scenes.cpp): a scene is written the way a glTF
// exporter would lay it out, material by material and mesh by mesh.
#pragma once

#include <string>

#include "scene.h"

namespace rt {

// Appends a material; returns its index.
int add_material(SceneAsset& a, const Material& m);

// A mesh of one primitive under a new root node of the same name; returns the node index.
int add_mesh_node(SceneAsset& a, const std::string& name, Primitive p);

// A quad centred at c spanning c +- u +- v, facing cross(u, v), indexed; uv (0, 0) at c - u + v (top left, v down) to
// (uv_scale, uv_scale) at c + u - v.
Primitive make_quad(const glm::vec3& c, const glm::vec3& u, const glm::vec3& v, float uv_scale, int material);

}  // namespace rt
