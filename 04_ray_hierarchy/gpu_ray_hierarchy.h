// Stage 04 on the GPU: for every batch of rays the wavefront pipeline hands over (BatchTraceInputs), one ray-space
// hierarchy per group of the batch (consecutive rays of one kind, and one light for shadow rays), built bottom-up
// and traversed top-down against the scene's triangles, level by level (Roger, Assarsson & Holzschuch 2007,
// sections 4-5):
//
//   build     rh_build.comp, one dispatch per level: node j of level l bounds children [jB, (j+1)B) of level l - 1
//             (level 0 = the rays). --levels limits how many levels are built above the rays.
//   objects   per frame (prepare): the triangles' bounding spheres and, with --objects tree, the object tree over
//             them (object_tree.h: Morton codes, the shared radix sort, clusters, levels; shaders/ot_build.comp).
//   traverse  candidate pairs (ray side, object side) (rh_pairs.glsl): the top ray level against every top item
//             (triangles, mesh objects or the tree's root), implicitly; per chunk of pairs: rh_cull.comp (the
//             cone+sphere test; each survivor splits one side, counts its children and reserves their places: an
//             atomic per work group of 64 pairs on the children's count), rh_expand.comp writing the children
//             pairs, window by window, each window traced on before the next (depth first over steps); while the
//             children cannot outnumber one window, rh_cull.comp writes them itself and no rh_expand.comp runs.
//   local     rh_leaf.comp, on every (ray, triangle) pair a step leaves: the ray against the triangle's sphere, then
//             the exact ray/triangle test; for closest hits then rh_fold.comp (rh_closest.glsl: brute force's hit).
//
// Every buffer holds at most `capacity()` entries (from the storage limit, Wavefront::storage_limit()). A batch is
// traced speculatively first: every step's children go to one window, written and dispatched by the GPU alone, with
// nothing read back until the batch's groups are done; a pass that finds no room for a pair or a hit drops it and
// marks its group. One read-back then: no mark (the rule: a window rarely fills) and the batch is done; a mark, and
// that group and every later one are traced again, their windows and the hit list's room sized from read-back
// lengths, so that nothing overflows (what the first try found stays: every hit it listed and every occlusion it
// set are real, and its counts were never added). So a pair is never dropped, however many survive. A batch as large as
// one of its kind that ran out of room skips the try (speculation_limit_).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/gpu/gl/buffer.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/primitives/radix_sort.h"
#include "common/gpu/primitives/scan.h"
#include "common/gpu/gl/shader.h"
#include "common/gpu/pipeline/wavefront.h"
#include "common/scene/scene.h"
#include "hierarchy_options.h"
#include "hierarchy_stats.h"
#include "object_tree.h"

namespace rt {

// A run of consecutive triangles (the flattened scene keeps no mesh boundaries: objects are runs of one material).
struct ObjectRange {
    std::uint32_t first = 0, count = 0;
};
// Runs of equal material id, at most `max_count` triangles each.
std::vector<ObjectRange> object_ranges(const std::vector<std::uint32_t>& material_ids, std::uint32_t max_count = 4096);

// Object trees of at most this many triangles are built in one dispatch (ot_build.comp, mode 5): on a small scene the
// tree's passes are mostly dispatches, four or five a level.
constexpr std::size_t kOneGroupTreeTriangles = 4096;

class GpuRayHierarchy {
public:
    GpuRayHierarchy();
    // Per frame: the triangles' bounding spheres, and the objects of options.objects (mesh runs from `objects`, or
    // the tree, built over the scene box `bounds`): the only per-frame work on the geometry.
    void prepare(const gpu::GpuScene& scene, const std::vector<ObjectRange>& objects, const Bounds& bounds);
    // One batch of the pipeline: closest hits (trace) or occlusion (shadow) for every ray of it.
    void trace(const gpu::BatchTraceInputs& in, bool shadow);

