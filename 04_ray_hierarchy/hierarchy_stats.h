// Stage 04's frame statistics (the "ray_hierarchy" object of --stats): the options the frame ran with, the object
// tree, the GPU's read-backs, and per ray kind what the traversal tested at each level and at the leaves. The
// traversal sums HierarchyKindStats on the GPU; the renderer fills HierarchyFrameStats; to_json writes it
// (nlohmann's conversion hook, found by ADL).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/trace/ray.h"
#include "hierarchy_options.h"

namespace rt {

// Per ray kind (shadow, reflection, refraction): what the traversal did, summed over a frame.
struct HierarchyLevelStats {
    std::uint64_t nodes = 0, pairs_in = 0, pairs_out = 0;   // pairs tested at the level, and those that survived
};
struct HierarchyKindStats {
    std::uint64_t rays = 0, groups = 0;
    std::uint64_t object_pairs_in = 0, object_pairs_out = 0;   // pairs tested whose object side is an object node
    // Per ray level, the pairs tested whose ray side is on it: [0] = single rays (against object nodes and, in
    // sphere tests, triangles), [1..] nodes.
    std::vector<HierarchyLevelStats> levels;
    std::uint64_t leaf_pairs = 0;      // (ray, triangle) pairs that reached the leaves (level 0's pairs_in)
    std::uint64_t sphere_tests = 0;    // the per-ray test of those pairs before the exact one (--sphere-test on)
    std::uint64_t box_tests = 0;       // the second, of the pairs the sphere test kept (--box-test on)
    std::uint64_t local_tests = 0;     // exact ray/triangle tests at the leaves (the pairs that passed both)
    std::uint64_t fold_tests = 0;      // the closest-hit fold's re-tests (rh_closest.glsl)
    std::uint64_t brute_force_tests = 0;   // rays x triangles
    std::uint64_t node_tests() const;   // every pair test of the traversal (sphere, box) but the leaves' pairs
};

struct HierarchyKindTimes {      // ms of the kind's phases (the GPU timer's rh_build.<kind>, ...)
    double build = 0.0, traverse = 0.0, local_tests = 0.0;
};

struct HierarchyFrameStats {
    HierarchyOptions options;
    std::uint32_t object_levels = 0;
    std::size_t object_nodes = 0;
    std::uint64_t gpu_cpu_syncs = 0;
    bool traced = false;            // whether any secondary ray was traced
    std::size_t pair_capacity = 0;
    std::uint64_t chunks = 0, windows = 0, fold_rounds = 0, hit_list_prunes = 0;
    std::uint64_t groups_retraced = 0;   // groups a speculative try could not finish (gpu_ray_hierarchy.h)
    std::array<HierarchyKindStats, kRayKinds> kinds{};   // by RayKind; a kind without rays is left out
    std::array<HierarchyKindTimes, kRayKinds> times{};
    double fold_ms = 0.0;           // the closest-hit fold of reflection and refraction batches together
};

void to_json(nlohmann::json& out, const HierarchyFrameStats& stats);

}  // namespace rt
