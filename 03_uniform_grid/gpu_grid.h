// Stage 03's uniform grid, built on the GPU from scratch every frame (Kalojanov & Slusallek 2009, "A Parallel
// Algorithm for Construction of Uniform Grids"): the sort-based build of the grid data the paper describes, a list of
// (cell, triangle) pairs sorted by cell plus a start and size per cell.
//
//   1. grid_chunks.comp  one thread per triangle: how many chunks of 512 cells its bounding box has; a scan of them
//                        says where each triangle's chunks start (grid_build.glsl: why a triangle is split)
//   2. grid_count.comp   one thread per chunk: how many of its cells the triangle overlaps (triangle/box test,
//                        grid_common.glsl); Scan::exclusive of the counts: where each chunk's pairs start
//   3. grid_write.comp   each chunk writes its (cell, triangle) pairs
//   4. RadixSort::sort   the pairs by cell (key_bits = the bits of the cell count); stable, so each cell lists its
//                        triangles in increasing id
//   5. grid_ranges.comp  each run of equal cells gives that cell's [begin, end); the sorted triangle ids are
//                        copied after the ranges, into the one buffer the traversal reads (grid_common.glsl)
//
// The grid box comes from the CPU (Scene::bounds, computed when the scene is flattened for the frame), not from a
// GPU reduction. Three read-backs per build, to size the buffers: the boxes' cells in all and the number of chunks
// (step 1), the number of pairs (step 2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/gpu/gl/buffer.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/primitives/radix_sort.h"
#include "common/gpu/primitives/scan.h"
#include "common/gpu/gl/shader.h"
#include "grid_stats.h"
#include "uniform_grid.h"

namespace rt {

class GpuGrid {
public:
    GpuGrid();   // needs a current context
    // Builds the grid over the uploaded scene. Throws SceneError (one line, with the sizes) when the cells or the
    // pairs would not fit one shader storage block.
    void build(const gpu::GpuScene& scene, const GridParams& params);
    // Binds the grid (header, counters, cell ranges, triangle lists) for the traversal (grid.glsl).
    void bind() const;
    // The traversal's counters (grid.glsl, GRID_STATS): cleared by build(), read back (waits for the GPU).
    std::vector<std::uint64_t> traversal_stats() const;
    // The frame's stats of the grid and its walks (grid_stats.h; reads back the counters and the cell ranges).
    GridFrameStats frame_stats() const;

    const GridParams& params() const { return params_; }
    std::size_t pairs() const { return pairs_; }
    // Read-backs (stats and tests): [begin, end) per cell, and the triangle ids of all cells.
    std::vector<std::uint32_t> cell_ranges() const;
    std::vector<std::uint32_t> triangles() const;
    // Read-backs since the last build() began, each a wait for the GPU: the build's three (the boxes' cells, the
    // chunks, the pairs: they size the next passes), and the ones above.
    std::uint64_t syncs() const { return syncs_; }

    static constexpr std::size_t kStatCount = 32;   // uints of counters after the header (GRID_STAT_COUNT)
    static constexpr std::size_t kHeaderBytes = sizeof(GridParams) + kStatCount * 4;

private:
    GridParams params_;
    std::size_t pairs_ = 0;
    mutable std::uint64_t syncs_ = 0;
    gpu::Program chunks_, count_, write_, ranges_;
    gpu::Scan scan_;
    gpu::RadixSort sort_;
    gpu::Buffer grid_, offsets_, chunk_pairs_, total_, keys_, values_;
};

}  // namespace rt
