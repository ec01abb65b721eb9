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

namespace rt {

// The key of each batch kind (ray_keys.h): reflection and refraction rays [coarse direction | cubic origin], shadow
// rays [cubic origin | direction].
enum class SortMode {
    off,         // queue order: exactly stage 04
    on,          // every batch sorted
    automatic,   // every batch sorted, the sorted order kept only where it is tighter (order_choice.h)
};
const char* sort_mode_name(SortMode mode);   // "off", "on", "auto"

struct SortOptions {
    SortMode mode = SortMode::automatic;   // --sort auto|on|off
    bool sorts() const { return mode != SortMode::off; }
    unsigned key_bits = 30;              // --key-bits: origin + direction bits of a key
    unsigned direction_bits = 4;         // --direction-bits: the coarse direction cell of reflection/refraction keys
    unsigned shadow_direction_bits = 12; // --shadow-direction-bits: the direction cell below a shadow key's origin
    unsigned fine_direction_bits = 8;    // --fine-direction-bits: --sort auto's second reflection/refraction key
                                         // (0 or = direction_bits: none)
};

class RaySortingRenderer : public RayHierarchyRenderer {
public:
    RaySortingRenderer();
    ~RaySortingRenderer() override;

    void add_options(CLI::App& app) override;   // stage 04's, --sort, --key-bits, --[shadow-]direction-bits
    SortOptions sort_options;

protected:
    void build(const Scene& scene, const RenderSettings& settings) override;
    void trace_batch(const gpu::BatchTraceInputs& in, bool shadow) override;
    std::vector<std::string> stage_programs() const override;
    void add_stage_stats(FrameResult& result) override;

private:
    struct BatchStats {   // per batch kind: 0 = trace (reflection, refraction), 1 = shadow
        std::uint64_t batches = 0, rays = 0, chunks = 0;
    };
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
    std::array<BatchStats, 2> batch_stats_{};
};

}  // namespace rt
