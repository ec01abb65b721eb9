#include "order_choice.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/gpu/gl/bindings.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt {

std::uint32_t order_fixed_width(const RhNode& node, float longest, float diagonal) {
    if (node.empty()) return 0;
    const auto widest = std::uint32_t(kOrderMaxWidth * kOrderWidthUnits);
    if (node.cone.w >= kRhAllDirections) return widest;
    const float reach = std::isfinite(longest) ? std::min(longest, kOrderReach * diagonal) : kOrderReach * diagonal;
    const float width = node.sphere.w + reach * std::sin(std::min(node.cone.w, 1.57079637f));
    const float units = width / diagonal * kOrderWidthUnits;
    if (!(units < kOrderMaxWidth * kOrderWidthUnits)) return widest;
    return std::uint32_t(units);
}

std::uint32_t order_radius_units(float radius, float diagonal) {
    const float units = radius / diagonal * kOrderWidthUnits;
    if (!(units >= 0.0f)) return 0;   // an empty sphere (radius < 0) or NaN
    return units < kOrderMaxWidth * kOrderWidthUnits ? std::uint32_t(units) : kOrderNoCap;
}

std::uint32_t order_width_cap(std::uint64_t radius_units_sum, std::uint32_t leaves) {
    if (leaves == 0) return kOrderNoCap;
    const double mean_diameter = 2.0 * double(radius_units_sum) / double(leaves);   // as on the GPU, in double
    return std::uint32_t(std::min(mean_diameter, double(kOrderNoCap)));
}

std::uint32_t order_width_cap(const std::vector<glm::vec4>& leaf_spheres, float diagonal) {
    std::uint64_t sum = 0;
    for (const glm::vec4& s : leaf_spheres) sum += order_radius_units(s.w, diagonal);
    return order_width_cap(sum, std::uint32_t(leaf_spheres.size()));
}

std::uint64_t order_cost(const std::vector<OrderRay>& rays, const std::vector<std::uint32_t>& order, int branching,
                         float diagonal, std::uint32_t cap) {
    const std::size_t b = std::size_t(branching);
    std::uint64_t sum = 0;
    for (std::size_t first = 0; first < rays.size(); first += b) {
        const std::size_t count = std::min(b, rays.size() - first);
        RhNode kids[16];
        float longest = 0.0f;
        for (std::size_t k = 0; k < count; ++k) {
            const OrderRay& r = rays[order.empty() ? first + k : order[first + k]];
            kids[k] = rh_leaf(r.origin, r.direction);
            longest = std::max(longest, r.tmax * glm::length(r.direction));
        }
        sum += std::min(order_fixed_width(rh_union(kids, count), longest, diagonal), cap);
    }
    return sum;
}

int choose_order(std::uint64_t queue_cost, std::uint64_t sorted_cost, std::optional<std::uint64_t> fine_cost) {
    int best = 1;
    std::uint64_t width = sorted_cost;
    if (fine_cost && *fine_cost < width) {
        best = 2;
        width = *fine_cost;
    }
    return keep_sorted_order(queue_cost, width) ? best : 0;
}

namespace {
// shaders/order_choice.glsl: OC_BINDING_* (the stage's own points; 04 rebinds its own before each of its passes).
constexpr unsigned kBindingOrder = gpu::kBindingWavefrontTraversalFirst + 0;
constexpr unsigned kBindingCost = gpu::kBindingWavefrontTraversalFirst + 1;
constexpr unsigned kBindingTally = gpu::kBindingWavefrontTraversalFirst + 2;
constexpr unsigned kBindingOrderFine = gpu::kBindingWavefrontTraversalFirst + 3;
constexpr unsigned kBindingLeaves = gpu::kBindingWavefrontTraversalFirst + 4;
constexpr std::size_t kCostWords = 8;   // three 64-bit width sums, then the leaves' radii
constexpr std::size_t kTallySize = 6;   // OC_TALLY_SIZE
constexpr std::size_t kTallyWords = 2 * kTallySize + 2 * kOrderRecords;   // the counts, then the records

void barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT); }

