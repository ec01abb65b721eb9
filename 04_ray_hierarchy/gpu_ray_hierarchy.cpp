// Stage 04's GPU hierarchy (gpu_ray_hierarchy.h), the rays' side: a batch's groups, the hierarchy built over each
// group's rays, bottom-up, and the stats the GPU sums for them. The traversal, the leaves and the fold are in
// gpu_ray_traversal.cpp, the objects' side in gpu_object_tree.cpp.
#include "gpu_ray_hierarchy.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "gpu_ray_hierarchy_detail.h"

namespace rt {

namespace {
using gpu::Buffer;
using gpu::Program;
using namespace rh_detail;
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

std::vector<std::string> GpuRayHierarchy::program_names() {
    std::vector<std::string> names;
    for (const char* p : {"rh_spheres.comp", "ot_build.comp", "rh_build.comp", "rh_cull.comp", "rh_expand.comp",
                          "rh_leaf.comp", "rh_fold.comp", "rh_args.comp", "rh_tally.comp"})
        names.push_back(std::string("04_ray_hierarchy/shaders/") + p);
    return names;
}

GpuRayHierarchy::GpuRayHierarchy()
    : info_(kInfoWords * sizeof(std::uint32_t)),
      tally_(std::size_t(kRayKinds) * kTallyWords * sizeof(std::uint32_t)),
      args_((kMaxSteps + 1) * 3 * sizeof(std::uint32_t)) {
    reset_stats();
}

void GpuRayHierarchy::reset_stats() {
    cpu_stats_ = stats_ = {};
    tally_.clear_u32(0);
    tally_read_ = true;
    fold_rounds = prunes = chunks = windows = syncs = groups_retraced = 0;
}

// The CPU's own counts plus the GPU's sums (one read-back, only when a trace ran since the last one).
HierarchyFrameStats GpuRayHierarchy::frame_stats() {
    HierarchyFrameStats f;
    f.options = options;
    f.object_levels = object_levels();
    f.object_nodes = object_nodes();
    f.kinds = stats();   // adds its read-back to syncs
    f.gpu_cpu_syncs = syncs;
    f.pair_capacity = capacity();
    f.chunks = chunks;
    f.windows = windows;
    f.groups_retraced = groups_retraced;
    f.fold_rounds = fold_rounds;
    f.hit_list_prunes = prunes;
    return f;
}

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
        ks.box_tests += sum(kInfoBoxTests);
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

void GpuRayHierarchy::copy_tally(gpu::Buffer& dst, std::size_t offset) const {
    rh_detail::barrier();   // the tally passes' writes, before the copy reads them
    tally_.copy_to(dst, tally_bytes(), 0, offset);
}

std::size_t GpuRayHierarchy::tally_bytes() { return std::size_t(kRayKinds) * kTallyWords * sizeof(std::uint32_t); }

std::uint64_t GpuRayHierarchy::tally_pairs(const std::uint32_t* tally) {
    std::uint64_t pairs = 0;
    for (int k = 0; k < kRayKinds; ++k) {
        const std::uint32_t* w = tally + std::size_t(k) * kTallyWords;
        auto sum = [&](std::uint32_t info_word) { return word64(w, info_word - kInfoExact); };
        for (int l = 0; l < rh_detail::kMaxRayLevels; ++l) pairs += sum(kInfoLevelIn + 2 * std::uint32_t(l));
        pairs += sum(kInfoLeafPairs);   // stats(): level 0's pairs_in gets the leaf pairs too
    }
    return pairs;
}

void GpuRayHierarchy::compile(const gpu::Wavefront& wavefront) {
    const gpu::ShaderDefines& d = wavefront.defines();
    if (d == compiled_for_ && spheres_) return;
    compile_spheres(d);
    compile_tree(d);
    build_ = Program::compute("04_ray_hierarchy/shaders/rh_build.comp", d);
    cull_ = Program::compute("04_ray_hierarchy/shaders/rh_cull.comp", d);
    gpu::ShaderDefines writes_children = d;
    writes_children.emplace("RH_CULL_WRITES_CHILDREN", "1");
    cull_children_ = Program::compute("04_ray_hierarchy/shaders/rh_cull.comp", writes_children);
    expand_ = Program::compute("04_ray_hierarchy/shaders/rh_expand.comp", d);
    leaf_closest_ = Program::compute("04_ray_hierarchy/shaders/rh_leaf.comp", d);
    gpu::ShaderDefines shadow = d;
    shadow.emplace("RH_SHADOW", "1");
    shadow.emplace("RT_SHADOW_RAYS", "1");   // the shadow rule of the opacity test (opacity.glsl)
    leaf_shadow_ = Program::compute("04_ray_hierarchy/shaders/rh_leaf.comp", shadow);
    fold_ = Program::compute("04_ray_hierarchy/shaders/rh_fold.comp", d);
    args_pass_ = Program::compute("04_ray_hierarchy/shaders/rh_args.comp", d);
    tally_pass_ = Program::compute("04_ray_hierarchy/shaders/rh_tally.comp", d);
    compiled_for_ = d;
}

std::uint32_t GpuRayHierarchy::read_info(int index) { return read_info(index, 1)[0]; }

std::vector<std::uint32_t> GpuRayHierarchy::read_info(int first, int count) {
    ++syncs;
    return info_.download<std::uint32_t>(std::size_t(count), std::size_t(first));
}

std::string GpuRayHierarchy::phase(const char* name) const {
    return std::string(name) + "." + ray_kind_name(RayKind(group_.kind));
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

    // Speculatively first (gpu_ray_hierarchy.h), then one look at the mark and at the hit list's length: for closest
    // hits the fold's first look at its flag, after its first rounds (which change nothing when a group is marked).
    // The per-pixel test counts (in.tests_per_pixel: --heatmap, and --pixel's watch list with them) are added as the
    // tests run, so a group traced twice would count twice: those frames take the windows' read-backs from the start.
    const std::vector<Group> groups = find_groups(in);
    std::size_t& limit = speculation_limit_[shadow ? 1 : 0];
    const bool speculate = options.speculate && n < limit && in.tests_per_pixel == nullptr;
    fitted_ = true;
    trace_groups(groups, 0, speculate);
    bool folded = false;
    if (speculate && !groups.empty() && traversable()) {
        std::vector<std::uint32_t> w;   // rh_info.glsl: RH_INFO_OVERFLOW, RH_INFO_HITS
        if (shadow)
            w = read_info(0, 2);
        else
            folded = fold(in, &w);
        if (w[0] != 0) {
            // The hits past the list's end were not written; those before it are real hits of their rays.
            const std::uint32_t first = w[0] - 1, fixed[2] = {0u, std::min(w[1], std::uint32_t(hit_capacity_))};
            info_.upload(fixed, sizeof fixed, 0);
            hits_bound_ = fixed[1];
            groups_retraced += groups.size() - first;
            retrace_ = true;
            trace_groups(groups, first, false);
            retrace_ = false;
            limit = n;
        }
    } else if (fitted_ && n >= limit) {
        limit = std::size_t(n) + 1;
    }
    if (!shadow && !folded) fold(in);
    tally_read_ = false;
    gpu::check_gl("04_ray_hierarchy: trace");
}

// Groups [first, end) of the batch, each built and traversed; `speculative`: with no read-back (one window a step).
void GpuRayHierarchy::trace_groups(const std::vector<Group>& groups, std::size_t first, bool speculative) {
    speculative_ = speculative;
    for (std::size_t i = first; i < groups.size(); ++i) {
        const Group& g = groups[i];
        group_ = g;
        group_mark_ = std::uint32_t(i + 1);
        HierarchyKindStats& ks = cpu_stats_[g.kind];
        if (!retrace_) {
            ks.rays += g.count;
            ks.groups += 1;
            ks.brute_force_tests += std::uint64_t(g.count) * triangles_;
        }
        if (!traversable()) continue;
        const int top = build(*in_, g);
        const std::vector<std::uint32_t> zeros(kInfoWords - kInfoGroupFirst, 0u);
        info_.upload(zeros.data(), zeros.size() * 4, kInfoGroupFirst * 4);
        traverse(top);
        tally_group();
    }
    speculative_ = false;
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

// The groups are the batch's runs (BatchTraceInputs::runs): the pipeline queues each kind of ray, and each light's
// shadow rays, in a block of its own and knows how many went to each, so nothing is read back to find them.
std::vector<GpuRayHierarchy::Group> GpuRayHierarchy::find_groups(const gpu::BatchTraceInputs& in) {
    std::vector<Group> groups;
    std::size_t next = 0;   // where the next run must start
    for (const gpu::RayRun& run : in.runs) {
        if (run.first != next || run.count == 0) break;
        groups.push_back({std::uint32_t(run.first), std::uint32_t(run.count),
                          std::min<std::uint32_t>(std::uint32_t(run.kind), std::uint32_t(kRayKinds - 1))});
        next += run.count;
    }
    if (groups.size() != in.runs.size() || next != in.count)
        throw std::logic_error("04_ray_hierarchy: the batch's runs do not cover its rays in order");
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
    if (!retrace_)
        for (std::size_t l = 0; l < level_nodes_.size(); ++l) ks.levels[l].nodes += level_nodes_[l];
    // The level tables of rh_cull.comp (both of its variants).
    std::vector<unsigned> first(kMaxRayLevels, 0u), nodes(kMaxRayLevels, 0u);
    std::copy(level_first_.begin(), level_first_.end(), first.begin());
    std::copy(level_nodes_.begin(), level_nodes_.end(), nodes.begin());
    for (const Program* cull : {&cull_, &cull_children_}) {
        cull->set("rh_level_first", first);
        cull->set("rh_level_nodes", nodes);
    }
    return int(level_nodes_.size()) - 1;
}

}  // namespace rt
