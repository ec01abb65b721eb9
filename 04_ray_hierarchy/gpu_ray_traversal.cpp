// Stage 04's traversal, the pairs' side of GpuRayHierarchy (gpu_ray_hierarchy.h): candidate pairs (ray side, object
// side) from the top, tested and their children counted and placed (rh_cull.comp), expanded (rh_expand.comp) step by
// step, depth first, window by window; the (ray, triangle) pairs of the last step to the leaves (rh_leaf.comp), and for
// closest hits the fold (rh_fold.comp, rh_closest.glsl). The groups, the rays' build and the stats are in
// gpu_ray_hierarchy.cpp, the objects' side in gpu_object_tree.cpp.
#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

#include "gpu_ray_hierarchy.h"
#include "gpu_ray_hierarchy_detail.h"

namespace rt {

namespace {
using gpu::Program;
using namespace rh_detail;
}  // namespace

// The buffers of one step of the traversal, with rh_cull.comp's counts and group places for `pairs` pairs tested
// there (only a step cut into windows for rh_expand.comp needs them: 0 otherwise). Grown as needed, never shrunk.
void GpuRayHierarchy::step_buffers(int step, std::size_t pairs) {
    if (int(pairs_.size()) <= step) {
        pairs_.resize(step + 1);
        counts_.resize(step + 1);
        offsets_.resize(step + 1);
    }
    counts_[step].reserve(pairs * 4);
    offsets_[step].reserve((pairs / 64 + 1) * 4);   // the work groups' first output places
}

void GpuRayHierarchy::set_source(const Program& p, const Source& s) const {
    p.set("rh_implicit", s.implicit ? 1u : 0u);
    p.set("rh_pair_first", s.pair_first);
    p.set("rh_top_level", unsigned(top_));
    p.set("rh_node_first", s.node_first);
    p.set("rh_item_first", s.item_first);
    p.set("rh_item_count", std::max<std::uint32_t>(s.item_count, 1));
    p.set("rh_item_flag", s.item_flag);
}

// The top's pairs are every top node with every item (triangles, mesh objects or the tree's top level): implicit
// chunks of at most capacity() pairs, whole rows of items when a row fits.
void GpuRayHierarchy::traverse(int top) {
    top_ = top;
    // Every split takes one side one level down, so after this many steps only (ray, triangle) pairs are left.
    const int object_steps = options.objects == ObjectMode::tree     ? int(object_levels())
                             : options.objects == ObjectMode::meshes ? 1
                                                                     : 0;
    max_depth_ = top + object_steps;
    const bool triangles = options.objects == ObjectMode::triangles;
    const std::uint32_t items = std::uint32_t(triangles ? triangles_ : objects_);
    const std::uint32_t item_first = triangles ? 0u : object_level_first_.back();
    const std::uint32_t flag = triangles ? kTriangleFlag : 0u;
    const std::uint32_t nodes = level_nodes_[top];
    const std::uint32_t cap = std::uint32_t(capacity_);
    if (items <= cap) {
        const std::uint32_t per_chunk = cap / items;
        for (std::uint32_t n0 = 0; n0 < nodes; n0 += per_chunk) {
            const std::uint32_t k = std::min(per_chunk, nodes - n0);
            test_chunk(0, Source{true, 0, n0, item_first, items, flag}, k * items, false);
        }
    } else {
        for (std::uint32_t n0 = 0; n0 < nodes; ++n0)
            for (std::uint32_t i0 = 0; i0 < items; i0 += cap) {
                const std::uint32_t k = std::min(cap, items - i0);
                test_chunk(0, Source{true, 0, n0, item_first + i0, k, flag}, k, false);
            }
    }
}

// One chunk of pairs at one step of the traversal: test and place, the leaves' pairs to rh_leaf.comp, then the
// children expanded window by window, each window traced on before the next (depth first, so each step needs one
// buffer of capacity() pairs).
//
// `on_gpu`: the chunk's length is known on the GPU only (rh_info[kInfoStepCount + step], args_ holds its dispatch),
// and `count` is a bound of it. While the children of a chunk cannot outnumber one window (count x the most
// children a pair has), or always in a speculative batch (gpu_ray_hierarchy.h), the test pass writes them itself and
// the traversal goes on without reading anything back: the next step's passes are dispatched indirectly. Otherwise
// the chunk's counts are read back (one sync), to cut it into windows for rh_expand.comp.
void GpuRayHierarchy::test_chunk(int step, const Source& src, std::uint32_t count, bool on_gpu) {
    if (step > kMaxSteps) throw std::logic_error("04_ray_hierarchy: more traversal steps than rh_info.glsl holds");
    step_buffers(step, 0);
    const std::uint32_t b = std::uint32_t(options.branching);
    const std::uint32_t slot = kInfoStepCount + std::uint32_t(step);
    std::uint32_t total = 0;
    // The most children one pair of this chunk can have: B rays, kObjectBranching tree nodes or a cluster's
    // kClusterSize triangles (the same number), or a mesh object's triangles (only at the top: below it every object
    // side is a triangle).
    const std::uint64_t most =
        options.objects == ObjectMode::meshes && step == 0 ? 4096 : std::max<std::uint32_t>(b, kObjectBranching);
    // Every split takes one side one level down, so all pairs of a step are equally deep: the last step holds only
    // (ray, triangle) pairs, and only it does. They go to the leaves; the other steps are tested and expanded.
    if (step >= max_depth_) {
        ++chunks;
        leaves(step, count, on_gpu);
        return;
    }
    // While the children cannot outnumber one window, the test pass writes them itself (rh_cull.comp compiled with
    // RH_CULL_WRITES_CHILDREN) and the traversal goes on without reading anything back; a speculative batch always
    // does, and the pass marks the group when they do not fit (rh_info.glsl: rh_mark_overflow).
    const bool chain = speculative_ || std::uint64_t(count) * most <= capacity_;
    const std::uint32_t cap = std::uint32_t(capacity_);
    {
        std::optional<gpu::GpuTimer::Scope> timed;
        if (timer) timed.emplace(*timer, phase("rh_traverse"));
        const std::uint32_t zero = 0;   // the children's count, which rh_cull.comp's groups add to
        info_.upload(&zero, sizeof zero, (slot + 1) * sizeof zero);
        const Program& cull = chain ? cull_children_ : cull_;
        in_->rays.bind(gpu::kWavefrontBindingRaysIn);
        nodes_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
        objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
        if (!src.implicit) pairs_[step].bind(gpu::kWavefrontBindingTraversalFirst + 3);
        info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
        if (chain) {   // the children, in one window
            step_buffers(step + 1, 0);
            pairs_[step + 1].reserve(std::size_t(cap) * 8);
            pairs_[step + 1].bind(gpu::kWavefrontBindingTraversalFirst + 4);
            order_.bind(gpu::kWavefrontBindingTraversalFirst + 5);   // rh_common.glsl: RH_BINDING_CULL_ORDER
            // The next step's dispatch, written by the pass's last work group; zero until then, so that when no
            // group runs (a chunk of no pairs) the next step has no groups either, not an earlier chunk's.
            const std::uint32_t no_groups[3] = {0, 1, 1};
            args_.upload(no_groups, sizeof no_groups, std::size_t(step + 1) * 12);
            args_.bind(gpu::kWavefrontBindingTraversalFirst + 6);
            cull.set("rh_identity_order", options.objects == ObjectMode::tree ? 0u : 1u);
            cull.set("rh_args_first", unsigned(step + 1) * 3);
            cull.set("rh_window_room", cap);
            cull.set("rh_overflow_mark", group_mark_);
        } else {   // the counts and the groups' first places, for rh_expand.comp's windows
            step_buffers(step, count);
            counts_[step].bind(gpu::kWavefrontBindingTraversalFirst + 5);
            offsets_[step].bind(gpu::kWavefrontBindingTraversalFirst + 4);
        }
        set_source(cull, src);
        cull.set("rh_group_first", unsigned(in_->first + group_.first));
        cull.set("rh_branching", b);
        cull.set("rh_split_by_width", options.objects == ObjectMode::tree ? 1u : 0u);
        cull.set("rh_box_test", options.box_test ? 1u : 0u);
        cull.set("rh_children_slot", slot + 1);
        dispatch_chunk(cull, step, count, on_gpu);
        if (!chain) {   // the chunk's length (when only the GPU knows it) and its children's, in one read-back
            const std::vector<std::uint32_t> lengths = read_info(int(slot), 2);
            if (on_gpu) count = lengths[0];
            on_gpu = false;
            total = lengths[1];
        }
        ++chunks;
    }
    if (chain) {   // one window of at most `cap` pairs, whatever the GPU found; the test pass wrote its dispatch
        ++windows;
        const auto bound = std::uint32_t(std::min<std::uint64_t>(std::uint64_t(count) * most, cap));
        test_chunk(step + 1, Source{false, 0, 0, 0, 0, 0}, bound, true);
        return;
    }
    if (total > cap) fitted_ = false;   // a speculative try would have run out of room here
    for (std::uint32_t w0 = 0; w0 < total; w0 += cap) {
        const std::uint32_t w = std::min(cap, total - w0);
        expand(step, src, count, false, w0, w);
        test_chunk(step + 1, Source{false, 0, 0, 0, 0, 0}, w, false);
    }
}

// A pass over a chunk of `count` pairs (rh_pairs.glsl: rh_chunk_count): dispatched for them, or, on_gpu, indirectly
// for the length the GPU wrote to the step's slot (count is then only a bound).
void GpuRayHierarchy::dispatch_chunk(const Program& p, int step, std::uint32_t count, bool on_gpu) const {
    p.set("rh_count", count);
    p.set("rh_count_slot", on_gpu ? kInfoStepCount + std::uint32_t(step) : 0u);
    if (on_gpu)
        p.dispatch_indirect(args_, std::size_t(step) * 12);
    else
        p.dispatch_threads(count);
    barrier();
}

// The children of a chunk's survivors with outputs in [w0, w0 + w) to pairs_[step + 1].
void GpuRayHierarchy::expand(int step, const Source& src, std::uint32_t count, bool on_gpu, std::uint32_t w0,
                             std::uint32_t w) {
    std::optional<gpu::GpuTimer::Scope> timed;
    if (timer) timed.emplace(*timer, phase("rh_traverse"));
    step_buffers(step + 1, 0);
    pairs_[step + 1].reserve(std::size_t(w) * 8);
    order_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
    objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
    if (!src.implicit) pairs_[step].bind(gpu::kWavefrontBindingTraversalFirst + 3);
    pairs_[step + 1].bind(gpu::kWavefrontBindingTraversalFirst + 4);
    counts_[step].bind(gpu::kWavefrontBindingTraversalFirst + 5);
    offsets_[step].bind(gpu::kWavefrontBindingTraversalFirst + 6);
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    set_source(expand_, src);
    expand_.set("rh_window_first", w0);
    expand_.set("rh_window_count", w);
    expand_.set("rh_branching", unsigned(options.branching));
    expand_.set("rh_identity_order", options.objects == ObjectMode::tree ? 0u : 1u);
    dispatch_chunk(expand_, step, count, on_gpu);
    ++windows;
}

// The last step's chunk of `count` (ray, triangle) pairs (a bound of them, on_gpu) to rh_leaf.comp.
void GpuRayHierarchy::leaves(int step, std::uint32_t count, bool on_gpu) {
    const std::uint32_t leaf_pairs = count;
    if (shadow_ || speculative_) {   // a speculative batch: a hit past the list's end marks the group
        leaf_dispatch(step, 0, count, on_gpu);
        return;
    }
    // The hit list holds hit_capacity_ entries: a chunk goes in once there is room for all of its leaf pairs (each
    // may add one hit); when there is not, hits left behind by closer ones are pruned, and the chunk is split if
    // needed (a part of n pairs holds at most n leaf pairs). Only a batch whose rays all keep 4 hits within the tie
    // range would fill it: then a clear error, not a dropped hit.
    const std::uint64_t cap = hit_capacity_;
    if (hits_bound_ + leaf_pairs > cap) {
        hits_bound_ = read_info(1);
        if (hits_bound_ + leaf_pairs > cap) {
            prune_hits();
            hits_bound_ = read_info(1);
        }
    }
    if (hits_bound_ + leaf_pairs <= cap) {
        leaf_dispatch(step, 0, count, on_gpu);
        hits_bound_ += leaf_pairs;
        return;
    }
    if (on_gpu) {   // the chunk is cut into parts by its length: read it
        count = read_info(int(kInfoStepCount) + step);
        on_gpu = false;
    }
    for (std::uint32_t first = 0; first < count;) {
        if (hits_bound_ + (count - first) > cap) {
            hits_bound_ = read_info(1);
            if (hits_bound_ + (count - first) > cap) {
                prune_hits();
                hits_bound_ = read_info(1);
            }
        }
        const std::uint64_t room = cap - hits_bound_;
        if (room == 0)
            throw std::runtime_error("04_ray_hierarchy: more than " + std::to_string(cap) +
                                     " hits within the tie range of their rays' closest hits (the hit list is full)");
        const std::uint32_t n = std::uint32_t(std::min<std::uint64_t>(room, count - first));
        leaf_dispatch(step, first, n, false);
        hits_bound_ += n;
        first += n;
    }
}

void GpuRayHierarchy::leaf_dispatch(int step, std::uint32_t first, std::uint32_t count, bool on_gpu) {
    std::optional<gpu::GpuTimer::Scope> timed;
    if (timer) timed.emplace(*timer, phase("rh_local"));
    const Program& p = shadow_ ? leaf_shadow_ : leaf_closest_;
    const gpu::BatchTraceInputs& in = *in_;
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    in.results.bind(gpu::kWavefrontBindingResults);
    if (in.tests_per_pixel) in.tests_per_pixel->bind(gpu::kWavefrontBindingTestsPerPixel);
    pairs_[step].bind(gpu::kWavefrontBindingTraversalFirst + 3);
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    if (!shadow_) {
        hits_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
        state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    }
    in.wavefront.set_uniforms(p);
    set_source(p, Source{false, first, 0, 0, 0, 0});
    p.set("rh_group_first", unsigned(in.first + group_.first));
    p.set("rh_batch_first", unsigned(in.first));
    p.set("rh_sphere_test", options.sphere_test ? 1u : 0u);
    p.set("rh_box_test", options.box_test ? 1u : 0u);
    p.set("rh_hit_room", std::uint32_t(hit_capacity_));
    p.set("rh_overflow_mark", group_mark_);
    dispatch_chunk(p, step, count, on_gpu);
}

void GpuRayHierarchy::prune_hits() {
    fitted_ = false;   // the list was full, or nearly: a speculative try might not have fitted
    const std::uint32_t used = read_info(1);
    ++prunes;
    prune_flags_.reserve(hit_capacity_ * 4);
    prune_offsets_.reserve(hit_capacity_ * 4);
    hits_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
    state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    prune_flags_.bind(gpu::kWavefrontBindingTraversalFirst + 6);
    fold_.set("rh_mode", 4u);
    fold_.set("rh_count", used);
    fold_.dispatch_threads(used);
    barrier();
    scan_.exclusive_flags(prune_flags_, prune_offsets_, used, &info_, 4);   // the kept count: the length
    hits_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
    state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    prune_offsets_.bind(gpu::kWavefrontBindingTraversalFirst + 6);
    hits_tmp_.bind(gpu::kWavefrontBindingTraversalFirst + 3);
    fold_.set("rh_mode", 5u);
    fold_.dispatch_threads(used);
    barrier();
    std::swap(hits_, hits_tmp_);
}

// Step 2 of rh_closest.glsl: one listed hit per ray and round, in increasing triangle id, until none is left. The
// rounds run kFoldRoundsPerRead at a time with nothing read back: the select pass is dispatched indirectly for the
// hit list's length (rh_args.comp), and a round with nothing left to fold changes nothing (no ray has a `next`). Only
// then is the flag of the last select read: 0 means every ray was folded. Most rays list one hit, so one read per
// batch is the rule. `first_look` (a speculative batch): the first read also takes the group mark and the hit list's
// length (rh_info words 0 and 1, into *first_look); a mark returns false at once (the rounds changed nothing), true
// when the batch is folded.
bool GpuRayHierarchy::fold(const gpu::BatchTraceInputs& in, std::vector<std::uint32_t>* first_look) {
    std::optional<gpu::GpuTimer::Scope> timed;
    if (timer) timed.emplace(*timer, "rh_local.fold");
    const std::uint32_t n = std::uint32_t(in.count);
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    in.results.bind(gpu::kWavefrontBindingResults);
    if (in.tests_per_pixel) in.tests_per_pixel->bind(gpu::kWavefrontBindingTestsPerPixel);
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    args_.bind(gpu::kWavefrontBindingTraversalFirst + 6);
    args_pass_.set("rh_slot", 1u);   // rh_info.glsl: RH_INFO_HITS, the hit list's length
    args_pass_.set("rh_args_first", 0u);   // words 0-2: the top step's, never dispatched indirectly
    args_pass_.dispatch(1);
    barrier();
    hits_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
    state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    in.wavefront.set_uniforms(fold_);
    fold_.set("rh_batch_first", unsigned(in.first));
    for (;;) {
        for (int round = 0; round < kFoldRoundsPerRead; ++round) {
            const std::uint32_t zero = 0;
            info_.upload(&zero, 4, 8);
            fold_.set("rh_mode", 1u);
            fold_.set("rh_count", std::uint32_t(hit_capacity_));   // the shader stops at the list's length
            fold_.dispatch_indirect(args_, 0);
            barrier();
            ++fold_rounds;
            fold_.set("rh_mode", 2u);
            fold_.set("rh_count", n);
            fold_.dispatch_threads(n);
            barrier();
        }
        if (first_look) {
            std::vector<std::uint32_t>& look = *first_look;
            look = read_info(0, 3);
            first_look = nullptr;
            if (look[0] != 0) return false;
            if (look[2] == 0) break;
        } else if (read_info(2) == 0) {
            break;
        }
    }
    fold_.set("rh_mode", 3u);
    fold_.set("rh_count", n);
    fold_.dispatch_threads(n);
    barrier();
    // The fold's re-tests per ray kind (rh_info.glsl: RH_INFO_FOLD_TESTS + kind) into the GPU's sums.
    tally_.bind(gpu::kWavefrontBindingTraversalFirst + 6);
    tally_pass_.set("rh_mode", 1u);
    tally_pass_.dispatch(1);
    barrier();
    return true;
}

}  // namespace rt