    HierarchyOptions options;
    gpu::GpuTimer* timer = nullptr;   // phases "rh_build", "rh_traverse", "rh_local" (per kind: "rh_build.shadow" ...)
    // Stats since reset_stats(), indexed by RayKind (0 = primary, unused). The traversal's counts are summed on the
    // GPU (shaders/rh_tally.comp) and read here, once after the traces that made them (one sync).
    const std::array<HierarchyKindStats, kRayKinds>& stats();
    void reset_stats();
    // The frame's "ray_hierarchy" stats, with stats()'s one read, but for what the stage alone knows (whether it
    // traced, its pass times).
    HierarchyFrameStats frame_stats();
    // What one trace cost the traversal, for a caller that compares two orders of a batch (stage 05's --sort auto):
    // the GPU's running sums copied into `dst` at `offset` (tally_bytes() bytes; a copy on the GPU, no read-back)
    // before and after the trace. tally_pairs() of the later copy minus that of the earlier is every pair the trace
    // tested at every ray level, of every kind: node_tests() + leaf_pairs.
    void copy_tally(gpu::Buffer& dst, std::size_t offset) const;
    static std::size_t tally_bytes();
    static std::uint64_t tally_pairs(const std::uint32_t* tally);
    std::uint64_t fold_rounds = 0, prunes = 0, chunks = 0, windows = 0;
    // Groups traced again since reset_stats(): a speculative try found no room in a window or the hit list.
    std::uint64_t groups_retraced = 0;
    // GPU -> CPU read-backs since reset_stats() (each waits for the GPU); stats() adds one when it reads the counts.
    std::uint64_t syncs = 0;
    // The object tree of the last prepare(): levels above the triangles and nodes (0 without a tree).
    std::uint32_t object_levels() const { return std::uint32_t(object_level_count_.size()); }
    std::size_t object_nodes() const { return object_nodes_; }
    // The last tree grouped every 4 nodes (build_tree: its prefix groups' worst case would pass the storage limit;
    // build_object_tree's every_4). The limit it is held against: the GL limit, or this many bytes (for the tests).
    bool tree_every_4() const { return tree_every_4_; }
    std::size_t tree_limit_for_testing = 0;
    // Trees of at most this many triangles are built by one work group in one dispatch (ot_build.comp, mode 5),
    // larger ones a pass a dispatch; the same tree either way. Tests set it to build one tree both ways.
    std::size_t one_group_tree_triangles = kOneGroupTreeTriangles;
    // The tree as the GPU built it (order, nodes, levels), for the tests: the same as build_object_tree's.
    ObjectTree download_tree() const;
    // The bounding spheres of the finest objects the ray nodes are culled against, as prepare() left them: the
    // tree's leaves (clusters) with --objects tree, the mesh objects with meshes (ObjectNode: a sphere every 4
    // vec4s), the triangles with triangles (a sphere per vec4). Stage 05's --sort auto takes their mean diameter as
    // the width beyond which a ray node's tightness no longer matters.
    struct LeafSpheres {
        const gpu::Buffer* buffer = nullptr;
        std::uint32_t count = 0, stride = 1;   // spheres, and vec4s from one to the next
    };
    LeafSpheres leaf_spheres() const;
    // Entries per buffer (pairs, hits, counts) for the current storage limit.
    std::size_t capacity() const { return capacity_; }
    // Programs compiled for the current variant.
    static std::vector<std::string> program_names();

private:
    struct Source {        // a chunk of candidate pairs (rh_pairs.glsl)
        bool implicit = true;
        std::uint32_t pair_first = 0, node_first = 0, item_first = 0, item_count = 0, item_flag = 0;
    };
    struct Group {
        std::uint32_t first = 0, count = 0;   // rays [first, first + count) of the batch
        std::uint32_t kind = 0;
    };
    void compile(const gpu::Wavefront& wavefront);
    std::vector<Group> find_groups(const gpu::BatchTraceInputs& in);
    void trace_groups(const std::vector<Group>& groups, std::size_t first, bool speculative);
    bool traversable() const {   // something to meet: triangles, and the objects of options.objects
        return triangles_ != 0 && (options.objects == ObjectMode::triangles || objects_ != 0);
    }
    int build(const gpu::BatchTraceInputs& in, const Group& g);
    void traverse(int top);
    void build_tree(const Bounds& bounds);   // gpu_object_tree.cpp, with prepare() and download_tree()
    void test_chunk(int step, const Source& src, std::uint32_t count, bool on_gpu);
    void expand(int step, const Source& src, std::uint32_t count, bool on_gpu, std::uint32_t w0, std::uint32_t w);
    void leaves(int step, std::uint32_t count, bool on_gpu);
    void dispatch_chunk(const gpu::Program& p, int step, std::uint32_t count, bool on_gpu) const;
    void tally_group();   // the group's counts into the GPU's sums (no read-back)
    void leaf_dispatch(int step, std::uint32_t first, std::uint32_t count, bool on_gpu);
    void prune_hits();
    bool fold(const gpu::BatchTraceInputs& in, std::vector<std::uint32_t>* first_look = nullptr);
    void set_source(const gpu::Program& p, const Source& s) const;
    void step_buffers(int step, std::size_t pairs);
    std::uint32_t read_info(int index);   // one word of rh_info, in one read-back (counted in syncs)
    std::vector<std::uint32_t> read_info(int first, int count);   // words [first, first + count), in one
    std::string phase(const char* name) const;

