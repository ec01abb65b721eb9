// Stage 05's frame statistics (the "ray_sorting" object of --stats, beside stage 04's "ray_hierarchy"): the key
// layouts of the frame and, per batch kind, the batches sorted and those whose sorted order was kept. The renderer
// fills the struct; to_json writes it (nlohmann's conversion hook, found by ADL).
#pragma once

#include <array>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "order_choice.h"
#include "ray_keys.h"
#include "sort_options.h"

namespace rt {

struct SortBatchStats {   // per batch kind: 0 = trace (reflection, refraction), 1 = shadow
    std::uint64_t batches = 0, rays = 0, chunks = 0;
};

struct SortFrameStats {
    SortOptions options;
    unsigned shadow_direction_bits = 0, fine_direction_bits = 0;   // as used (the defaults give way to short keys)
    std::array<RayKeyLayout, 3> layouts{};                         // trace, shadow, trace's fine key
    std::array<SortBatchStats, 2> batches{};
    std::array<GpuOrderChoice::Tally, 2> kept{};                   // batches whose sorted order was kept
    std::array<double, 2> sort_ms{};
};

void to_json(nlohmann::json& out, const SortFrameStats& stats);

}  // namespace rt
