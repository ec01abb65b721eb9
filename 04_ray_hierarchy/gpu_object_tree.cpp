// Stage 04's per-frame work on the geometry, the objects' side of GpuRayHierarchy (gpu_ray_hierarchy.h): the
// triangles' bounding spheres (rh_spheres.comp) and, by --objects, the mesh objects or the object tree
// (object_tree.h; shaders/ot_build.comp and the shared radix sort). The rays' side is in gpu_ray_hierarchy.cpp, the
// traversal and the leaves in gpu_ray_traversal.cpp.
#include "gpu_ray_hierarchy.h"

#include <algorithm>

#include "gpu_ray_hierarchy_detail.h"

namespace rt {

namespace {
using gpu::Program;
using rh_detail::barrier;
}  // namespace

void GpuRayHierarchy::prepare(const gpu::GpuScene& scene, const std::vector<ObjectRange>& objects,
                              const Bounds& bounds) {
    triangles_ = scene.triangle_count();
    objects_ = 0;
    object_nodes_ = 0;
    object_level_first_.clear();
    object_level_count_.clear();
    if (!spheres_) spheres_ = Program::compute("04_ray_hierarchy/shaders/rh_spheres.comp");
    order_.reserve(4);   // bound by every expansion, read only with --objects tree
    objects_buf_.reserve(sizeof(ObjectNode));
    spheres_buf_.reserve(std::max<std::size_t>(triangles_, 1) * sizeof(glm::vec4));
    scene.bind();
    spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
    if (triangles_ == 0) return;
    spheres_.set("rh_mode", 0u);
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
        spheres_.set("rh_mode", 1u);
        spheres_.set("rh_count", unsigned(nodes.size()));
        spheres_.dispatch_threads(nodes.size());
        barrier();
        objects_ = object_nodes_ = nodes.size();
        object_level_first_ = {0};
        object_level_count_ = {std::uint32_t(nodes.size())};
    } else if (options.objects == ObjectMode::tree) {
        build_tree(bounds);
    }
    gpu::check_gl("04_ray_hierarchy: bounding spheres and objects");
}

// object_tree.h: Morton codes of the spheres' centres, sorted; clusters; levels up to a single root.
void GpuRayHierarchy::build_tree(const Bounds& bounds) {
    if (!tree_) tree_ = Program::compute("04_ray_hierarchy/shaders/ot_build.comp");
    if (!radix_) radix_ = std::make_unique<gpu::RadixSort>();
    const std::uint32_t n = std::uint32_t(triangles_);
    keys_.reserve(std::size_t(n) * 4);
    order_.reserve(std::size_t(n) * 4);
    spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
    keys_.bind(gpu::kWavefrontBindingTraversalFirst + 3);
    order_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
    tree_.set("ot_mode", 0u);
    tree_.set("ot_count", n);
    tree_.set("ot_box_min", bounds.lo);
    tree_.set("ot_scale", morton_scale(bounds.lo, bounds.hi));
    tree_.dispatch_threads(n);
    barrier();
    radix_->sort(keys_, order_, n, 3 * kMortonAxisBits);
    // The levels' sizes follow from n alone: level 1 holds ceil(n / kClusterSize) clusters, each level above
    // ceil(below / kObjectBranching) nodes, up to one.
    std::uint32_t total = 0;
    for (std::uint32_t count = (n + kClusterSize - 1) / kClusterSize;;
         count = (count + kObjectBranching - 1) / kObjectBranching) {
        object_level_first_.push_back(total);
        object_level_count_.push_back(count);
        total += count;
        if (count <= 1) break;
    }
    objects_buf_.reserve(std::size_t(total) * sizeof(ObjectNode));
    spheres_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 1);
    objects_buf_.bind(gpu::kWavefrontBindingTraversalFirst + 2);
    order_.bind(gpu::kWavefrontBindingTraversalFirst + 0);
    for (std::size_t l = 0; l < object_level_count_.size(); ++l) {
        tree_.set("ot_mode", l == 0 ? 1u : 2u);
        tree_.set("ot_count", object_level_count_[l]);
        tree_.set("ot_triangles", n);
        tree_.set("ot_child_first", l == 0 ? 0u : object_level_first_[l - 1]);
        tree_.set("ot_child_count", l == 0 ? n : object_level_count_[l - 1]);
        tree_.set("ot_node_first", object_level_first_[l]);
        tree_.set("ot_level", unsigned(l + 1));
        tree_.set("ot_fanout", l == 0 ? kClusterSize : kObjectBranching);
        tree_.dispatch_threads(object_level_count_[l]);
        barrier();
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
