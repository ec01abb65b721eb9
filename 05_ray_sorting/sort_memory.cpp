#include "sort_memory.h"

namespace rt {

namespace {

// order_choice.comp's recorded choice: 0 the queue's order, 1 the sorted one, 2 the fine one.
BatchPlan plan_of_choice(std::uint32_t choice) {
    return choice == 0 ? BatchPlan::queue : choice == 1 ? BatchPlan::sorted : BatchPlan::fine;
}

}  // namespace

BatchPlan SortMemory::plan(std::size_t kind, std::uint32_t slot, const SortOptions& options) {
    if (options.mode != SortMode::automatic || slot >= kOrderRecords) return BatchPlan::measure;
    Batch& b = batches_[kind][slot];
    if (b.to_check != BatchPlan::measure) {   // the frame after a measure that kept a sort
        ++b.unmeasured;
        return BatchPlan::check_queue;
    }
    if (b.order == BatchPlan::measure || b.unmeasured + 1 >= options.probe_every) return BatchPlan::measure;
    ++b.unmeasured;
    return b.order;
}

void SortMemory::measured(std::size_t kind, std::uint32_t slot, std::uint64_t rays) {
    if (slot < kOrderRecords) batches_[kind][slot].rays = rays;
}

std::array<std::uint64_t, 2> SortMemory::learn(const GpuOrderChoice::FrameTally& tally, const SortOptions& options) {
    std::array<std::uint64_t, 2> dropped{};
    for (std::size_t k = 0; k < 2; ++k)
        for (std::size_t slot = 0; slot < kOrderRecords; ++slot) {
            Batch& b = batches_[k][slot];
            const std::uint64_t pairs = tally.work[k][slot];
            const bool recorded = pairs != GpuOrderChoice::kNoWork;
            if (tally.choices[k][slot] != kOrderNoRecord) {   // measured: a kept sort is checked next frame
                const BatchPlan order = plan_of_choice(tally.choices[k][slot]);
                const bool check = order != BatchPlan::queue && recorded;
                b = {order, 0, check ? order : BatchPlan::measure, check ? pairs : 0, b.rays};
            } else if (b.to_check != BatchPlan::measure && recorded) {   // checked: the queue's order tested `pairs`
                const bool sort_won = sort_pays(pairs, b.sorted_pairs, b.rays, options.batch_cost, options.ray_cost);
                if (!sort_won) dropped[k] += 1;
                b.order = sort_won ? b.to_check : BatchPlan::queue;
                b.to_check = BatchPlan::measure;
            }
        }
    return dropped;
}

}  // namespace rt