    gpu::ShaderDefines compiled_for_;   // the wavefront defines the programs were compiled with
    gpu::Program spheres_, mesh_spheres_;   // rh_spheres.comp: per triangle; per mesh object (--objects meshes)
    void compile_spheres(const gpu::ShaderDefines& defines);
    gpu::Program build_, cull_, expand_, leaf_closest_, leaf_shadow_, fold_, args_pass_,
        tally_pass_;
    gpu::Program cull_children_;   // rh_cull.comp writing the children itself (a step whose children fit one window)
    // ot_build.comp, one program per mode (OT_MODE): codes, clusters, level, cuts, heads, and all of a small tree.
    enum TreeMode { kTreeCodes, kTreeClusters, kTreeLevel, kTreeCuts, kTreeHeads, kTreeOneGroup, kTreeModes };
    std::array<gpu::Program, kTreeModes> tree_;
    void compile_tree(const gpu::ShaderDefines& defines);
    gpu::Scan scan_;   // the hit list's prune (prune_hits) and the tree's groups (build_tree)
    std::unique_ptr<gpu::RadixSort> radix_;   // the tree's sort (created with the first tree)
    gpu::Buffer spheres_buf_, objects_buf_, order_, keys_, nodes_, info_, state_, hits_, hits_tmp_, prune_flags_,
        prune_offsets_;
    gpu::Buffer tally_;   // per ray kind, the GPU's sums of the traversal's counts (rh_tally.comp)
    // The tree's build (ot_build.comp): per node below, its group; the levels' sizes and first nodes, and per
    // node the codes it spans (two levels, alternately below and being built).
    gpu::Buffer tree_groups_, tree_codes_;
    bool tree_every_4_ = false;   // the last tree grouped every 4 nodes (its prefix groups would not fit the limit)
    gpu::Buffer args_;   // indirect dispatch arguments (3 uints each) per step (rh_cull.comp) and the fold's
    std::vector<gpu::Buffer> pairs_, counts_, offsets_;   // per step of the depth-first traversal (0 = the top)
    std::vector<std::uint32_t> level_first_, level_nodes_;   // the ray hierarchy's levels (level 0 = the rays)
    std::vector<std::uint32_t> object_level_first_, object_level_count_;   // the object tree's (level 1 first)
    std::size_t triangles_ = 0, objects_ = 0, object_nodes_ = 0, capacity_ = 0, hit_capacity_ = 0;
    // The stats the CPU counts itself (rays, groups, nodes, brute force), and with the GPU's sums added (stats()).
    std::array<HierarchyKindStats, kRayKinds> cpu_stats_, stats_;
    bool tally_read_ = true;   // stats_ holds the GPU's sums as they are now
    std::uint64_t hits_bound_ = 0;    // an upper bound of the hit list's length (read back when it may be full)
    // The batch being traced.
    const gpu::BatchTraceInputs* in_ = nullptr;
    Group group_;
    bool shadow_ = false;
    int top_ = 0;
    bool speculative_ = false;    // the group's steps go to one window each; no read-back (trace)
    bool retrace_ = false;        // the groups are traced again: the CPU's counts of them are in already
    // Per batch kind (closest hits, shadow): batches of this many rays or more are traced the careful way from the
    // start. A batch that outgrows its windows (many rays, a big scene) mostly does so again, and its try would be
    // wasted work each time: a speculative batch that ran out of room lowers the limit to its size, and a careful one
    // that fitted (no step cut into windows, no hits pruned) raises it past its size.
    std::array<std::size_t, 2> speculation_limit_{SIZE_MAX, SIZE_MAX};
    bool fitted_ = true;          // the batch being traced, so far
    std::uint32_t group_mark_ = 0;   // rh_info.glsl: rh_overflow_mark, 1 + the group's place in the batch
    int max_depth_ = 0;   // steps after which only (ray, triangle) pairs are left
};

}  // namespace rt
