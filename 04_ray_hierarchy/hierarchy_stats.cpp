#include "hierarchy_stats.h"

namespace rt {

std::uint64_t HierarchyKindStats::node_tests() const {
    std::uint64_t n = 0;
    for (const HierarchyLevelStats& l : levels) n += l.pairs_in;
    return n - leaf_pairs;
}

void to_json(nlohmann::json& out, const HierarchyFrameStats& f) {
    const HierarchyOptions& o = f.options;
    const bool tree = o.objects == ObjectMode::tree;
    out = {{"branching", o.branching},
           {"levels_limit", o.levels},
           {"objects", object_mode_name(o.objects)},
           {"sphere_test", o.sphere_test},
           {"box_test", o.box_test},
           {"object_tree",
            {{"levels", f.object_levels},
             {"nodes", f.object_nodes},
             {"cluster_size", tree ? kClusterSize : 0u},
             {"branching", tree ? kObjectBranching : 0u}}},
           {"gpu_cpu_syncs", f.gpu_cpu_syncs},
           {"traced", f.traced},
           {"pair_capacity", f.pair_capacity},
           {"chunks", f.chunks},
           {"windows", f.windows},
           {"groups_retraced", f.groups_retraced},
           {"fold_rounds", f.fold_rounds},
           {"hit_list_prunes", f.hit_list_prunes}};
    nlohmann::json kinds = nlohmann::json::object();
    for (int k = 1; k < kRayKinds; ++k) {
        const HierarchyKindStats& s = f.kinds[std::size_t(k)];
        if (s.rays == 0) continue;
        nlohmann::json levels = nlohmann::json::array();
        for (std::size_t l = 0; l < s.levels.size(); ++l) {
            const HierarchyLevelStats& L = s.levels[l];
            levels.push_back({{"level", l}, {"nodes", L.nodes}, {"pairs_in", L.pairs_in}, {"pairs_out", L.pairs_out}});
        }
        const std::uint64_t tests = s.local_tests + s.fold_tests;
        const HierarchyKindTimes& t = f.times[std::size_t(k)];
        kinds[ray_kind_name(RayKind(k))] = {
            {"rays", s.rays},
            {"groups", s.groups},
            {"levels", levels},
            {"object_level", {{"pairs_in", s.object_pairs_in}, {"pairs_out", s.object_pairs_out}}},
            {"node_tests", s.node_tests()},
            {"leaf_pairs", s.leaf_pairs},
            {"sphere_tests", s.sphere_tests},
            {"box_tests", s.box_tests},
            {"local_tests", s.local_tests},
            {"fold_tests", s.fold_tests},
            {"tests_per_ray", double(tests) / double(s.rays)},
            {"node_tests_per_ray", double(s.node_tests()) / double(s.rays)},
            {"brute_force_tests", s.brute_force_tests},
            {"percent_of_brute_force",
             s.brute_force_tests ? 100.0 * double(tests) / double(s.brute_force_tests) : 0.0},
            {"time_ms", {{"build", t.build}, {"traverse", t.traverse}, {"local_tests", t.local_tests}}}};
    }
    out["kinds"] = kinds;
    out["fold_ms"] = f.fold_ms;
}

}  // namespace rt
