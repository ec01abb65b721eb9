// --sort auto across frames: which order the k-th batch of a kind takes, and what a frame's choices teach.
//
// Measuring a batch's orders costs its sorts (about 30 passes each), and from one frame to the next a batch's rays come
// from the same surfaces, camera and lights, so the order that won stays the winner. The k-th batch of a kind
// remembers it and takes it unmeasured for the next probe_every - 1 frames. A sort the measure keeps (a proxy:
// order_choice.h) is checked once against the real thing: the next frame traces the batch in the queue's order, and the
// sort is remembered only if it tested fewer pairs by more than it costs (sort_pays). 05's README, "Remembering the
// choice" and "Checking a kept sort".
#pragma once

#include <array>
#include <cstdint>

#include "order_choice.h"
#include "sort_options.h"

namespace rt {

// How a batch is traced this frame.
enum class BatchPlan {
    measure,       // sort by every key, let the GPU choose (order_choice.h), remember it; --sort on: its one sort
    queue,         // the queue's order won: stage 04's trace, no sort
    check_queue,   // the queue's order, to check the sort the last measure kept
    sorted,        // the sorted order won: one sort, unmeasured
    fine,          // the fine key's sorted order won: one sort by that key, unmeasured
};

constexpr bool plan_sorts(BatchPlan p) { return p == BatchPlan::measure || p == BatchPlan::sorted || p == BatchPlan::fine; }

class SortMemory {
public:
    // The plan of the slot-th batch of a kind (0 trace, 1 shadow) this frame. Always `measure` unless --sort auto.
    BatchPlan plan(std::size_t kind, std::uint32_t slot, const SortOptions& options);
    // A measured batch's rays (what its sort cost, for the check).
    void measured(std::size_t kind, std::uint32_t slot, std::uint64_t rays);
    // The frame's choices and pairs, read from the GPU once at frame end: remembers each measured batch's choice and
    // settles each checked one. Returns the sorts dropped per kind (the check found the queue's order as good).
    std::array<std::uint64_t, 2> learn(const GpuOrderChoice::FrameTally& tally, const SortOptions& options);

private:
    struct Batch {
        BatchPlan order = BatchPlan::measure;   // the order to take unmeasured (queue, sorted, fine); measure: none yet
        unsigned unmeasured = 0;                // frames it was taken unmeasured since
        BatchPlan to_check = BatchPlan::measure;   // the sorted order the last measure kept, still to check (measure: none)
        std::uint64_t sorted_pairs = 0;         // the pairs that order tested when measured
        std::uint64_t rays = 0;                 // the batch's rays when last measured
    };
    std::array<std::array<Batch, kOrderRecords>, 2> batches_{};
};

}  // namespace rt
