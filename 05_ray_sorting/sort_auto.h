// --sort auto: a wrapper round the sorted traversal (sorting_renderer.h) that sorts a batch only where it pays.
// A measured batch is sorted by every key and the GPU keeps the order whose lowest hierarchy nodes are tightest
// (order_choice.h); sort_memory.h remembers each batch's winner for the next frames and checks a kept sort once
// against the queue's order, dropping it if it saved fewer pairs than it cost. 05's README, "--sort auto".
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "order_choice.h"
#include "sort_memory.h"
#include "sorting_renderer.h"

namespace rt {

class AutoSortTraversal final : public gpu::Traversal {
public:
    AutoSortTraversal(const SortOptions& options, std::unique_ptr<SortedTraversal> sorted);
    ~AutoSortTraversal() override;

    void add_options(CLI::App& app) override { sorted_->add_options(app); }
    std::string unsupported(const Scene& scene, const RenderSettings& settings) const override {
        return sorted_->unsupported(scene, settings);
    }
    void build(const gpu::FrameInputs& frame) override;
    // Not auto: the sorted traversal's. Auto: the batch's plan (sort_memory.h) says how it is traced.
    void trace_batch(const gpu::BatchTraceInputs& in, bool shadow) override;
    std::string steps() const override { return sorted_->steps(); }
    void end_frame() override;   // the frame's choices, read once, remembered (sort_memory.h)
    void report(gpu::FrameReport& report) override;
    std::vector<std::string> programs() const override;

private:
    bool automatic() const { return options_.mode == SortMode::automatic; }
    // The batch sorted by every key, the GPU's choice written into the sorted traversal's order (the trace's
    // reflection and refraction rays also by the fine key).
    void measure(const gpu::BatchTraceInputs& in, std::size_t kind, std::uint32_t slot);
    // The second key for reflection and refraction batches: its direction bits, 0 for none (equal to
    // --direction-bits, or the default above a short --key-bits).
    unsigned fine_direction_bits() const;
    // Whether a measured batch records its pairs, for the check of a kept sort (no frame is left to use it below 3).
    bool checks_sorts() const { return options_.probe_every >= 3; }

    const SortOptions& options_;   // the stage's
    std::unique_ptr<SortedTraversal> sorted_;
    float diagonal_ = 1.0f;                              // the scene box's diagonal (the choice's unit of width)
    RayKeyLayout fine_layout_{};                         // the trace batches' fine key, set per frame
    GpuOrderChoice choice_;
    gpu::Buffer fine_order_;
    SortMemory memory_;                                  // across frames
    std::array<std::uint32_t, 2> batch_index_{};         // the frame's batches of each kind so far
    std::array<GpuOrderChoice::Tally, 2> kept_{};        // the frame's batches sorted by a remembered order
    GpuOrderChoice::FrameTally tally_{};                 // end_frame's read of the measured batches' choices
    std::array<std::uint64_t, 2> sorts_dropped_{};       // end_frame: kept sorts the check dropped
};

}  // namespace rt
