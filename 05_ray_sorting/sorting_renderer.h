// Stage 05: stage 04's ray-space hierarchy over sorted rays (Garanzha & Loop 2010; Reis's pipeline). Every batch the
// wavefront pipeline hands over is sorted by ray key (ray_sort.h), gathered into sorted order, traced through stage
// 04's hierarchy, and its results scattered back to queue order: the pipeline (and so the image, the hits and the ray
// counts) cannot tell the difference; only the hierarchy's cost changes. --sort off is stage 04; --sort auto (the
// default) keeps a batch's sorted order only where it makes the hierarchy's lowest nodes tighter (order_choice.h) and,
// checked in the next frame, saves more pairs than the sort costs; sort_memory.h remembers those choices across frames.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "04_ray_hierarchy/ray_hierarchy_renderer.h"
#include "order_choice.h"
#include "ray_sort.h"
#include "sort_memory.h"
#include "sort_options.h"
#include "sort_stats.h"

namespace rt {

class RaySortingRenderer : public RayHierarchyRenderer {
public:
    RaySortingRenderer();
    ~RaySortingRenderer() override;

    void add_options(CLI::App& app) override;   // stage 04's and sort_options.h's
    SortOptions sort_options;

protected:
    void build(const Scene& scene, const RenderSettings& settings) override;
    void trace_batch(const gpu::BatchTraceInputs& in, bool shadow) override;
    void end_frame() override;   // --sort auto: the frame's choices, read once, remembered (sort_memory.h)
    std::vector<std::string> stage_programs() const override;
    void add_stage_stats(FrameResult& result) override;   // stage 04's and sort_stats.h's

private:
    // The four steps of a sorted batch (trace_batch).
    void sort(const gpu::BatchTraceInputs& in, std::size_t kind, std::uint32_t slot, BatchPlan plan);
    void gather(const gpu::BatchTraceInputs& in);
    void trace_sorted(const gpu::BatchTraceInputs& in, bool shadow, std::uint32_t slot, BatchPlan plan);
    void scatter(const gpu::BatchTraceInputs& in, bool shadow);
    // A batch the memory traces in the queue's order (stage 04's trace), and its pairs when it checks a kept sort.
    void trace_unsorted(const gpu::BatchTraceInputs& in, bool shadow, std::uint32_t slot, BatchPlan plan);

    void compile();
    // sort_options' value; above key_bits (the default, a short key) half of it.
    unsigned shadow_direction_bits() const;
    // --sort auto's second key for reflection and refraction batches: its direction bits, 0 for none (not auto, equal
    // to --direction-bits, or the default above a short --key-bits).
    unsigned fine_direction_bits() const;
    // Whether a measured batch records its pairs, for the check of a kept sort (no frame is left to use it below 3).
    bool checks_sorts() const { return sort_options.mode == SortMode::automatic && sort_options.probe_every >= 3; }

    float diagonal_ = 1.0f;   // the scene box's diagonal (the choice's unit of width)
    std::unique_ptr<RaySorter> sorter_;   // created with the first frame (needs the context)
    GpuOrderChoice choice_;
    // Per batch kind (trace, shadow) and the trace batches' fine key, set per frame (the scene box, the lights).
    std::array<RayKeyLayout, 3> layouts_{};
    gpu::Program gather_, scatter_;
    gpu::Buffer order_, fine_order_, sorted_rays_, sorted_results_;

    SortMemory memory_;                                  // --sort auto across frames
    std::array<std::uint32_t, 2> batch_index_{};         // the frame's batches of each kind so far
    std::array<SortBatchStats, 2> batch_stats_{};
    std::array<GpuOrderChoice::Tally, 2> kept_{};        // the frame's batches sorted by a remembered order
    GpuOrderChoice::FrameTally tally_{};                 // end_frame's read of the measured batches' choices
    std::array<std::uint64_t, 2> sorts_dropped_{};       // end_frame: kept sorts the check dropped
};

}  // namespace rt
