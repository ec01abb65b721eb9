#include "gpu_ray_hierarchy.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

namespace rt {

namespace {
using gpu::Buffer;
using gpu::Program;

constexpr const char* kKindNames[4] = {"primary", "shadow", "reflection", "refraction"};
constexpr std::size_t kMaxCapacity = std::size_t(1) << 20;   // entries per buffer: 16 MiB of (node, triangle) pairs

void barrier() {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

// The RhObject layout of rh_common.glsl.
struct GpuObject {
    glm::vec4 sphere{0.0f};
    std::uint32_t first = 0, count = 0, pad0 = 0, pad1 = 0;
};
static_assert(sizeof(GpuObject) == 32);
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
    std::uint64_t n = object_pairs_in;
    for (std::size_t l = 1; l < levels.size(); ++l) n += levels[l].pairs_in;
    return n;
}

std::vector<std::string> GpuRayHierarchy::program_names() {
    std::vector<std::string> names;
    for (const char* p : {"rh_spheres.comp", "rh_heads.comp", "rh_build.comp", "rh_test.comp", "rh_expand.comp",
                          "rh_leaf.comp", "rh_fold.comp"})
        names.push_back(std::string("04_ray_hierarchy/") + p);
    return names;
}

GpuRayHierarchy::GpuRayHierarchy() : info_(8 * sizeof(std::uint32_t)), group_count_(sizeof(std::uint32_t)) {}

void GpuRayHierarchy::compile(const gpu::Wavefront& wavefront) {
    std::string key;
    for (const auto& [name, value] : wavefront.defines()) key += name + "=" + value + ";";
    if (key == key_ && spheres_) return;
    const gpu::ShaderDefines& d = wavefront.defines();
    spheres_ = Program::compute("04_ray_hierarchy/rh_spheres.comp", d);
    build_ = Program::compute("04_ray_hierarchy/rh_build.comp", d);
    heads_ = Program::compute("04_ray_hierarchy/rh_heads.comp", d);
    test_ = Program::compute("04_ray_hierarchy/rh_test.comp", d);
    expand_ = Program::compute("04_ray_hierarchy/rh_expand.comp", d);
    leaf_closest_ = Program::compute("04_ray_hierarchy/rh_leaf.comp", d);
    gpu::ShaderDefines shadow = d;
    shadow["RH_SHADOW"] = "1";
    leaf_shadow_ = Program::compute("04_ray_hierarchy/rh_leaf.comp", shadow);
    fold_ = Program::compute("04_ray_hierarchy/rh_fold.comp", d);
    key_ = key;
}

void GpuRayHierarchy::prepare(const gpu::GpuScene& scene, const std::vector<ObjectRange>& objects) {
    triangles_ = scene.triangle_count();
    objects_ = objects.size();
    if (!spheres_) spheres_ = Program::compute("04_ray_hierarchy/rh_spheres.comp");
    std::vector<GpuObject> gpu_objects(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) {
        gpu_objects[i].first = objects[i].first;
        gpu_objects[i].count = objects[i].count;
    }
    spheres_buf_.reserve(std::max<std::size_t>(triangles_, 1) * sizeof(glm::vec4));
    objects_buf_.reserve(std::max<std::size_t>(objects_, 1) * sizeof(GpuObject));
    if (!gpu_objects.empty()) objects_buf_.upload(gpu_objects.data(), gpu_objects.size() * sizeof(GpuObject));
    scene.bind();
    spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
    objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
    for (unsigned mode = 0; mode < 2; ++mode) {
        const std::size_t n = mode == 0 ? triangles_ : objects_;
        if (n == 0) continue;
        spheres_.set("rh_mode", mode);
        spheres_.set("rh_count", unsigned(n));
        spheres_.dispatch_threads(n);
        barrier();
    }
    gpu::check_gl("04_ray_hierarchy: bounding spheres");
}

std::uint32_t GpuRayHierarchy::read_info(int index) const { return info_.download_value<std::uint32_t>(index); }

std::string GpuRayHierarchy::phase(const char* name) const {
    return std::string(name) + "." + kKindNames[group_.kind];
}

void GpuRayHierarchy::level_buffers(int index) {
    if (int(pairs_.size()) <= index) {
        pairs_.resize(index + 1);
        counts_.resize(index + 1);
        offsets_.resize(index + 1);
    }
    pairs_[index].reserve(capacity_ * 8);
    counts_[index].reserve(capacity_ * 4);
    offsets_[index].reserve(capacity_ * 4);   // the work groups' offsets (capacity / 64), or the hit list's scan
    group_sums_.reserve(capacity_ / 64 * 4 + 4);
}

void GpuRayHierarchy::trace(const gpu::BatchTraceInputs& in, bool shadow) {
    compile(in.wavefront);
    in_ = &in;
    shadow_ = shadow;
    capacity_ = std::clamp<std::size_t>(in.wavefront.storage_limit() / 16, 64, kMaxCapacity);
    if (options.pair_capacity > 0) capacity_ = std::min(capacity_, std::max<std::size_t>(options.pair_capacity, 16));
    const std::uint32_t n = std::uint32_t(in.count);
    // The hit list: 4 entries per ray (every ray keeps its closest hits after a prune; a ray of the batch takes 64
    // bytes in the queue, so 4 x 16 bytes per ray fit the storage limit too), or capacity() when that is more.
    const std::size_t per_ray = std::size_t(std::clamp(options.hit_list_per_ray, 1, 4));
    hit_capacity_ = options.hit_list_per_ray < 4 ? per_ray * n : std::max<std::size_t>(capacity_, per_ray * n);
    if (n == 0) return;

    // Results start as "nothing hit".
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    in.results.bind(gpu::kWavefrontBindingResults);
    if (in.tests_per_pixel) in.tests_per_pixel->bind(gpu::kWavefrontBindingTestsPerPixel);
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
        info_.clear_u32(0);
        hits_bound_ = 0;
    }

