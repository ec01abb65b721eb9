// The object side of stage 04's traversal: a tree of bounding spheres over the triangles, rebuilt every frame, so
// that the ray hierarchy's nodes meet a few object nodes instead of every triangle. Roger et al. (2007) test the top
// ray nodes against every triangle; Reis ("Exploring Ray-Space Hierarchy", closing section) names the way out: an
// object-space hierarchy beside the ray-space one. The build is LBVH-style and cheap enough for every frame:
//
//   1. Morton code of each triangle's sphere centre in a grid of cubic cells over the scene box (10 bits per axis);
//   2. the triangles sorted by code (the shared radix sort on the GPU; stable, so equal codes keep id order);
//   3. level 1: clusters of up to kClusterSize consecutive sorted triangles; level l > 1: nodes bounding up to
//      B = kObjectBranching consecutive nodes of level l - 1, up to a single root. The groups follow the codes'
//      prefixes (group_heads below: the largest subtrees of at most B nodes of the binary radix tree the sorted codes
//      define, Karras 2012), so a node never spans a jump of the Morton curve: a group of any B consecutive nodes
//      could straddle two distant stretches of the curve and bound the space between them (04's README, "The object
//      tree"; docs/benchmarks.md, "Stage 04: where the node tests go").
//
// The traversal then works on pairs (ray node, object node): a pair whose cone-swept sphere misses the object's
// sphere or box is dropped for every ray and triangle below both; a surviving pair splits one side (see
// rh_split_rays), until (ray, triangle) pairs remain. Those get two cheap per-ray tests (rh_ray_may_hit: the ray
// against the triangle's bounding sphere; rh_ray_box_may_hit: against its box) and only then the exact ray/triangle
// test.
//
// --objects selects the published variants: `triangles` (Roger et al.: the top ray nodes against every triangle),
// `meshes` (runs of one material as objects, each against the top nodes first: Reis's object culling) and `tree`
// (this file; the default). The GPU twin is shaders/ot_build.comp and rh_cull.comp.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "ray_hierarchy.h"

