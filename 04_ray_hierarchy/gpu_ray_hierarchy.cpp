#include "gpu_ray_hierarchy.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

namespace rt {

namespace {
using gpu::Buffer;
using gpu::Program;

constexpr std::size_t kMaxCapacity = std::size_t(1) << 20;   // entries per buffer: 16 MiB of (node, triangle) pairs
constexpr std::uint32_t kTriangleFlag = 0x80000000u;          // rh_common.glsl: RH_TRIANGLE_FLAG
constexpr std::uint32_t kMaxRayIndex = 1u << 27;              // RH_RAY_INDEX_BITS
constexpr int kMaxRayLevels = 32;                             // rh_cull.comp's level tables
// rh_info.glsl
constexpr std::uint32_t kInfoWords = 224, kInfoExact = 10, kInfoObjectIn = 12, kInfoObjectOut = 14,
                        kInfoLevelIn = 16, kInfoLevelOut = 80, kInfoLeafPairs = 144, kInfoStepCount = 160, kInfoGroupFirst = 8;
constexpr int kMaxSteps = 63;   // rh_info.glsl: RH_INFO_STEP_COUNT slots
// rh_tally.comp: per ray kind, the 64-bit sums of rh_info's words kInfoExact .. kInfoLeafPairs + 1, then the sphere
// tests and the fold tests.
constexpr std::uint32_t kTallyWords = 144, kTallyGroupPairs = 68, kTallySphere = 136, kTallyFold = 138;
// rh_groups.comp's list [count, (first ray, kind) per group]: the groups read back at once (more take a second read).
constexpr std::uint32_t kGroupsAtOnce = 64;

void barrier() {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

std::uint64_t word64(const std::uint32_t* w, std::uint32_t i) { return std::uint64_t(w[i + 1]) << 32 | w[i]; }
}  // namespace

std::vector<ObjectRange> object_ranges(const std::vector<std::uint32_t>& material_ids, std::uint32_t max_count) {
    std::vector<ObjectRange> objects;
    for (std::uint32_t i = 0; i < material_ids.size(); ++i) {
        if (objects.empty() || objects.back().count == max_count || material_ids[i] != material_ids[i - 1])
            objects.push_back({i, 0});
        ++objects.back().count;
    }
    return objects;
}

std::uint64_t HierarchyKindStats::node_tests() const {
    std::uint64_t n = 0;
    for (const HierarchyLevelStats& l : levels) n += l.pairs_in;
    return n - leaf_pairs;
}

std::vector<std::string> GpuRayHierarchy::program_names() {
    std::vector<std::string> names;
    for (const char* p : {"rh_spheres.comp", "ot_build.comp", "rh_heads.comp", "rh_groups.comp", "rh_build.comp",
                          "rh_cull.comp", "rh_expand.comp", "rh_leaf.comp", "rh_fold.comp", "rh_args.comp",
                          "rh_tally.comp"})
        names.push_back(std::string("04_ray_hierarchy/shaders/") + p);
    return names;
}

GpuRayHierarchy::GpuRayHierarchy()
    : info_(kInfoWords * sizeof(std::uint32_t)), group_count_(sizeof(std::uint32_t)),
      tally_(std::size_t(kRayKinds) * kTallyWords * sizeof(std::uint32_t)),
      args_((kMaxSteps + 1) * 3 * sizeof(std::uint32_t)) {
    reset_stats();
}

void GpuRayHierarchy::reset_stats() {
    cpu_stats_ = stats_ = {};
    tally_.clear_u32(0);
    tally_read_ = true;
    fold_rounds = prunes = chunks = windows = syncs = 0;
}

// The CPU's own counts plus the GPU's sums (one read-back, only when a trace ran since the last one).
const std::array<HierarchyKindStats, kRayKinds>& GpuRayHierarchy::stats() {
    if (tally_read_) return stats_;
    std::vector<std::uint32_t> t = tally_.download<std::uint32_t>(std::size_t(kRayKinds) * kTallyWords);
    ++syncs;
    tally_read_ = true;
    stats_ = cpu_stats_;
    for (int k = 0; k < kRayKinds; ++k) {
        const std::uint32_t* w = t.data() + std::size_t(k) * kTallyWords;
        auto sum = [&](std::uint32_t info_word) { return word64(w, info_word - kInfoExact); };
        HierarchyKindStats& ks = stats_[std::size_t(k)];
        for (std::size_t l = 0; l < ks.levels.size(); ++l) {
            ks.levels[l].pairs_in += sum(kInfoLevelIn + 2 * std::uint32_t(l));
            ks.levels[l].pairs_out += sum(kInfoLevelOut + 2 * std::uint32_t(l));
        }
        const std::uint64_t exact = sum(kInfoExact), leaf_pairs = sum(kInfoLeafPairs);
        ks.leaf_pairs += leaf_pairs;
        ks.sphere_tests += word64(w, kTallySphere);
        if (!ks.levels.empty()) {
            ks.levels[0].pairs_in += leaf_pairs;
            ks.levels[0].pairs_out += exact;
        }
        ks.object_pairs_in += sum(kInfoObjectIn);
        ks.object_pairs_out += sum(kInfoObjectOut);
        ks.local_tests += exact;
        ks.fold_tests += word64(w, kTallyFold);
    }
    return stats_;
}

void GpuRayHierarchy::compile(const gpu::Wavefront& wavefront) {
    std::string key;
    for (const auto& [name, value] : wavefront.defines()) key += name + "=" + value + ";";
    if (key == key_ && spheres_) return;
    const gpu::ShaderDefines& d = wavefront.defines();
    spheres_ = Program::compute("04_ray_hierarchy/shaders/rh_spheres.comp", d);
    tree_ = Program::compute("04_ray_hierarchy/shaders/ot_build.comp", d);
    build_ = Program::compute("04_ray_hierarchy/shaders/rh_build.comp", d);
    heads_ = Program::compute("04_ray_hierarchy/shaders/rh_heads.comp", d);
    groups_ = Program::compute("04_ray_hierarchy/shaders/rh_groups.comp", d);
    cull_ = Program::compute("04_ray_hierarchy/shaders/rh_cull.comp", d);
    expand_ = Program::compute("04_ray_hierarchy/shaders/rh_expand.comp", d);
    leaf_closest_ = Program::compute("04_ray_hierarchy/shaders/rh_leaf.comp", d);
    gpu::ShaderDefines shadow = d;
    shadow.emplace("RH_SHADOW", "1");
    shadow.emplace("RT_SHADOW_RAYS", "1");   // the shadow rule of the opacity test (opacity.glsl)
    leaf_shadow_ = Program::compute("04_ray_hierarchy/shaders/rh_leaf.comp", shadow);
    fold_ = Program::compute("04_ray_hierarchy/shaders/rh_fold.comp", d);
    args_pass_ = Program::compute("04_ray_hierarchy/shaders/rh_args.comp", d);
    tally_pass_ = Program::compute("04_ray_hierarchy/shaders/rh_tally.comp", d);
    key_ = key;
}

std::uint32_t GpuRayHierarchy::read_info(int index) {
    ++syncs;
    return info_.download_value<std::uint32_t>(index);
}

std::string GpuRayHierarchy::phase(const char* name) const {
    return std::string(name) + "." + ray_kind_name(RayKind(group_.kind));
}

// The buffers of one step of the traversal, for `pairs` pairs tested there (grown as needed, never shrunk).
void GpuRayHierarchy::step_buffers(int step, std::size_t pairs) {
    if (int(pairs_.size()) <= step) {
        pairs_.resize(step + 1);
        counts_.resize(step + 1);
        offsets_.resize(step + 1);
    }
    counts_[step].reserve(pairs * 4);
    offsets_[step].reserve((pairs / 64 + 1) * 4);   // the work groups' offsets
    group_sums_.reserve((capacity_ / 64 + 1) * 4);
}

void GpuRayHierarchy::trace(const gpu::BatchTraceInputs& in, bool shadow) {
    compile(in.wavefront);
    in_ = &in;
    shadow_ = shadow;
    capacity_ = std::clamp<std::size_t>(in.wavefront.storage_limit() / 16, 64, kMaxCapacity);
    if (options.pair_capacity > 0) capacity_ = std::min(capacity_, std::max<std::size_t>(options.pair_capacity, 16));
    const std::uint32_t n = std::uint32_t(in.count);
    if (n >= kMaxRayIndex)
        throw std::runtime_error("04_ray_hierarchy: a batch of " + std::to_string(n) + " rays exceeds the " +
                                 std::to_string(kMaxRayIndex) + " a pair can name");
    // The hit list: 4 entries per ray (every ray keeps its closest hits after a prune; a ray of the batch takes 64
    // bytes in the queue, so 4 x 16 bytes per ray fit the storage limit too), or capacity() when that is more.
    const std::size_t per_ray = std::size_t(std::clamp(options.hit_list_per_ray, 1, 4));
    hit_capacity_ = options.hit_list_per_ray < 4 ? per_ray * n : std::max<std::size_t>(capacity_, per_ray * n);
    if (n == 0) return;

    // Results start as "nothing hit".
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    in.results.bind(gpu::kWavefrontBindingResults);
    if (in.tests_per_pixel) in.tests_per_pixel->bind(gpu::kWavefrontBindingTestsPerPixel);
    info_.clear_u32(0);
    if (shadow) {
        in.results.clear_u32(0);
    } else {
        state_.reserve(std::size_t(n) * 32);
        hits_.reserve(hit_capacity_ * 16);
        hits_tmp_.reserve(hit_capacity_ * 16);
        state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
        in.wavefront.set_uniforms(fold_);
        fold_.set("rh_mode", 0u);
        fold_.set("rh_count", n);
        fold_.dispatch_threads(n);
        barrier();
        hits_bound_ = 0;
    }

    for (const Group& g : find_groups(in)) {
        group_ = g;
        HierarchyKindStats& ks = cpu_stats_[g.kind];
        ks.rays += g.count;
        ks.groups += 1;
        ks.brute_force_tests += std::uint64_t(g.count) * triangles_;
        if (triangles_ == 0 || (options.objects != ObjectMode::triangles && objects_ == 0)) continue;
        const int top = build(in, g);
        const std::vector<std::uint32_t> zeros(kInfoWords - kInfoGroupFirst, 0u);
        info_.upload(zeros.data(), zeros.size() * 4, kInfoGroupFirst * 4);
        traverse(top);
        tally_group();
    }
    if (!shadow) fold(in);
    tally_read_ = false;
    gpu::check_gl("04_ray_hierarchy: trace");
}

// The group's counts (rh_info.glsl: per ray level the pairs tested and kept, the object level's, the exact tests)
// added to the GPU's sums per ray kind, and its exact tests to the pipeline's test counters, on the GPU: nothing is
// read back per group (stats() reads the sums once).
void GpuRayHierarchy::tally_group() {
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    tally_.bind(gpu::kWavefrontBindingTraversalFirst + 6);
    tally_pass_.set("rh_mode", 0u);
    tally_pass_.set("rh_kind", group_.kind);
    tally_pass_.set("rh_sphere_test", options.sphere_test ? 1u : 0u);
    tally_pass_.dispatch_threads(kTallyGroupPairs + 2);
    barrier();
}

std::vector<GpuRayHierarchy::Group> GpuRayHierarchy::find_groups(const gpu::BatchTraceInputs& in) {
    const std::uint32_t n = std::uint32_t(in.count);
    head_flags_.reserve(std::size_t(n) * 4);
    group_heads_.reserve(std::size_t(n) * 4);
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    head_flags_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    heads_.set("wf_input_first", unsigned(in.first));
    heads_.set("wf_input_count", n);
    heads_.dispatch_threads(n);
    barrier();
    compaction_.compact_indices(head_flags_, n, group_heads_, group_count_);
    // One list [count, (first ray, kind) per group] (rh_groups.comp), read back at once.
    group_list_.reserve((1 + 2 * std::size_t(n)) * 4);
    group_heads_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    group_count_.bind(gpu::kWavefrontBindingTraversalFirst + 6);
    group_list_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
    groups_.set("wf_input_first", unsigned(in.first));
    groups_.set("wf_input_count", n);
    groups_.dispatch_threads(n);
    barrier();
    std::vector<std::uint32_t> list = group_list_.download<std::uint32_t>(1 + 2 * std::min(n, kGroupsAtOnce));
    ++syncs;
    const std::uint32_t count = list[0];
    if (count > kGroupsAtOnce) {   // more groups than the first read holds: the rest in a second one
        list = group_list_.download<std::uint32_t>(1 + 2 * std::size_t(count));
        ++syncs;
    }
    std::vector<Group> groups;
    for (std::uint32_t i = 0; i < count; ++i) {
        Group g;
        g.first = list[1 + 2 * i];
        g.count = (i + 1 < count ? list[1 + 2 * (i + 1)] : n) - g.first;
        g.kind = std::min<std::uint32_t>(list[2 + 2 * i], std::uint32_t(kRayKinds - 1));
        groups.push_back(g);
    }
    return groups;
}

// Bottom-up, one dispatch per level; returns the top level (>= 1).
int GpuRayHierarchy::build(const gpu::BatchTraceInputs& in, const Group& g) {
    std::optional<gpu::GpuTimer::Scope> timed;
    if (timer) timed.emplace(*timer, phase("rh_build"));
    const std::uint32_t b = std::uint32_t(options.branching);
    level_first_.assign(1, 0);
    level_nodes_.assign(1, g.count);
    std::uint32_t total = 0;
    for (std::uint32_t n = g.count;;) {
        n = (n + b - 1) / b;
        level_first_.push_back(total);
        level_nodes_.push_back(n);
        total += n;
        const int upper = int(level_nodes_.size()) - 1;
        if (n <= 1 || (options.levels > 0 && upper >= options.levels) || upper + 1 >= kMaxRayLevels) break;
    }
    nodes_.reserve(std::size_t(total) * 32);
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    nodes_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
    for (std::size_t l = 1; l < level_nodes_.size(); ++l) {
        build_.set("rh_from_rays", l == 1 ? 1u : 0u);
        build_.set("rh_child_first", l == 1 ? unsigned(in.first + g.first) : level_first_[l - 1]);
        build_.set("rh_child_count", level_nodes_[l - 1]);
        build_.set("rh_parent_first", level_first_[l]);
        build_.set("rh_parent_count", level_nodes_[l]);
        build_.set("rh_branching", b);
        build_.dispatch_threads(level_nodes_[l]);
        barrier();
    }
    HierarchyKindStats& ks = cpu_stats_[g.kind];
    if (ks.levels.size() < level_nodes_.size()) ks.levels.resize(level_nodes_.size());
    for (std::size_t l = 0; l < level_nodes_.size(); ++l) ks.levels[l].nodes += level_nodes_[l];
    // The level tables of rh_cull.comp.
    std::vector<unsigned> first(kMaxRayLevels, 0u), nodes(kMaxRayLevels, 0u);
    std::copy(level_first_.begin(), level_first_.end(), first.begin());
    std::copy(level_nodes_.begin(), level_nodes_.end(), nodes.begin());
    cull_.set("rh_level_first", first);
    cull_.set("rh_level_nodes", nodes);
    return int(level_nodes_.size()) - 1;
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
    max_depth_ = top + int(options.objects == ObjectMode::tree ? object_levels() : options.objects == ObjectMode::meshes ? 1 : 0);
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

// One chunk of pairs at one step of the traversal: test, scan, the leaves' pairs to rh_leaf.comp, then the
// children expanded window by window, each window traced on before the next (depth first, so each step needs one
// buffer of capacity() pairs).
//
// `on_gpu`: the chunk's length is known on the GPU only (rh_info[kInfoStepCount + step], args_ holds its dispatch),
// and `count` is a bound of it. While the children of a chunk cannot outnumber one window (count x the most
// children a pair has), the traversal goes on without reading anything back: the passes are dispatched indirectly.
// Only when that bound passes capacity() are the chunk's counts read back (one sync), to cut it into windows.
void GpuRayHierarchy::test_chunk(int step, const Source& src, std::uint32_t count, bool on_gpu) {
    if (step > kMaxSteps) throw std::logic_error("04_ray_hierarchy: more traversal steps than rh_info.glsl holds");
    step_buffers(step, count);
    const std::uint32_t b = std::uint32_t(options.branching);
    const std::uint32_t slot = kInfoStepCount + std::uint32_t(step);
    std::uint32_t total = 0;
    // The most children one pair of this chunk can have: B rays, 4 tree nodes or a cluster's 4 triangles, or a mesh
    // object's triangles (only at the top: below it every object side is a triangle).
    const std::uint64_t most = options.objects == ObjectMode::meshes && step == 0 ? 4096 : std::max<std::uint32_t>(b, 4);
    // Every split takes one side one level down, so all pairs of a step are equally deep: the last step holds only
    // (ray, triangle) pairs, and only it does. They go to the leaves; the other steps are tested and expanded.
    if (step >= max_depth_) {
        ++chunks;
        leaves(step, count, on_gpu);
        return;
    }
    const bool chain = std::uint64_t(count) * most <= capacity_;
    {
        std::optional<gpu::GpuTimer::Scope> timed;
        if (timer) timed.emplace(*timer, phase("rh_traverse"));
        if (on_gpu) group_sums_.clear_u32(0);   // the scan reads the sums of every work group the bound may need
        in_->rays.bind(gpu::kWavefrontBindingRaysIn);
        nodes_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
        spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
        objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
        if (!src.implicit) pairs_[step].bind(gpu::kWavefrontBindingTraversalFirst + 3);
        counts_[step].bind(gpu::kWavefrontBindingTraversalFirst + 5);
        info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
        group_sums_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
        set_source(cull_, src);
        cull_.set("rh_group_first", unsigned(in_->first + group_.first));
        cull_.set("rh_branching", b);
        cull_.set("rh_split_larger", options.objects == ObjectMode::tree ? 1u : 0u);
        dispatch_chunk(cull_, step, count, on_gpu);
        const std::size_t groups = (std::size_t(count) + 63) / 64;
        compaction_.scan().exclusive(group_sums_, offsets_[step], groups, &info_, (slot + 1) * 4);
        if (!chain) {
            if (on_gpu) count = read_info(int(slot));
            on_gpu = false;
            total = read_info(int(slot) + 1);
        }
        ++chunks;
    }
    const std::uint32_t cap = std::uint32_t(capacity_);
    if (chain) {   // one window of at most `cap` pairs, whatever the GPU found
        expand(step, src, count, on_gpu, 0, cap);
        {
            std::optional<gpu::GpuTimer::Scope> timed;
            if (timer) timed.emplace(*timer, phase("rh_traverse"));
            info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
            args_.bind(gpu::kWavefrontBindingTraversalFirst + 6);
            args_pass_.set("rh_slot", slot + 1);
            args_pass_.set("rh_args_first", unsigned(step + 1) * 3);
            args_pass_.dispatch(1);
            barrier();
        }
        test_chunk(step + 1, Source{false, 0, 0, 0, 0, 0}, std::uint32_t(std::min<std::uint64_t>(std::uint64_t(count) * most, cap)), true);
        return;
    }
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
    if (shadow_) {
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
    dispatch_chunk(p, step, count, on_gpu);
}

void GpuRayHierarchy::prune_hits() {
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
    compaction_.scan().exclusive_flags(prune_flags_, prune_offsets_, used, &info_, 4);   // the kept count: the length
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

// Step 2 of rh_closest.glsl: one listed hit per ray and round, in increasing triangle id, until none is left.
void GpuRayHierarchy::fold(const gpu::BatchTraceInputs& in) {
    std::optional<gpu::GpuTimer::Scope> timed;
    if (timer) timed.emplace(*timer, "rh_local.fold");
    const std::uint32_t n = std::uint32_t(in.count);
    const std::uint32_t used = read_info(1);
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    in.results.bind(gpu::kWavefrontBindingResults);
    if (in.tests_per_pixel) in.tests_per_pixel->bind(gpu::kWavefrontBindingTestsPerPixel);
    hits_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
    state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    in.wavefront.set_uniforms(fold_);
    fold_.set("rh_batch_first", unsigned(in.first));
    for (;;) {
        const std::uint32_t zero = 0;
        info_.upload(&zero, 4, 8);
        fold_.set("rh_mode", 1u);
        fold_.set("rh_count", used);
        if (used > 0) fold_.dispatch_threads(used);
        barrier();
        if (read_info(2) == 0) break;
        ++fold_rounds;
        fold_.set("rh_mode", 2u);
        fold_.set("rh_count", n);
        fold_.dispatch_threads(n);
        barrier();
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
}

}  // namespace rt