std::uint64_t u64(const std::uint32_t* lo_hi) { return std::uint64_t(lo_hi[1]) << 32 | lo_hi[0]; }

// After the counts and records, the work copies: per slot, per kind, before and after (record_work).
std::size_t work_offset(std::size_t kind, std::uint32_t record, bool after) {
    return kTallyWords * 4 + ((std::size_t(record) * 2 + kind) * 2 + (after ? 1 : 0)) * GpuRayHierarchy::tally_bytes();
}

// The tally buffer as reset_tally() leaves it: counts 0, no choice recorded.
std::vector<std::uint32_t> empty_tally() {
    std::vector<std::uint32_t> v(kTallyWords, 0);
    std::fill(v.begin() + 2 * kTallySize, v.end(), kOrderNoRecord);
    return v;
}
}  // namespace

void GpuOrderChoice::compile(const gpu::ShaderDefines& defines) {
    if (cost_ && defines == defines_) return;   // compiled for these already
    cost_ = gpu::Program::compute("05_ray_sorting/shaders/order_cost.comp", defines);
    choice_ = gpu::Program::compute("05_ray_sorting/shaders/order_choice.comp", defines);
    defines_ = defines;
    if (!tally_) reset_tally();
}

void GpuOrderChoice::sum(const gpu::Buffer* order, unsigned slot, std::size_t first, std::size_t count,
                         int branching, float diagonal) const {
    if (order) order->bind_range(kBindingOrder, 0, count * 4);
    cost_.set("oc_count", unsigned(count));
    cost_.set("oc_first", unsigned(first));
    cost_.set("oc_branching", unsigned(branching));
    cost_.set("oc_diagonal", diagonal);
    cost_.set("oc_sorted", order ? 1u : 0u);
    cost_.set("oc_slot", slot);
    cost_.set("oc_mode", 0u);
    cost_.dispatch_threads((count + std::size_t(branching) - 1) / std::size_t(branching));   // a thread per node
}

void GpuOrderChoice::choose(const gpu::ShaderDefines& defines, const gpu::Buffer& rays, std::size_t first,
                            std::size_t count, gpu::Buffer& order, const gpu::Buffer* fine_order, int branching,
                            float diagonal, int kind, std::uint32_t record) {
    compile(defines);
    if (count == 0) return;
    if (!costs_) {
        costs_ = gpu::Buffer(kCostWords * 4);
        costs_.clear_u32(0);
    }
    const std::uint32_t zero[6] = {};
    costs_.upload(zero, sizeof zero);   // the three width sums; words 6, 7 are the frame's
    costs_.bind(kBindingCost);
    (leaves_ ? *leaves_ : costs_).bind(kBindingLeaves);
    cost_.set("oc_leaf_count", leaves_ ? leaf_count_ : 0u);
    cost_.set("oc_leaf_stride", leaf_stride_);
    if (!leaves_measured_) measure_leaves(diagonal);
    rays.bind(gpu::kBindingWavefrontRaysIn);
    order.bind_range(kBindingOrder, 0, count * 4);   // also read (not used) by the queue's sum
    sum(nullptr, 0, first, count, branching, diagonal);
    sum(&order, 1, first, count, branching, diagonal);
    if (fine_order) sum(fine_order, 2, first, count, branching, diagonal);
    barrier();
    order.bind_range(kBindingOrder, 0, count * 4);
    (fine_order ? *fine_order : order).bind_range(kBindingOrderFine, 0, count * 4);
    tally_.bind(kBindingTally);
    choice_.set("oc_count", unsigned(count));
    choice_.set("oc_first", unsigned(first));
    choice_.set("oc_kind", unsigned(kind));
    choice_.set("oc_candidates", fine_order ? 2u : 1u);
    choice_.set("oc_record", record < kOrderRecords ? std::uint32_t(kind) * kOrderRecords + record : kOrderNoRecord);
    choice_.dispatch_threads(count);
    barrier();
    gpu::check_gl("05_ray_sorting: order choice");
}