namespace rt {

enum class ObjectMode { triangles, meshes, tree };
const char* object_mode_name(ObjectMode mode);

constexpr std::uint32_t kClusterSize = 4;        // triangles per leaf of the tree, at most
constexpr std::uint32_t kObjectBranching = 4;    // children per node above the leaves, at most
static_assert(kClusterSize == kObjectBranching, "group_heads and ot_build.comp group every level alike");
constexpr unsigned kMortonAxisBits = 10;         // per axis: 2^30 cells

// One object node, as on the GPU (std430 RhObject, 64 bytes). Level 1 nodes bound triangles: order[first + k] for
// k < count (meshes: the identity order). Level l > 1 nodes bound nodes [first, first + count) of level l - 1.
// The sphere bounds the children's spheres (for the cone+sphere test of ray nodes); the box (xyz of box_lo, box_hi;
// unpadded, as rh_ray_box_test pads) bounds the triangles' vertices, for the box test of single rays and ray nodes,
// which is tighter on long or thin clusters. Mesh objects keep the box of all space (the box test keeps every ray).
struct ObjectNode {
    glm::vec4 sphere{0.0f};
    std::uint32_t first = 0, count = 0, level = 1, pad = 0;
    glm::vec4 box_lo{-INFINITY, -INFINITY, -INFINITY, 0.0f}, box_hi{INFINITY, INFINITY, INFINITY, 0.0f};
};
static_assert(sizeof(ObjectNode) == 64);

struct ObjectTree {
    std::vector<std::uint32_t> order;         // triangle ids in the leaves' order (Morton; identity for meshes)
    std::vector<ObjectNode> nodes;            // level 1 first, then each level up; the last level holds the root(s)
    std::vector<std::uint32_t> level_first;   // [l - 1]: index of level l's first node
    std::vector<std::uint32_t> level_count;   // [l - 1]: nodes of level l
    std::uint32_t levels() const { return std::uint32_t(level_count.size()); }
};

// Cells per unit of the cubic Morton grid over the box: 2^10 / (largest extent); 0 for an empty, flat-to-a-point or
// non-finite box (every code is then 0 and the tree is the triangles in id order, still correct).
float morton_scale(glm::vec3 lo, glm::vec3 hi);
// 30-bit Morton code of p (x above y above z at each level), cells clamped to the grid; NaN goes to cell 0.
std::uint32_t morton_code(glm::vec3 p, glm::vec3 lo, float scale);

// How far apart two neighbouring nodes of a level are on the Morton curve, for group_heads: 33..64 when their codes
// differ (32 + the number of the highest bit they differ in, counting from 1), else 1..32 from their positions k and
// k + 1 (equal codes are split as the radix tree splits them, by index; ot_build.comp: ot_strength).
std::uint32_t boundary_strength(std::uint32_t last_code, std::uint32_t next_first_code, std::uint32_t k);
// The groups of one level: the first node of each (in order, from 0) of the nodes whose codes span
// [first_code[i], last_code[i]], sorted. A boundary is cut when the subtree of the strengths' Cartesian tree it
// splits (ties to the left) holds more than kObjectBranching nodes; a level the rule would not at least halve is
// grouped every kObjectBranching nodes instead (codes spaced by powers of two would otherwise split off one node a
// level). Each group has 1 to kObjectBranching nodes.
// every_4: group every kObjectBranching nodes whatever the codes (the build's choice when the worst case of prefix
// groups, a tree of n nodes over n triangles, would not fit the GPU's storage limit: GpuRayHierarchy::build_tree).
std::vector<std::uint32_t> group_heads(const std::vector<std::uint32_t>& first_code,
                                       const std::vector<std::uint32_t>& last_code, bool every_4 = false);

// The sphere bounding spheres s[first + k] (through `order` when given), padded like every bound of the stage.
glm::vec4 sphere_union(const glm::vec4* spheres, std::size_t count);
glm::vec4 sphere_union(const std::vector<glm::vec4>& spheres, const std::uint32_t* order, std::uint32_t first,
                       std::uint32_t count);

// The tree over triangles with these bounding spheres (rh_triangle_sphere), in the scene box [lo, hi]; with the
// triangles' vertices (3 per triangle) the nodes' boxes too, else every box is all space.
ObjectTree build_object_tree(const std::vector<glm::vec4>& triangle_spheres, glm::vec3 lo, glm::vec3 hi,
                             const std::vector<glm::vec3>& triangles = {}, bool every_4 = false);
// `meshes`: one level of objects, runs [first, first + count) of triangles in id order.
ObjectTree mesh_objects(const std::vector<glm::vec4>& triangle_spheres,
                        const std::vector<std::pair<std::uint32_t, std::uint32_t>>& runs);

// The cheap per-ray test before the exact one: can the ray o + t d, 0 < t <= tmax, reach sphere s? rh_may_hit for
// a single ray (spread 0, no trigonometry), plus the ray's length: a sphere farther than tmax |d| is out of reach
// (shadow rays end at their light). Conservative in floats like rh_may_hit; false for a ray that cannot hit
// anything (zero or non-finite direction or origin, as rh_leaf's empty leaf).
bool rh_ray_may_hit(glm::vec3 origin, glm::vec3 direction, float tmax, glm::vec4 sphere);

// The second cheap test, after the sphere's: can the ray o + t d, 0 < t <= tmax, pass through the axis-aligned box of
// triangle (a, b, c)? The slab test (Kay & Kajiya 1986): on each axis the ray is inside the box's slab for t in
// [(lo - o) / d, (hi - o) / d] (ends swapped when d < 0; every t or none when d = 0), and it meets the box when the
// three intervals and (0, tmax] overlap. A sphere is a loose bound for a long, thin or large triangle (its radius is
// half the longest side, whatever the triangle's width); its box is tight for the axis-aligned walls and thin strips
// of real scenes (04's README, "The cheap tests"). The box is padded by RH_PAD of the coordinates' size, the exit by
// RH_PAD relatively, so that a pair the exact test hits is never culled (its rounding is a few ulps). False for a ray
// that cannot hit anything, as rh_ray_may_hit; a NaN tmax keeps the pair.
bool rh_ray_box_may_hit(glm::vec3 origin, glm::vec3 direction, float tmax, glm::vec3 a, glm::vec3 b, glm::vec3 c);
// The same against the box [lo, hi] (an object node's). Padded by the box's own size, so a node's test keeps every
// ray its triangles' tests keep: the box holds theirs, and every step of the test is monotone in the box.
bool rh_ray_box_test(glm::vec3 origin, glm::vec3 direction, float tmax, glm::vec3 lo, glm::vec3 hi);

// The same for every ray of a ray node at once (rh_common.glsl: rh_node_box_test): can some ray o + t d, t >= 0, of
// the node (origin in its sphere, direction in its cone) pass through the box [lo, hi]? The slab test in interval
// arithmetic: on each axis the origins' coordinate lies in [c - r, c + r] and the unit directions' in the range of
// cos(angle to the axis) over the cone, so the rays' points at t lie in an interval that meets the slab for t in a
// half-line or two; the box is out of reach when the axes' t ranges do not overlap. After the cone+sphere test in
// --box-test on: the box of a large or thin triangle is far tighter than its sphere. Padded as rh_ray_box_test, the
// direction bounds by kRhPad (they hold the GPU's sin and cos too); false for an empty node, true for one of every
// direction. The GLSL twin computes the same bounds with the GPU's sin and cos, so the two may differ on a pair
// within the padding; both keep every pair whose rays can hit.
bool rh_node_box_test(const RhNode& node, glm::vec3 lo, glm::vec3 hi);

// Which side of a surviving (ray node, object node) pair to split in `tree` mode: the rays when their beam is wider
// than kSplitRaysWidth of the object node's radius where it meets it (beam: sphere radius + distance x sin(spread);
// every direction: always), else the object node. Either choice is exact; a dual-tree traversal keeps both sides of
// a pair about the same size (a factor of 1). A quarter splits the rays sooner, while their beam is still narrower
// than the object: single rays then meet the object nodes with their own tests, which know each ray's length (a
// shadow ray ends at its light) and line, where a node knows neither (04's README, "The split rule", measures it on
// the 25 scenes of scripts/bench).
constexpr float kSplitRaysWidth = 0.25f;
bool rh_split_rays(const RhNode& node, glm::vec4 object_sphere);

// The whole pair traversal on the CPU, for the property tests: every (ray, triangle) pair that reaches the exact test,
// given the ray hierarchy's levels (rh_build) and, for meshes and tree, the object tree. Counts as the GPU's stats.
struct RhTraceRay {
    glm::vec3 origin, direction;
    float tmax = INFINITY;
};
struct PairTraversal {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> exact;   // (ray, triangle) pairs given the exact test
    std::uint64_t node_tests = 0;     // tests of (ray node or ray, object node or triangle) pairs (sphere, box)
    std::uint64_t sphere_tests = 0;   // rh_ray_may_hit tests of (ray, triangle) pairs
    std::uint64_t box_tests = 0;      // rh_ray_box_may_hit tests of the pairs that passed the sphere's
};
// `triangles` (3 vertices each): given, the box tests too (--box-test on): a ray node against a triangle's or object
// node's box after its sphere, a single ray against an object node's, a (ray, triangle) pair that passes the sphere
// test against the triangle's box.
PairTraversal traverse_pairs(const std::vector<RhTraceRay>& rays, const std::vector<std::vector<RhNode>>& levels,
                             int branching, const std::vector<glm::vec4>& triangle_spheres, const ObjectTree& tree,
                             ObjectMode mode, const std::vector<glm::vec3>& triangles = {});

}  // namespace rt
