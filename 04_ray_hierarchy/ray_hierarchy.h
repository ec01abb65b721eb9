// Stage 04's data structure on the CPU: the ray-space hierarchy of Roger, Assarsson & Holzschuch (2007), "Whitted
// Ray-Tracing for Dynamic Scenes using a Ray-Space Hierarchy on the GPU". Instead of a structure over the triangles,
// a tree is built over the rays of one bounce: each node bounds its rays with a sphere (every origin inside) and a
// cone (every direction inside). A (node, triangle) pair whose cone-swept sphere misses the triangle's bounding
// sphere is dropped for every ray below the node at once.
//
// These are the C++ twins of shaders/rh_common.glsl (the GPU builds and traverses; this file is what the property
// tests and the figure use): the same formulas in the same order, float throughout.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rt {

// --branching: children per node. 4 = 2x2 pixel blocks of the queue's Morton order; 8 and 16 as in Reis's tests.
constexpr int kDefaultBranching = 4;
bool valid_branching(int branching);   // 4, 8 or 16

constexpr float kRhPad = 1e-4f;              // RH_PAD
constexpr float kRhAllDirections = 3.1415f;  // RH_ALL_DIRECTIONS

// 8 floats, as on the GPU (std430 RhNode): centre, radius (< 0: empty); unit axis, spread angle in radians.
struct RhNode {
    glm::vec4 sphere{0.0f, 0.0f, 0.0f, -1.0f};
    glm::vec4 cone{1.0f, 0.0f, 0.0f, 0.0f};
    bool empty() const { return !(sphere.w >= 0.0f); }
};
static_assert(sizeof(RhNode) == 32);

RhNode rh_leaf(glm::vec3 origin, glm::vec3 direction);
RhNode rh_union(const RhNode* children, std::size_t count);
glm::vec4 rh_triangle_sphere(glm::vec3 a, glm::vec3 b, glm::vec3 c);
// The conservative test: false only when no ray of the node can reach the sphere.
bool rh_may_hit(const RhNode& node, glm::vec4 sphere);

// A whole hierarchy over rays (origin, direction pairs): levels[0] are the leaves, levels[l][j] bounds children
// [j * B, (j + 1) * B) of level l - 1. At least one level above the rays, then up to a single root, or `max_levels`
// upper levels when > 0.
struct RhRay {
    glm::vec3 origin, direction;
};
std::vector<std::vector<RhNode>> rh_build(const std::vector<RhRay>& rays, int branching, int max_levels = 0);

// In double, with no padding: does the node hold the ray (origin in the sphere, direction in the cone)? For the
// property tests (every ray lies inside all its ancestors).
bool rh_contains(const RhNode& node, glm::vec3 origin, glm::vec3 direction);

}  // namespace rt