    for (const Group& g : find_groups(in)) {
        group_ = g;
        HierarchyKindStats& ks = stats[g.kind];
        ks.rays += g.count;
        ks.groups += 1;
        ks.brute_force_tests += std::uint64_t(g.count) * triangles_;
        if (triangles_ == 0) continue;
        const int top = build(in, g);
        traverse(top);
    }
    if (!shadow) fold(in);
    // The leaves' tests, counted here, go to the pipeline's test counter in a few adds (one thread each).
    for (; pending_tests_ > 0;) {
        const std::uint32_t add = std::uint32_t(std::min<std::uint64_t>(pending_tests_, 1u << 31));
        fold_.set("rh_mode", 6u);
        fold_.set("rh_count", add);
        fold_.dispatch(1);
        barrier();
        pending_tests_ -= add;
    }
    gpu::check_gl("04_ray_hierarchy: trace");
}

std::vector<GpuRayHierarchy::Group> GpuRayHierarchy::find_groups(const gpu::BatchTraceInputs& in) {
    const std::uint32_t n = std::uint32_t(in.count);
    level_buffers(0);
    Buffer& flags = counts_[0];
    flags.reserve(std::size_t(n) * 4);
    group_heads_.reserve(std::size_t(n) * 4);
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    flags.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    heads_.set("wf_input_first", unsigned(in.first));
    heads_.set("wf_input_count", n);
    heads_.dispatch_threads(n);
    barrier();
    compaction_.compact_indices(flags, n, group_heads_, group_count_);
    const std::uint32_t count = group_count_.download_value<std::uint32_t>();
    const std::vector<std::uint32_t> heads = group_heads_.download<std::uint32_t>(count);
    std::vector<Group> groups;
    for (std::uint32_t i = 0; i < count; ++i) {
        Group g;
        g.first = heads[i];
        g.count = (i + 1 < count ? heads[i + 1] : n) - heads[i];
        const gpu::WavefrontRay r = in.rays.download_value<gpu::WavefrontRay>(in.first + g.first);
        g.kind = (r.depth_kind >> 16) & 3u;
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
        if (n <= 1 || (options.levels > 0 && upper >= options.levels)) break;
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
    HierarchyKindStats& ks = stats[g.kind];
    if (ks.levels.size() < level_nodes_.size()) ks.levels.resize(level_nodes_.size());
    for (std::size_t l = 0; l < level_nodes_.size(); ++l) ks.levels[l].nodes += level_nodes_[l];
    return int(level_nodes_.size()) - 1;
}

void GpuRayHierarchy::set_source(const Program& p, const Source& s) const {
    p.set("rh_implicit", s.implicit ? 1u : 0u);
    p.set("rh_pair_first", s.pair_first);
    p.set("rh_node_first", s.node_first);
    p.set("rh_item_first", s.item_first);
    p.set("rh_item_count", std::max<std::uint32_t>(s.item_count, 1));
}

// The top level's pairs are every top node with every item (object or triangle): implicit chunks of at most
// capacity() pairs, whole rows of items when a row fits.
void GpuRayHierarchy::traverse(int top) {
    top_ = top;
    for (int l = 0; l <= top + 1; ++l) level_buffers(l);
    const bool objects = options.object_culling && objects_ > 0;
    const std::uint32_t items = std::uint32_t(objects ? objects_ : triangles_);
    const std::uint32_t nodes = level_nodes_[top];
    const std::uint32_t cap = std::uint32_t(capacity_);
    if (items <= cap) {
        const std::uint32_t per_chunk = cap / items;
        for (std::uint32_t n0 = 0; n0 < nodes; n0 += per_chunk) {
            const std::uint32_t k = std::min(per_chunk, nodes - n0);
            test_chunk(objects ? top + 1 : top, Source{true, 0, n0, 0, items}, k * items, objects);
        }
    } else {
        for (std::uint32_t n0 = 0; n0 < nodes; ++n0)
            for (std::uint32_t i0 = 0; i0 < items; i0 += cap) {
                const std::uint32_t k = std::min(cap, items - i0);
                test_chunk(objects ? top + 1 : top, Source{true, 0, n0, i0, k}, k, objects);
            }
    }
}

// One chunk of pairs at `level` (top + 1 = the object level): test, scan, then expand window by window, each window
// traced down to the leaves before the next (depth first, so each level needs one buffer of capacity() pairs).
void GpuRayHierarchy::test_chunk(int level, const Source& src, std::uint32_t count, bool objects) {
    HierarchyKindStats& ks = stats[group_.kind];
    const int node_level = objects ? top_ : level;
    const std::uint32_t b = std::uint32_t(options.branching);
    std::uint32_t total = 0, survivors = 0;
    {
        std::optional<gpu::GpuTimer::Scope> timed;
        if (timer) timed.emplace(*timer, phase("rh_traverse"));
        const std::uint32_t zero = 0;
        info_.upload(&zero, 4, 0);
        nodes_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
        spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
        objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
        if (!src.implicit) pairs_[level].bind(gpu::kWavefrontBindingTraversalFirst + 3);
        counts_[level].bind(gpu::kWavefrontBindingTraversalFirst + 5);
        info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
        group_sums_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
        set_source(test_, src);
        test_.set("rh_count", count);
        test_.set("rh_level_first", level_first_[node_level]);
        test_.set("rh_children", level_nodes_[node_level - 1]);
        test_.set("rh_branching", b);
        test_.set("rh_objects_mode", objects ? 1u : 0u);
        test_.dispatch_threads(count);
        barrier();
        const std::size_t groups = (std::size_t(count) + 63) / 64;
        compaction_.scan().exclusive(group_sums_, offsets_[level], groups, &info_, 12);
        std::uint32_t info[4];
        info_.download(info, sizeof info);
        survivors = info[0];
        total = info[3];
        ++chunks;
    }
    if (objects) {
        ks.object_pairs_in += count;
        ks.object_pairs_out += survivors;
    } else {
        ks.levels[level].pairs_in += count;
        ks.levels[level].pairs_out += survivors;
    }
    const int out_level = objects ? top_ : level - 1;
    const std::uint32_t cap = std::uint32_t(capacity_);
    for (std::uint32_t w0 = 0; w0 < total; w0 += cap) {
        const std::uint32_t w = std::min(cap, total - w0);
        {
            std::optional<gpu::GpuTimer::Scope> timed;
            if (timer) timed.emplace(*timer, phase("rh_traverse"));
            objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
            if (!src.implicit) pairs_[level].bind(gpu::kWavefrontBindingTraversalFirst + 3);
            pairs_[out_level].bind(gpu::kWavefrontBindingTraversalFirst + 4);
            counts_[level].bind(gpu::kWavefrontBindingTraversalFirst + 5);
            offsets_[level].bind(gpu::kWavefrontBindingTraversalFirst + 6);
            set_source(expand_, src);
            expand_.set("rh_count", count);
            expand_.set("rh_window_first", w0);
            expand_.set("rh_window_count", w);
            expand_.set("rh_branching", b);
            expand_.set("rh_objects_mode", objects ? 1u : 0u);
            expand_.dispatch_threads(count);
            barrier();
            ++windows;
        }
        if (out_level == 0)
            leaves(w);
        else
            test_chunk(out_level, Source{false, 0, 0, 0, 0}, w, false);
    }
}

void GpuRayHierarchy::leaves(std::uint32_t count) {
    HierarchyKindStats& ks = stats[group_.kind];
    ks.levels[0].pairs_in += count;
    ks.local_tests += count;
    pending_tests_ += count;
    if (shadow_) {
        leaf_dispatch(0, count);
        return;
    }
    // The hit list holds hit_capacity_ entries: a chunk goes in once there is room for all of its pairs (each may
    // add one hit); when there is not, hits left behind by closer ones are pruned, and the chunk is split if needed.
    // Only a batch whose rays keep 4 hits each within the tie range would fill it: then a clear error, not a
    // dropped hit.
    const std::uint64_t cap = hit_capacity_;
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
        leaf_dispatch(first, n);
        hits_bound_ += n;
        first += n;
    }
}

void GpuRayHierarchy::leaf_dispatch(std::uint32_t first, std::uint32_t count) {
    std::optional<gpu::GpuTimer::Scope> timed;
    if (timer) timed.emplace(*timer, phase("rh_local"));
    const Program& p = shadow_ ? leaf_shadow_ : leaf_closest_;
    const gpu::BatchTraceInputs& in = *in_;
    in.rays.bind(gpu::kWavefrontBindingRaysIn);
    in.results.bind(gpu::kWavefrontBindingResults);
    if (in.tests_per_pixel) in.tests_per_pixel->bind(gpu::kWavefrontBindingTestsPerPixel);
    pairs_[0].bind(gpu::kWavefrontBindingTraversalFirst + 3);
    if (!shadow_) {
        hits_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
        state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
        info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    }
    in.wavefront.set_uniforms(p);
    set_source(p, Source{false, first, 0, 0, 0});
    p.set("rh_count", count);
    p.set("rh_group_first", unsigned(in.first + group_.first));
    p.set("rh_batch_first", unsigned(in.first));
    p.dispatch_threads(count);
    barrier();
}

void GpuRayHierarchy::prune_hits() {
    const std::uint32_t used = read_info(1);
    ++prunes;
    Buffer& flags = counts_[0];
    Buffer& offsets = offsets_[0];
    flags.reserve(hit_capacity_ * 4);
    offsets.reserve(hit_capacity_ * 4);
    hits_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
    state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    flags.bind(gpu::kWavefrontBindingTraversalFirst + 6);
    fold_.set("rh_mode", 4u);
    fold_.set("rh_count", used);
    fold_.dispatch_threads(used);
    barrier();
    compaction_.scan().exclusive_flags(flags, offsets, used, &info_, 4);   // the kept count becomes the list length
    hits_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
    state_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    info_.bind(gpu::kWavefrontBindingTraversalFirst + 7);
    offsets.bind(gpu::kWavefrontBindingTraversalFirst + 6);
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
    std::uint32_t info[8];
    info_.download(info, sizeof info);
    for (int k = 0; k < 4; ++k) stats[k].fold_tests += info[4 + k];
}

}  // namespace rt
