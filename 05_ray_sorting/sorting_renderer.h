// Stage 05: stage 04's ray-space hierarchy over sorted rays (Garanzha & Loop 2010; Reis's pipeline). For every batch
// the wavefront pipeline hands over, the rays are sorted by key (ray_sort.h), copied into sorted order, traced
// through the stage-04 hierarchy, and their results put back in queue order: the pipeline (and so the image, the
// hits and the ray counts) cannot tell the difference; only the hierarchy's cost changes. --sort off is stage 04;
// --sort auto (the default) keeps a batch's sorted order only when it makes the hierarchy's lowest nodes tighter
// than the queue's order (order_choice.h), so sorting never widens the nodes it was meant to tighten.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "04_ray_hierarchy/ray_hierarchy_renderer.h"
#include "order_choice.h"
#include "ray_sort.h"
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
    std::vector<std::string> stage_programs() const override;
    void add_stage_stats(FrameResult& result) override;   // stage 04's and sort_stats.h's

private:
    float diagonal_ = 1.0f;   // the scene box's diagonal (the choice's unit of width)
    void compile();
    // sort_options' value; above key_bits (the default, a short key) half of it.
    unsigned shadow_direction_bits() const;
    // --sort auto's second key for reflection and refraction batches: its direction bits, 0 for none (not auto, equal
    // to --direction-bits, or the default above a short --key-bits).
    unsigned fine_direction_bits() const;

    std::unique_ptr<RaySorter> sorter_;   // created with the first frame (needs the context)
    GpuOrderChoice choice_;
    // Per batch kind (trace, shadow) and the trace batches' fine key, set per frame (the scene box, the lights).
    std::array<RayKeyLayout, 3> layouts_{};
    gpu::Program gather_, scatter_;
    gpu::Buffer order_, fine_order_, sorted_rays_, sorted_results_;
    std::array<SortBatchStats, 2> batch_stats_{};
};

}  // namespace rt
