#include "sort_auto.h"

#include <cmath>

#include <glm/glm.hpp>

namespace rt {

AutoSortTraversal::AutoSortTraversal(const SortOptions& options, std::unique_ptr<SortedTraversal> sorted)
    : options_(options), sorted_(std::move(sorted)) {}
AutoSortTraversal::~AutoSortTraversal() = default;

unsigned AutoSortTraversal::fine_direction_bits() const {
    const unsigned f = options_.fine_direction_bits;
    if (!automatic() || f > options_.key_bits || f == options_.direction_bits) return 0;
    return f;
}

void AutoSortTraversal::build(const gpu::FrameInputs& frame) {
    sorted_->build(frame);
    batch_index_ = {};
    kept_ = {};
    if (!automatic()) return;
    choice_.reset_tally();
    const Bounds& box = frame.scene.bounds;
    const float diagonal = glm::length(box.hi - box.lo);
    diagonal_ = std::isfinite(diagonal) && diagonal > 0.0f ? diagonal : 1.0f;
    // The width cap (order_choice.h): the spheres the hierarchy's lowest nodes meet.
    const GpuRayHierarchy::LeafSpheres leaves = sorted_->hierarchy().hierarchy().leaf_spheres();
    choice_.set_leaves(*leaves.buffer, leaves.count, leaves.stride);
    fine_layout_ = make_key_layout(box.lo, box.hi, options_.key_bits, fine_direction_bits(),
                                   unsigned(frame.scene.light_count()), KeyOrder::direction_first);
}

// One batch as its plan says: traced in the queue's order (stage 04's trace), or sorted (measured, or by the order
// that won), gathered, traced and scattered back.
void AutoSortTraversal::trace_batch(const gpu::BatchTraceInputs& in, bool shadow) {
    if (!automatic() || in.count == 0) return sorted_->trace_batch(in, shadow);
    const std::size_t kind = shadow ? 1 : 0;
    const std::uint32_t slot = batch_index_[kind]++;
    const BatchPlan plan = memory_.plan(kind, slot, options_);
    SortBatchStats& stats = sorted_->frame_stats().batches[kind];
    const GpuRayHierarchy& hierarchy = sorted_->hierarchy().hierarchy();
    // The pairs the batch tests, recorded around its trace for the check of a kept sort (sort_memory.h).
    const bool record = plan == BatchPlan::check_queue || (plan == BatchPlan::measure && checks_sorts());

    if (!plan_sorts(plan)) {   // the queue's order won, or is checked against the sort the last measure kept
        stats.skipped_batches += 1;
        stats.skipped_rays += in.count;
        if (plan == BatchPlan::check_queue) stats.checked_batches += 1;
        if (record) choice_.record_work(hierarchy, int(kind), slot, false);
        sorted_->hierarchy().trace_batch(in, shadow);
        if (record) choice_.record_work(hierarchy, int(kind), slot, true);
        return;
    }
    {
        auto timed = sorted_->timer().scope(SortedTraversal::sort_phase(shadow));
        if (plan == BatchPlan::measure) {
            measure(in, kind, slot);
        } else {   // the sorted order that won when last measured: one sort, unmeasured
            sorted_->sort(in, plan == BatchPlan::fine ? fine_layout_ : sorted_->layout(shadow), kind,
                          sorted_->order());
            kept_[kind].batches += 1;
            kept_[kind].rays += in.count;
            if (plan == BatchPlan::fine) kept_[kind].fine_batches += 1;
        }
        sorted_->gather(in);
    }
    if (record) choice_.record_work(hierarchy, int(kind), slot, false);
    sorted_->trace_sorted(in, shadow);
    if (record) choice_.record_work(hierarchy, int(kind), slot, true);
    sorted_->scatter(in, shadow);
}

void AutoSortTraversal::measure(const gpu::BatchTraceInputs& in, std::size_t kind, std::uint32_t slot) {
    sorted_->sort(in, sorted_->layout(kind == 1), kind, sorted_->order());
    // Reflection and refraction rays: a second order by the finer direction cell, for the choice.
    const bool fine = kind == 0 && fine_direction_bits() > 0;
    if (fine) sorted_->sort(in, fine_layout_, 2, fine_order_);
    choice_.choose(in.wavefront.defines(), in.rays, in.first, in.count, sorted_->order(), fine ? &fine_order_ : nullptr,
                   sorted_->hierarchy().hierarchy().options.branching, diagonal_, int(kind), slot);
    sorted_->frame_stats().batches[kind].measured_batches += 1;
    memory_.measured(kind, slot, in.count);   // what its sort cost, for the check
}

void AutoSortTraversal::end_frame() {
    sorted_->end_frame();
    sorts_dropped_ = {};
    if (!automatic()) return;
    // The measured batches' choices and the recorded pairs, tallied on the GPU and read here once per frame.
    tally_ = choice_.tally();
    sorts_dropped_ = memory_.learn(tally_, options_);
}

std::vector<std::string> AutoSortTraversal::programs() const {
    std::vector<std::string> programs = sorted_->programs();
    if (automatic())
        for (const char* p : {"order_cost.comp", "order_choice.comp"})
            programs.push_back(std::string("05_ray_sorting/shaders/") + p);
    return programs;
}

void AutoSortTraversal::report(gpu::FrameReport& report) {
    SortFrameStats& f = sorted_->frame_stats();
    f.fine_direction_bits = fine_direction_bits();
    if (automatic()) {
        f.layouts[2] = fine_layout_;
        ++f.gpu_cpu_syncs;   // end_frame's read
        // Batches (and their rays) whose sorted order was kept, and of them those that kept the fine key's: the
        // measured batches' choices (end_frame's read) and those sorted by a remembered order (kept_).
        for (std::size_t k = 0; k < 2; ++k) {
            const GpuOrderChoice::Tally& t = tally_.kept[k];
            f.kept[k] = {t.batches + kept_[k].batches, t.rays + kept_[k].rays, t.fine_batches + kept_[k].fine_batches};
            f.batches[k].sorts_dropped = sorts_dropped_[k];
        }
    }
    sorted_->report(report);
}

}  // namespace rt
