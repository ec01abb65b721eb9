// Stage 03's frame statistics (the "grid" object of --stats): the grid built this frame and what walking it cost,
// per ray kind. The renderer fills the struct; to_json writes it (nlohmann's conversion hook, found by ADL).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "common/trace/ray.h"

namespace rt {

struct GridWalkStats {          // one ray kind
    std::uint64_t rays = 0;
    std::uint64_t cells_visited = 0;
    std::uint64_t tests = 0;    // ray/triangle tests
};

struct GridFrameStats {
    bool built = false;         // false: every ray of the frame was rasterized, no grid was needed
    bool trace_primary = false; // --primary trace
    // The rest only when built:
    glm::ivec3 resolution{0};
    std::optional<float> lambda, lambda_used;   // empty with --grid-res (no heuristic)
    std::size_t cells = 0, pairs = 0, empty_cells = 0, max_triangles_per_cell = 0;
    double build_ms = 0.0;
    std::array<GridWalkStats, kRayKinds> walks{};
    std::uint64_t loop_bound_reached = 0;       // rays that stopped at the DDA's step bound
    std::uint64_t gpu_cpu_syncs = 0;            // the grid's read-backs in the frame: its build's 3, the stats' 2
};

// empty_cells and max_triangles_per_cell from the grid's per-cell [first, end) ranges.
void count_cell_occupancy(const std::vector<std::uint32_t>& ranges, GridFrameStats& stats);

void to_json(nlohmann::json& out, const GridFrameStats& stats);

}  // namespace rt
