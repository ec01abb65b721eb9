// --sort auto: per batch, keep the sorted order only when it makes stage 04's lowest nodes tighter than the queue's
// order does. The C++ twin of shaders/order_choice.glsl, order_cost.comp and order_choice.comp (the GPU decides
// without a read-back; these are what the tests compare it with).
//
// Why a choice: the wavefront queue is already coherent (8x8 pixel tiles in Morton order), so for rays one bounce
// from the camera a sort can only match it, and its cell boundaries sometimes split neighbours the queue kept
// together (sorting every batch makes more leaf pairs on some scenes: 05's README, "Choosing per batch"). The cost
// proxy is the level-1 nodes' beam width where they meet the scene: level 1 (B rays) is the side every (ray, object)
// pair splits down to, so its width decides how many pairs reach the exact test, up to the width of the objects it
// meets (the cap, order_width_cap below).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "04_ray_hierarchy/gpu_ray_hierarchy.h"
#include "04_ray_hierarchy/ray_hierarchy.h"
#include "common/gpu/gl/buffer.h"
#include "common/gpu/gl/shader.h"

namespace rt {

// Fixed point of the widths (OC_UNITS, OC_MAX_WIDTH): 1/4096 of the scene's diagonal, at most 4 diagonals.
constexpr float kOrderWidthUnits = 4096.0f;
constexpr float kOrderMaxWidth = 4.0f;
constexpr float kOrderReach = 0.125f;   // OC_REACH: the width is taken at this part of the diagonal (or the ray's end)

// A level-1 node's width radius + L sin(min(spread, pi/2)), L = min(longest, kOrderReach diagonal) (every direction:
// the most),
// in those units, rounded down; 0 for an empty node.
std::uint32_t order_fixed_width(const RhNode& node, float longest, float diagonal);

// A ray as the choice reads it: the hierarchy's leaf, and its length tmax |d|.
struct OrderRay {
    glm::vec3 origin, direction;
    float tmax = 0.0f;
};

// The cap of every node's width (order_choice.glsl: oc_width_cap): the mean diameter of the finest objects the ray
// nodes are culled against (the object tree's clusters, mesh objects or triangles), in width units, from the sum of
// their radii in width units (each rounded down, empty or NaN spheres 0, at most kOrderMaxWidth); no leaves: no cap
// (kOrderMaxWidth). A ray node wider than the leaf it meets is split into its rays there, so a wider one costs no more
// below.
std::uint32_t order_radius_units(float radius, float diagonal);
std::uint32_t order_width_cap(std::uint64_t radius_units_sum, std::uint32_t leaves);
std::uint32_t order_width_cap(const std::vector<glm::vec4>& leaf_spheres, float diagonal);
constexpr auto kOrderNoCap = std::uint32_t(kOrderMaxWidth * kOrderWidthUnits);
// Leaves one thread of order_cost.comp's oc_mode 1 sums (OC_LEAVES_PER_THREAD): on llvmpipe a pass costs about the
// same per thread whatever the thread does, and the object tree of 1M triangles has about 300K leaves.
constexpr std::uint32_t kOrderLeavesPerThread = 16;

// The summed width of the level-1 nodes over rays[order[0..n)] taken B at a time (order empty: queue order), each
// node's width at most `cap`.
std::uint64_t order_cost(const std::vector<OrderRay>& rays, const std::vector<std::uint32_t>& order, int branching,
                         float diagonal, std::uint32_t cap = kOrderNoCap);

// The sorted order is kept only when tighter by more than 1/32 of the queue's width (OC_MARGIN_DENOMINATOR): the
// width is a proxy of the cost, and a sort that gains less is not worth its passes (05's README, "Choosing per
// batch"). In double, as on the GPU: exact for sums below 2^53.
constexpr double kOrderMarginDenominator = 32.0;
inline bool keep_sorted_order(std::uint64_t queue_cost, std::uint64_t sorted_cost) {
    return double(sorted_cost) * kOrderMarginDenominator < double(queue_cost) * (kOrderMarginDenominator - 1.0);
}

// The check's rule (sort_auto.h): a sort the measure kept stays only if the pairs it saved (queue's order
// minus sorted, both measured on the batch) pay for its passes: more than batch_cost + ray_cost x its rays, in pair
// tests (sort_options.h: kSortBatchCost, kSortRayCost). With both costs 0: any saving.
inline bool sort_pays(std::uint64_t queue_pairs, std::uint64_t sorted_pairs, std::uint64_t rays,
                      std::uint64_t batch_cost, std::uint64_t ray_cost) {
    return sorted_pairs < queue_pairs && queue_pairs - sorted_pairs > batch_cost + ray_cost * rays;
}

// The order a batch is traced in: 0 = the queue's, 1 = the sorted one, 2 = the fine one (reflection and refraction
// batches are also sorted by a finer direction cell, --fine-direction-bits): the tighter sort (the coarse one on a
// tie) if keep_sorted_order says so against the queue.
int choose_order(std::uint64_t queue_cost, std::uint64_t sorted_cost, std::optional<std::uint64_t> fine_cost = {});

// The choices of a frame's first kOrderRecords batches of each kind are recorded (order_choice.glsl: OC_RECORDS), so
// the renderer can take the order that won in the next frames without measuring again (sort_auto.h).
constexpr std::uint32_t kOrderRecords = 64;
constexpr std::uint32_t kOrderNoRecord = 0xffffffffu;   // OC_NO_RECORD: no batch chose in that slot

// The choice on the GPU: shaders/order_cost.comp sums the widths of each order, shaders/order_choice.comp writes the
// chosen one into `order` (queue order first + i, the fine order, or `order` as it is). No read-back: the counts
// reach the CPU with the stats.
class GpuOrderChoice {
public:
    // rays[first, first + count) of the batch, `order` its sorted order (RaySorter::sort) and `fine_order` (or null)
    // its order by the finer direction cell; kind: 0 trace, 1 shadow. `defines`: the wavefront's (the passes read
    // its rays through wavefront.glsl). The choice is recorded in slot `record` of its kind (below kOrderRecords;
    // kOrderNoRecord: not recorded).
    void choose(const gpu::ShaderDefines& defines, const gpu::Buffer& rays, std::size_t first, std::size_t count,
                gpu::Buffer& order, const gpu::Buffer* fine_order, int branching, float diagonal, int kind,
                std::uint32_t record = kOrderNoRecord);
    // Per frame, before its batches: the bounding spheres the ray nodes meet last (`count` of them, `stride` vec4s
    // apart; GpuRayHierarchy::leaf_spheres), whose mean diameter caps every node's width (order_width_cap). Measured
    // by the next choose(), once. Until the first call, and with count 0, no cap.
    void set_leaves(const gpu::Buffer& spheres, std::uint32_t count, std::uint32_t stride);
    // The cap the last choose() used, in width units (a read-back: for the tests).
    std::uint32_t width_cap() const;
    // The last batch's sums: queue, sorted, fine (0 without one). A read-back: for the tests.
    std::array<std::uint64_t, 3> last_costs() const;
    // Per batch kind since reset_tally(): batches and rays that kept a sorted order, and batches that kept the fine
    // one; and each recorded slot's choice (0 queue, 1 sorted, 2 fine; kOrderNoRecord: none since the reset). One
    // read-back for both.
    struct Tally {
        std::uint64_t batches = 0, rays = 0, fine_batches = 0;
    };
    struct FrameTally {
        std::array<Tally, 2> kept{};
        std::array<std::array<std::uint32_t, kOrderRecords>, 2> choices{};
        // Per recorded slot, what its batch cost the hierarchy (record_work; kNoWork: not recorded since the reset).
        std::array<std::array<std::uint64_t, kOrderRecords>, 2> work{};
    };
    FrameTally tally() const;
    void reset_tally();
    // The check of a choice (sort_auto.h): the pairs the hierarchy tested for the batch of slot `record` of
    // `kind`, in whatever order it was traced (GpuRayHierarchy::tally_pairs): its tally copied into this one's
    // buffer before (`after` false) and after the trace, on the GPU; tally() brings the difference with the choices.
    void record_work(const GpuRayHierarchy& hierarchy, int kind, std::uint32_t record, bool after);
    static constexpr std::uint64_t kNoWork = UINT64_MAX;

private:
    void compile(const gpu::ShaderDefines& defines);
    void sum(const gpu::Buffer* order, unsigned slot, std::size_t first, std::size_t count, int branching,
             float diagonal) const;
    void measure_leaves(float diagonal);
    gpu::ShaderDefines defines_;   // the variant cost_ and choice_ were compiled for
    gpu::Program cost_, choice_;
    gpu::Buffer costs_, tally_;
    const gpu::Buffer* leaves_ = nullptr;   // set_leaves(): the spheres, their count and stride
    std::uint32_t leaf_count_ = 0, leaf_stride_ = 1;
    bool leaves_measured_ = true;           // costs_ words 6, 7 hold their radii's sum
    // Slots whose work was recorded since reset_tally(), before and after (bit 0, 1), and one past the highest.
    std::array<std::array<std::uint8_t, kOrderRecords>, 2> work_copied_{};
    std::uint32_t work_records_ = 0;
};

}  // namespace rt
