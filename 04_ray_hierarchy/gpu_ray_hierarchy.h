// Stage 04 on the GPU: for every batch of rays the wavefront pipeline hands over (BatchTraceInputs), one ray-space
// hierarchy per group of the batch (consecutive rays of one kind, and one light for shadow rays), built bottom-up
// and traversed top-down against the scene's triangles, level by level (Roger, Assarsson & Holzschuch 2007,
// sections 4-5):
//
//   build     rh_build.comp, one dispatch per level: node j of level l bounds children [jB, (j+1)B) of level l - 1
//             (level 0 = the rays). --levels limits how many levels are built above the rays.
//   traverse  candidate pairs (node, triangle) of the top level (all of them, implicitly), or first (node, object)
//             with --object-culling; per chunk of pairs: rh_test.comp (the cone+sphere test; each survivor counts
//             its children), the shared exclusive scan (common/gpu/scan.h), rh_expand.comp writing the survivors'
//             (child, triangle) pairs, window by window, and down to the next level (depth first over chunks). The
//             scan runs over the sums of work groups of 64 pairs; rh_expand.comp adds the offsets inside a group.
//   local     rh_leaf.comp, the exact ray/triangle test on every (ray, triangle) pair that reached the leaves; for
//             closest hits then rh_fold.comp (rh_closest.glsl: brute force's exact hit).
//
// Every buffer holds at most `capacity()` entries (from the storage limit, Wavefront::storage_limit()): chunks and
// windows are sized so that none overflows, so a pair is never dropped, however many survive.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/gpu/buffer.h"
#include "common/gpu/gpu_scene.h"
#include "common/gpu/scan.h"
#include "common/gpu/shader.h"
#include "common/gpu/wavefront.h"

namespace rt {

struct HierarchyOptions {
    int branching = 4;          // --branching: 4, 8 or 16 children per node
    int levels = 0;             // --levels: upper levels used (0 = up to a single root)
    bool object_culling = true; // --object-culling: test top nodes against objects before their triangles
    std::size_t pair_capacity = 0;   // tests: entries per pair buffer (0 = from the storage limit, at most 2^20)
    int hit_list_per_ray = 4;        // tests: hit-list entries per ray of a batch (fewer force prunes)
};

// A run of consecutive triangles (the flattened scene keeps no mesh boundaries: objects are runs of one material).
struct ObjectRange {
    std::uint32_t first = 0, count = 0;
};
// Runs of equal material id, at most `max_count` triangles each.
std::vector<ObjectRange> object_ranges(const std::vector<std::uint32_t>& material_ids, std::uint32_t max_count = 4096);

// Per ray kind (shadow, reflection, refraction): what the traversal did, summed over a frame.
struct HierarchyLevelStats {
    std::uint64_t nodes = 0, pairs_in = 0, pairs_out = 0;   // pairs tested at the level, and those that survived
};
struct HierarchyKindStats {
    std::uint64_t rays = 0, groups = 0;
    std::uint64_t object_pairs_in = 0, object_pairs_out = 0;   // the object level (--object-culling)
    std::vector<HierarchyLevelStats> levels;                  // [0] = leaves (pairs_in = local tests), [1..] nodes
    std::uint64_t local_tests = 0;     // exact tests at the leaves
    std::uint64_t fold_tests = 0;      // the closest-hit fold's re-tests (rh_closest.glsl)
    std::uint64_t brute_force_tests = 0;   // rays x triangles
    std::uint64_t node_tests() const;
};

class GpuRayHierarchy {
public:
    GpuRayHierarchy();
    // Per frame: the triangles' and objects' bounding spheres (the only per-frame work on the geometry).
    void prepare(const gpu::GpuScene& scene, const std::vector<ObjectRange>& objects);
    // One batch of the pipeline: closest hits (trace) or occlusion (shadow) for every ray of it.
    void trace(const gpu::BatchTraceInputs& in, bool shadow);

    HierarchyOptions options;
    gpu::GpuTimer* timer = nullptr;   // phases "rh_build", "rh_traverse", "rh_local" (per kind: "rh_build.shadow" ...)
    // Stats since reset_stats(), indexed by RayKind (0 = primary, unused).
    std::array<HierarchyKindStats, 4> stats;
    void reset_stats() { stats = {}; }
    std::uint64_t fold_rounds = 0, prunes = 0, chunks = 0, windows = 0;
    // Entries per buffer (pairs, hits, counts) for the current storage limit.
    std::size_t capacity() const { return capacity_; }
    // Programs compiled for the current variant.
    static std::vector<std::string> program_names();

private:
    struct Source {        // a chunk of candidate pairs (rh_pairs.glsl)
        bool implicit = true;
        std::uint32_t pair_first = 0, node_first = 0, item_first = 0, item_count = 0;
    };
    struct Group {
        std::uint32_t first = 0, count = 0;   // rays [first, first + count) of the batch
        std::uint32_t kind = 0;
    };
    void compile(const gpu::Wavefront& wavefront);
    std::vector<Group> find_groups(const gpu::BatchTraceInputs& in);
    int build(const gpu::BatchTraceInputs& in, const Group& g);
    void traverse(int top);
    void test_chunk(int level, const Source& src, std::uint32_t count, bool objects);
    void leaves(std::uint32_t count);
    void leaf_dispatch(std::uint32_t first, std::uint32_t count);
    void prune_hits();
    void fold(const gpu::BatchTraceInputs& in);
    void set_source(const gpu::Program& p, const Source& s) const;
    void level_buffers(int index);
    std::uint32_t read_info(int index) const;
    std::string phase(const char* name) const;

    std::string key_;
    gpu::Program spheres_, build_, heads_, test_, expand_, leaf_closest_, leaf_shadow_, fold_;
    gpu::Compaction compaction_;
    gpu::Buffer spheres_buf_, objects_buf_, nodes_, info_, group_sums_, group_heads_, group_count_, state_, hits_, hits_tmp_;
    std::vector<gpu::Buffer> pairs_, counts_, offsets_;   // per level index (0 = leaves; top + 1 = objects)
    std::vector<std::uint32_t> level_first_, level_nodes_;
    std::size_t triangles_ = 0, objects_ = 0, capacity_ = 0, hit_capacity_ = 0;
    std::uint64_t pending_tests_ = 0;   // leaf tests not yet added to the test counter
    std::uint64_t hits_bound_ = 0;    // an upper bound of the hit list's length (read back when it may be full)
    // The batch being traced.
    const gpu::BatchTraceInputs* in_ = nullptr;
    Group group_;
    bool shadow_ = false;
    int top_ = 0;
};

}  // namespace rt
