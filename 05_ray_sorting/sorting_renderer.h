// Stage 05: stage 04's ray-space hierarchy over sorted rays (Garanzha & Loop 2010; Reis's pipeline). Every batch the
// wavefront pipeline hands over is sorted by ray key (ray_sort.h), gathered into sorted order, traced through stage
// 04's hierarchy, and its results scattered back to queue order: the pipeline (and so the image, the hits and the ray
// counts) cannot tell the difference; only the hierarchy's cost changes. --sort off is stage 04; --sort on sorts every
// batch; --sort auto (the default, sort_auto.h) keeps a batch's sorted order only where it pays.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "04_ray_hierarchy/ray_hierarchy_renderer.h"
#include "ray_sort.h"
#include "sort_options.h"
#include "sort_stats.h"

namespace rt {

// The sorted traversal: wraps stage 04's, and with --sort on sorts every batch before handing it over.
class SortedTraversal final : public gpu::Traversal {
public:
    SortedTraversal(SortOptions& options, std::unique_ptr<HierarchyTraversal> hierarchy);
    ~SortedTraversal() override;

    void add_options(CLI::App& app) override;   // stage 04's and sort_options.h's
    std::string unsupported(const Scene& scene, const RenderSettings& settings) const override {
        return hierarchy_->unsupported(scene, settings);
    }
    void build(const gpu::FrameInputs& frame) override;
    void trace_batch(const gpu::BatchTraceInputs& in, bool shadow) override;
    std::string steps() const override { return hierarchy_->steps(); }
    void report(gpu::FrameReport& report) override;   // stage 04's and sort_stats.h's
    std::vector<std::string> programs() const override;

    // The four steps of a sorted batch, for --sort auto (sort_auto.h), which chooses per batch.
    // 1. The rays' keys by `layout`, radix-sorted into `order`; slot: the batch kind (0 trace, 1 shadow) whose sort
    //    it is, or 2 for a second key of a batch (not counted as a sorted batch).
    void sort(const gpu::BatchTraceInputs& in, const RayKeyLayout& layout, std::size_t slot, gpu::Buffer& order);
    void gather(const gpu::BatchTraceInputs& in);                 // 2. the rays copied into order()'s order
    void trace_sorted(const gpu::BatchTraceInputs& in, bool shadow);   // 3. stage 04's hierarchy over them
    void scatter(const gpu::BatchTraceInputs& in, bool shadow);       // 4. the results put back in queue order

    gpu::Buffer& order() { return order_; }
    const RayKeyLayout& layout(bool shadow) const { return layouts_[shadow ? 1 : 0]; }
    HierarchyTraversal& hierarchy() { return *hierarchy_; }
    gpu::GpuTimer& timer() { return *timer_; }
    // Timer phase of a batch kind's sort and gather ("rs_sort.trace", "rs_sort.shadow").
    static const char* sort_phase(bool shadow) { return shadow ? "rs_sort.shadow" : "rs_sort.trace"; }
    // The frame's stats so far (reset by build()): a wrapper adds its own before report().
    SortFrameStats& frame_stats() { return stats_; }

private:
    void compile();
    // sort_options' value; above key_bits (the default, a short key) half of it.
    unsigned shadow_direction_bits() const;

    SortOptions& options_;                           // the stage's
    std::unique_ptr<HierarchyTraversal> hierarchy_;
    gpu::GpuTimer* timer_ = nullptr;                 // the frame's (build())
    std::unique_ptr<RaySorter> sorter_;              // created with the first frame that sorts (needs the context)
    std::array<RayKeyLayout, 2> layouts_{};          // trace, shadow: set per frame (the scene box, the lights)
    gpu::Program gather_, scatter_;
    gpu::Buffer order_, sorted_rays_, sorted_results_;
    SortFrameStats stats_;
};

// Stage 02's rasterized primary visibility + stage 04's hierarchy over sorted rays, --sort auto choosing.
class RaySortingRenderer : public gpu::GpuStage {
public:
    RaySortingRenderer();
    // Read by the traversals, which hold them by reference.
    HierarchyOptions hierarchy_options;
    SortOptions sort_options;
};

}  // namespace rt