// The leaves' radii in width units of the batch's diagonal (the frame's), summed into costs_ words 6 and 7
// (order_cost.comp, oc_mode 1: a thread sums kOrderLeavesPerThread leaves).
void GpuOrderChoice::measure_leaves(float diagonal) {
    const std::uint32_t zero[2] = {};
    costs_.upload(zero, sizeof zero, 6 * 4);
    cost_.set("oc_mode", 1u);
    cost_.set("oc_slot", 3u);
    cost_.set("oc_diagonal", diagonal);
    cost_.dispatch_threads((std::size_t(leaf_count_) + kOrderLeavesPerThread - 1) / kOrderLeavesPerThread);
    barrier();
    leaves_measured_ = true;
}

void GpuOrderChoice::set_leaves(const gpu::Buffer& spheres, std::uint32_t count, std::uint32_t stride) {
    leaves_ = count > 0 ? &spheres : nullptr;
    leaf_count_ = count;
    leaf_stride_ = std::max<std::uint32_t>(stride, 1);
    leaves_measured_ = leaves_ == nullptr;
}

std::array<std::uint64_t, 3> GpuOrderChoice::last_costs() const {
    std::uint32_t v[6] = {};
    if (costs_) costs_.download(v, sizeof v);
    return {u64(v), u64(v + 2), u64(v + 4)};
}

std::uint32_t GpuOrderChoice::width_cap() const {
    std::uint32_t v[kCostWords] = {};
    if (costs_) costs_.download(v, sizeof v);
    return order_width_cap(u64(v + 6), leaves_ ? leaf_count_ : 0u);
}

GpuOrderChoice::FrameTally GpuOrderChoice::tally() const {
    // One read-back: the counts and records, and the work copies of the slots recorded.
    const std::size_t bytes = work_offset(0, work_records_, false);
    std::vector<std::uint32_t> v = empty_tally();
    v.resize(bytes / 4);
    if (tally_) tally_.download(v.data(), bytes);
    FrameTally t;
    for (std::size_t k = 0; k < 2; ++k) {
        const std::uint32_t* w = v.data() + k * kTallySize;
        t.kept[k] = {u64(w), u64(w + 2), u64(w + 4)};
        std::copy_n(v.data() + 2 * kTallySize + k * kOrderRecords, kOrderRecords, t.choices[k].begin());
        for (std::uint32_t r = 0; r < kOrderRecords; ++r) {
            t.work[k][r] = kNoWork;
            if (work_copied_[k][r] != 3) continue;   // both copies, or none
            const auto pairs = [&](bool after) {
                return GpuRayHierarchy::tally_pairs(v.data() + work_offset(k, r, after) / 4);
            };
            t.work[k][r] = pairs(true) - pairs(false);
        }
    }
    return t;
}

void GpuOrderChoice::reset_tally() {
    const std::vector<std::uint32_t> v = empty_tally();
    if (!tally_) tally_ = gpu::Buffer(work_offset(0, kOrderRecords, false));
    tally_.upload(v.data(), kTallyWords * 4);
    work_copied_ = {};
    work_records_ = 0;
}

void GpuOrderChoice::record_work(const GpuRayHierarchy& hierarchy, int kind, std::uint32_t record, bool after) {
    if (record >= kOrderRecords) return;
    if (!tally_) reset_tally();
    const std::size_t k = kind == 0 ? 0 : 1;
    hierarchy.copy_tally(tally_, work_offset(k, record, after));
    work_copied_[k][record] = std::uint8_t(after ? work_copied_[k][record] | 2 : 1);
    work_records_ = std::max(work_records_, record + 1);
}

}  // namespace rt
