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
    std::uint64_t batches = 0, rays = 0, chunks = 0;   // sorted (with auto: measured, or by a remembered order)
    std::uint64_t measured_batches = 0;   // auto: sorted by every key and measured (order_choice.h)
    std::uint64_t skipped_batches = 0, skipped_rays = 0;   // auto: traced unsorted, their queue order having won
                                                           // or being checked against a kept sort (below)
    // auto: batches traced in the queue's order to check the sort their measure kept (sort_auto.h), and of
    // those the ones where the sort tested at least as many pairs, so the queue's order is taken until the next
    // measure.
    std::uint64_t checked_batches = 0, sorts_dropped = 0;
};

struct SortFrameStats {
    SortOptions options;
    unsigned shadow_direction_bits = 0, fine_direction_bits = 0;   // as used (the defaults give way to short keys)
    std::array<RayKeyLayout, 3> layouts{};                         // trace, shadow, trace's fine key
    std::array<SortBatchStats, 2> batches{};
    std::array<GpuOrderChoice::Tally, 2> kept{};                   // sorted batches whose sorted order was kept
    std::array<double, 2> sort_ms{};
    // Read-backs of the sorting in the frame (each a wait for the GPU): none inside a batch, only its statistics'.
    // The frame's total is this plus ray_hierarchy's gpu_cpu_syncs.
    std::uint64_t gpu_cpu_syncs = 0;
};

void to_json(nlohmann::json& out, const SortFrameStats& stats);

}  // namespace rt
