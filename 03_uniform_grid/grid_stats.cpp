#include "grid_stats.h"

#include <algorithm>

namespace rt {

void count_cell_occupancy(const std::vector<std::uint32_t>& ranges, GridFrameStats& stats) {
    stats.empty_cells = 0;
    stats.max_triangles_per_cell = 0;
    for (std::size_t c = 0; c < stats.cells; ++c) {
        const std::size_t size = ranges[2 * c + 1] - ranges[2 * c];
        stats.empty_cells += size == 0;
        stats.max_triangles_per_cell = std::max(stats.max_triangles_per_cell, size);
    }
}

void to_json(nlohmann::json& out, const GridFrameStats& s) {
    out = {{"built", s.built}, {"primary", s.trace_primary ? "trace" : "raster"},
           {"bounds", "Scene::bounds, from the CPU"}};
    if (!s.built) return;
    auto optional = [](const std::optional<float>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
    const std::size_t non_empty = s.cells - s.empty_cells;
    out["resolution"] = {s.resolution.x, s.resolution.y, s.resolution.z};
    out["lambda"] = optional(s.lambda);
    out["lambda_used"] = optional(s.lambda_used);
    out["cells"] = s.cells;
    out["pairs"] = s.pairs;
    out["empty_cells"] = s.empty_cells;
    out["mean_triangles_per_nonempty_cell"] = non_empty ? double(s.pairs) / double(non_empty) : 0.0;
    out["max_triangles_per_cell"] = s.max_triangles_per_cell;
    out["build_ms"] = s.build_ms;
    nlohmann::json kinds = nlohmann::json::object();
    for (int k = 0; k < kRayKinds; ++k) {
        const GridWalkStats& w = s.walks[std::size_t(k)];
        if (w.rays == 0) continue;
        kinds[ray_kind_name(RayKind(k))] = {{"rays", w.rays},
                                            {"cells_visited_per_ray", double(w.cells_visited) / double(w.rays)},
                                            {"tests_per_ray", double(w.tests) / double(w.rays)}};
    }
    out["traversal"] = kinds;
    out["loop_bound_reached"] = s.loop_bound_reached;
    out["gpu_cpu_syncs"] = s.gpu_cpu_syncs;
}

}  // namespace rt
