// Stage 04's per-frame work on the geometry, the objects' side of GpuRayHierarchy (gpu_ray_hierarchy.h): the
// triangles' bounding spheres (rh_spheres.comp) and, by --objects, the mesh objects or the object tree
// (object_tree.h; shaders/ot_build.comp and the shared radix sort). The rays' side is in gpu_ray_hierarchy.cpp, the
// traversal and the leaves in gpu_ray_traversal.cpp.
#include "gpu_ray_hierarchy.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "common/gpu/gl/storage_limit.h"
#include "gpu_ray_hierarchy_detail.h"

namespace rt {

namespace {
using gpu::Program;
using rh_detail::barrier;
using rh_detail::kMaxObjectLevels;
}  // namespace

void GpuRayHierarchy::prepare(const gpu::GpuScene& scene, const std::vector<ObjectRange>& objects,
                              const Bounds& bounds) {
    triangles_ = scene.triangle_count();
    objects_ = 0;
    object_nodes_ = 0;
    object_level_first_.clear();
    object_level_count_.clear();
    if (!spheres_) compile_spheres({});
    order_.reserve(4);   // bound by every expansion, read only with --objects tree
    objects_buf_.reserve(sizeof(ObjectNode));
    spheres_buf_.reserve(std::max<std::size_t>(triangles_, 1) * sizeof(glm::vec4));
    scene.bind();
    spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
    if (triangles_ == 0) return;
    spheres_.set("rh_count", unsigned(triangles_));
    spheres_.dispatch_threads(triangles_);
    barrier();
    if (options.objects == ObjectMode::meshes && !objects.empty()) {
        std::vector<ObjectNode> nodes(objects.size());
        for (std::size_t i = 0; i < objects.size(); ++i) {
            nodes[i].first = objects[i].first;
            nodes[i].count = objects[i].count;
        }
        objects_buf_.reserve(nodes.size() * sizeof(ObjectNode));
        objects_buf_.upload(nodes.data(), nodes.size() * sizeof(ObjectNode));
        objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
        mesh_spheres_.set("rh_count", unsigned(nodes.size()));
        mesh_spheres_.dispatch_threads(nodes.size());
        barrier();
        objects_ = object_nodes_ = nodes.size();
        object_level_first_ = {0};
        object_level_count_ = {std::uint32_t(nodes.size())};
    } else if (options.objects == ObjectMode::tree) {
        build_tree(bounds);
    }
    gpu::check_gl("04_ray_hierarchy: bounding spheres and objects");
}

// One program per pass, each holding only its own code (rh_spheres.comp: 2, ot_build.comp: 5): on llvmpipe the tree's
// passes run faster this way than as one program switching on a mode uniform (04's README, "The object tree").
void GpuRayHierarchy::compile_spheres(const gpu::ShaderDefines& defines) {
    spheres_ = Program::compute("04_ray_hierarchy/shaders/rh_spheres.comp", defines);
    gpu::ShaderDefines meshes = defines;
    meshes.emplace("RH_MESH_SPHERES", "1");
    mesh_spheres_ = Program::compute("04_ray_hierarchy/shaders/rh_spheres.comp", meshes);
}

void GpuRayHierarchy::compile_tree(const gpu::ShaderDefines& defines) {
    for (int mode = 0; mode < kTreeModes; ++mode) {
        gpu::ShaderDefines d = defines;
        d.emplace("OT_MODE", std::to_string(mode));
        tree_[std::size_t(mode)] = Program::compute("04_ray_hierarchy/shaders/ot_build.comp", d);
    }
}

// object_tree.h: Morton codes of the spheres' centres, sorted; clusters; levels up to a single root.
void GpuRayHierarchy::build_tree(const Bounds& bounds) {
    if (!tree_[0]) compile_tree({});
    const auto set = [&](const char* name, auto value) {   // a uniform of every mode's program
        for (const Program& p : tree_) p.set(name, value);
    };
    const Program &codes = tree_[kTreeCodes], &cuts = tree_[kTreeCuts], &heads = tree_[kTreeHeads];
    if (!radix_) radix_ = std::make_unique<gpu::RadixSort>();
    const std::uint32_t n = std::uint32_t(triangles_);
    keys_.reserve(std::size_t(n) * 4);
    order_.reserve(std::size_t(n) * 4);
    spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
    keys_.bind(gpu::kWavefrontBindingTraversalFirst + 3);
    order_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
    codes.set("ot_count", n);
    codes.set("ot_box_min", bounds.lo);
    codes.set("ot_scale", morton_scale(bounds.lo, bounds.hi));
    codes.dispatch_threads(n);
    barrier();
    radix_->sort(keys_, order_, n, 3 * kMortonAxisBits);
    // The levels (ot_build.comp modes 3, 4, 1/2 and a scan each): their sizes are the GPU's, so every level a tree of
    // n triangles can have is dispatched, and the sizes are read back once, at the end (one sync a frame, outside
    // every batch). Modes 3 and the scan run over a bound of the nodes below (a level at least halves the one below,
    // group_heads); mode 4 writes the level's size and, from it, the dispatch of mode 1/2 over its groups and of the
    // next level's mode 4 over the same nodes, so those run over the GPU's counts (at 1M triangles the bounds had
    // twice to three times the threads).
    // The prefix groups' worst case is a tree of about n nodes (64 bytes a triangle); where that passes the GPU's
    // storage limit (llvmpipe: 128 MiB, 2M triangles), every 4 nodes make a group (about n / 3 nodes).
    std::vector<std::uint32_t> sizes;   // bounds of each level's nodes
    std::uint64_t total_bound = 0;
    const auto size_levels = [&](std::uint32_t divisor) {
        sizes.clear();
        total_bound = 0;
        for (std::uint32_t below = n;;) {
            sizes.push_back((below + divisor - 1) / divisor);
            total_bound += sizes.back();
            if (sizes.back() <= 1) break;
            below = sizes.back();
        }
    };
    size_levels(2);
    const std::size_t limit = tree_limit_for_testing ? tree_limit_for_testing : gpu::max_storage_block_bytes();
    tree_every_4_ = total_bound * sizeof(ObjectNode) > limit;
    if (tree_every_4_) size_levels(kObjectBranching);
    if (sizes.size() > kMaxObjectLevels)
        throw std::logic_error("04_ray_hierarchy: more object tree levels than ot_levels holds");
    gpu::check_storage_block("04_ray_hierarchy: the object tree", std::size_t(total_bound) * sizeof(ObjectNode) / 4);
    objects_buf_.reserve(std::size_t(total_bound) * sizeof(ObjectNode));
    tree_groups_.reserve(std::size_t(n) * 4);
    // ot_build.comp's ot_codes: the levels' words, each level's dispatch (3 words from kArgsWord), then two halves of
    // codes (uvec4s), one for the level below and one for the level being built, alternately.
    constexpr auto kArgsWord = std::uint32_t(4 * ((2 + 2 * kMaxObjectLevels + 3) / 4));
    constexpr auto kLevelVec4s = std::uint32_t((kArgsWord + 3 * kMaxObjectLevels + 3) / 4);
    const auto args_offset = [&](std::size_t l) { return (kArgsWord + 3 * l) * sizeof(std::uint32_t); };
    const std::uint32_t half = sizes[0];
    tree_codes_.reserve((std::size_t(kLevelVec4s) + 2 * std::size_t(half)) * 16);
    const std::vector<std::uint32_t> zero(4 * kLevelVec4s, 0u);
    tree_codes_.upload(zero.data(), zero.size() * 4);
    set("ot_triangles", n);
    set("ot_every_4", tree_every_4_ ? 1u : 0u);
    set("ot_args_word", kArgsWord);
    const auto bind = [&] {   // again after each scan, which binds its own buffers
        order_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
        spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
        objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
        keys_.bind(gpu::kWavefrontBindingTraversalFirst + 3);
        tree_groups_.bind(gpu::kWavefrontBindingTraversalFirst + 4);
        tree_codes_.bind(gpu::kWavefrontBindingTraversalFirst + 5);
    };
    // A small tree: every level in one work group, one dispatch (ot_build.comp, mode 5); else a pass a dispatch.
    const bool one_group = n <= one_group_tree_triangles;
    if (one_group) {
        bind();
        const Program& all = tree_[kTreeOneGroup];
        all.set("ot_levels", unsigned(sizes.size()));
        all.set("ot_codes_first", kLevelVec4s);
        all.set("ot_half", half);
        all.dispatch(1);
        barrier();
    }
    for (std::size_t l = 0; !one_group && l < sizes.size(); ++l) {
        const std::uint32_t below = l == 0 ? n : sizes[l - 1];
        bind();
        set("ot_level", unsigned(l + 1));
        set("ot_codes_in", kLevelVec4s + unsigned((l + 1) % 2) * half);
        set("ot_codes_out", kLevelVec4s + unsigned(l % 2) * half);
        set("ot_count", below);
        if (!tree_every_4_) {   // the cuts and their scan (every 4 nodes, mode 4 needs neither)
            cuts.dispatch_threads(below);
            barrier();
            scan_.exclusive_flags(tree_groups_, tree_groups_, below, &tree_codes_, 0);   // the total to level word 0
            bind();
        }
        if (l == 0)
            heads.dispatch_threads(below);
        else   // the nodes below: the level below's groups, as its mode 4 wrote them
            heads.dispatch_indirect(tree_codes_, args_offset(l - 1));
        barrier();
        const Program& nodes = tree_[l == 0 ? kTreeClusters : kTreeLevel];
        nodes.set("ot_count", sizes[l]);
        nodes.dispatch_indirect(tree_codes_, args_offset(l));
        barrier();
    }
    const std::vector<std::uint32_t> levels = tree_codes_.download<std::uint32_t>(2 + 2 * sizes.size());
    ++syncs;
    std::uint32_t total = 0;
    for (std::size_t l = 0; l < sizes.size() && levels[2 + 2 * l] > 0; ++l) {
        object_level_first_.push_back(levels[3 + 2 * l]);
        object_level_count_.push_back(levels[2 + 2 * l]);
        total += levels[2 + 2 * l];
    }
    object_nodes_ = total;
    objects_ = object_level_count_.back();
}

GpuRayHierarchy::LeafSpheres GpuRayHierarchy::leaf_spheres() const {
    if (options.objects != ObjectMode::triangles && !object_level_count_.empty())
        return {&objects_buf_, object_level_count_[0], std::uint32_t(sizeof(ObjectNode) / 16)};
    return {&spheres_buf_, std::uint32_t(triangles_), 1};
}

ObjectTree GpuRayHierarchy::download_tree() const {
    ObjectTree tree;
    tree.level_first = object_level_first_;
    tree.level_count = object_level_count_;
    tree.nodes = objects_buf_.download<ObjectNode>(object_nodes_);
    tree.order = options.objects == ObjectMode::tree ? order_.download<std::uint32_t>(triangles_)
                                                     : std::vector<std::uint32_t>{};
    return tree;
}

}  // namespace rt
