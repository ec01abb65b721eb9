// Stage 05: stage 04's ray-space hierarchy over sorted rays (Garanzha & Loop 2010; Reis's pipeline). For every batch
// the wavefront pipeline hands over, the rays are sorted by key (ray_sort.h), copied into sorted order, traced
// through the stage-04 hierarchy, and their results put back in queue order: the pipeline (and so the image, the
// hits and the ray counts) cannot tell the difference; only the hierarchy's cost changes. --sort off is stage 04;
// --sort auto (the default) keeps a batch's sorted order only when it makes the hierarchy's lowest nodes tighter
// than the queue's order (order_choice.h), so sorting never widens the nodes it was meant to tighten, and, checked
// in the next frame, only when it saves more pairs than the sort costs (below); and a batch takes the order that won
// without measuring again, until --probe-every frames have passed (below).
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

    // --sort auto across frames. A sort costs about 30 passes whether its order is kept or not (on llvmpipe more
    // than the whole trace of a small scene: 05's README, "Remembering the choice"), and a reflection or refraction
    // batch is sorted twice to be measured; from one frame to the next a batch's rays come from the same surfaces,
    // camera and lights, so the order that won stays the winner. So the k-th batch of a kind remembers which order
    // won (recorded on the GPU, read with the frame's statistics: no extra read-back), and for the next
    // probe_every - 1 frames takes it unmeasured: the queue's order (traced exactly as stage 04 traces it, no sort)
    // or the one sorted order that won (one sort, no measure); then it is measured again.
    //
    // The measure is a proxy (order_choice.h: the level-1 nodes' width), and a proxy can be wrong by a little (05's
    // README, "Checking a kept sort"). So a sort the measure keeps is checked against the real thing: the batch's
    // pairs tested (node tests + leaf pairs, GpuRayHierarchy::tally_pairs) are recorded in the measured frame, the
    // next frame traces the batch in the queue's order and records them again, and the sort is remembered only if it
    // tested fewer, by more than the sort costs (--sort-batch-cost, --sort-ray-cost: order_choice.h, sort_pays). On a
    // still scene the remembered order then never tests more pairs than stage 04, by construction; the check costs one
    // frame's gain where the sort wins (the checked frame is stage 04's, with no sort). With probe_every < 3 no check
    // is made (no frame would be left to use it).
    static constexpr int kCheckOrder = 3;   // remembered_order: trace in the queue's order, to check a kept sort
    struct BatchMemory {
        int order = -1;            // the order to take: 0 queue, 1 sorted, 2 fine; -1 none yet
        unsigned unmeasured = 0;   // frames it was taken unmeasured since
        int to_check = 0;          // the sorted order the last measure kept, still to be checked (0: none)
        std::uint64_t sorted_pairs = 0;   // the pairs that order tested when measured
        std::uint64_t rays = 0;           // the batch's rays when last measured
    };
    std::array<std::array<BatchMemory, kOrderRecords>, 2> memory_{};
    std::array<std::uint32_t, 2> batch_index_{};        // the frame's batches of each kind so far
    std::array<GpuOrderChoice::Tally, 2> kept_{};       // the frame's batches sorted by a remembered order
    // The k-th (slot) batch of a kind: -1 (measure it), the order to take unmeasured, or kCheckOrder.
    int remembered_order(std::size_t kind, std::uint32_t slot);
};

}  // namespace rt
