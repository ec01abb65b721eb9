#include "gpu_grid.h"

#include <bit>
#include <string>

#include "common/gpu/gl/bindings.h"
#include "common/gpu/gl/gl_check.h"
#include "common/gpu/gl/storage_limit.h"
#include "common/scene/gltf/gltf_io.h"

namespace rt {

namespace {
constexpr unsigned kBindingGrid = 24, kBindingChunks = 27, kBindingOffsets = 28, kBindingKeys = 29, kBindingValues = 30;   // grid_common

void barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT); }

void check_fits(std::size_t bytes, std::size_t limit, const std::string& what) {
    if (bytes > limit)
        throw SceneError("the grid's " + what + " need " + gpu::describe_bytes(bytes) +
                         ", beyond this GPU's storage block limit of " + gpu::describe_bytes(limit) +
                         " (lower --grid-lambda or --grid-res)");
}
}  // namespace

GpuGrid::GpuGrid()
    : chunks_(gpu::Program::compute("03_uniform_grid/shaders/grid_chunks.comp")),
      count_(gpu::Program::compute("03_uniform_grid/shaders/grid_count.comp")),
      write_(gpu::Program::compute("03_uniform_grid/shaders/grid_write.comp")),
      ranges_(gpu::Program::compute("03_uniform_grid/shaders/grid_ranges.comp")),
      total_(sizeof(std::uint32_t)) {}

void GpuGrid::build(const gpu::GpuScene& scene, const GridParams& params) {
    syncs_ = 0;
    params_ = params;
    const std::size_t limit = gpu::max_storage_block_bytes();
    const std::size_t cells = params.cell_count, n = params.triangle_count;
    check_fits(kHeaderBytes + cells * 8, limit, std::to_string(cells) + " cells");

    // The header alone first: the build passes read the geometry from it.
    grid_.reserve(kHeaderBytes);
    grid_.upload(&params, sizeof(GridParams));
    scene.positions().bind(gpu::kBindingPositions);
    grid_.bind_range(kBindingGrid, 0, kHeaderBytes);

    // 1. Chunks of each triangle's box, scanned to where each triangle's chunks start. The boxes' cells in all bound
    //    the chunks and the pairs: below 2^32, no 32-bit count or offset of the build can wrap.
    offsets_.reserve(std::max<std::size_t>(n, 1) * sizeof(std::uint32_t));
    offsets_.bind(kBindingOffsets);
    chunk_pairs_.reserve(2 * sizeof(std::uint32_t));
    chunk_pairs_.clear_u32(0);
    chunk_pairs_.bind(kBindingChunks);
    chunks_.dispatch_threads(n);
    barrier();
    const std::vector<std::uint32_t> box_cells = chunk_pairs_.download<std::uint32_t>(2);
    ++syncs_;
    if (box_cells[1] != 0)
        throw SceneError("the grid's " + std::to_string(cells) + " cells are too many for the scene's " +
                         std::to_string(n) + " triangles: their bounding boxes cover more than 2^32 cells in all " +
                         "(lower --grid-lambda or --grid-res)");
    scan_.exclusive(offsets_, offsets_, n, &total_);
    const std::size_t chunks = total_.download_value<std::uint32_t>();
    ++syncs_;
    check_fits(chunks * 4, limit, std::to_string(chunks) + " build chunks");

    // 2. Count the cells of each chunk, scan the counts to where each chunk's pairs start; read back the pairs.
    chunk_pairs_.reserve(std::max<std::size_t>(chunks, 2) * sizeof(std::uint32_t));
    chunk_pairs_.bind(kBindingChunks);
    count_.set("grid_chunk_count", unsigned(chunks));
    count_.dispatch_threads(chunks);
    barrier();
    scan_.exclusive(chunk_pairs_, chunk_pairs_, chunks, &total_);
    pairs_ = total_.download_value<std::uint32_t>();
    ++syncs_;
    const std::size_t bytes = kHeaderBytes + cells * 8 + pairs_ * 4;
    check_fits(bytes, limit,
               std::to_string(cells) + " cells and " + std::to_string(pairs_) + " (cell, triangle) pairs");

    // The whole grid buffer: header, zeroed counters and ranges (cells no pair names stay [0, 0)).
    grid_.reserve(bytes);
    grid_.clear_u32(0);
    grid_.upload(&params, sizeof(GridParams));
    if (pairs_ == 0) return;

    // 3. Write the pairs.
    keys_.reserve(pairs_ * sizeof(std::uint32_t));
    values_.reserve(pairs_ * sizeof(std::uint32_t));
    scene.positions().bind(gpu::kBindingPositions);
    grid_.bind_range(kBindingGrid, 0, kHeaderBytes);
    offsets_.bind(kBindingOffsets);
    chunk_pairs_.bind(kBindingChunks);
    keys_.bind(kBindingKeys);
    values_.bind(kBindingValues);
    write_.set("grid_chunk_count", unsigned(chunks));
    write_.dispatch_threads(chunks);
    barrier();

    // 4. Sort the pairs by cell: only the bits a cell index uses.
    sort_.sort(keys_, values_, pairs_, unsigned(std::bit_width(std::uint32_t(cells - 1))));

    // 5. Cell ranges, then the triangle ids after them.
    grid_.bind_range(kBindingGrid, 0, bytes);
    keys_.bind(kBindingKeys);
    ranges_.set("grid_pair_count", unsigned(pairs_));
    ranges_.dispatch_threads(pairs_);
    values_.copy_to(grid_, pairs_ * 4, 0, kHeaderBytes + cells * 8);
    barrier();
}

void GpuGrid::bind() const {
    grid_.bind_range(kBindingGrid, 0, kHeaderBytes + std::size_t(params_.cell_count) * 8 + pairs_ * 4);
}

std::vector<std::uint64_t> GpuGrid::traversal_stats() const {
    ++syncs_;
    const std::vector<std::uint32_t> words = grid_.download<std::uint32_t>(kStatCount, sizeof(GridParams) / 4);
    std::vector<std::uint64_t> stats(kStatCount / 2);
    for (std::size_t i = 0; i < stats.size(); ++i) stats[i] = words[2 * i] | std::uint64_t(words[2 * i + 1]) << 32;
    return stats;
}

GridFrameStats GpuGrid::frame_stats() const {
    GridFrameStats stats;
    stats.built = true;
    stats.resolution = params_.res;
    stats.cells = params_.cell_count;
    stats.pairs = pairs_;
    count_cell_occupancy(cell_ranges(), stats);
    // grid.glsl's counters: rays [k], cells visited [kRayKinds + k], tests [2 kRayKinds + k], bound reached
    // [3 kRayKinds].
    const std::vector<std::uint64_t> s = traversal_stats();
    for (std::size_t k = 0; k < std::size_t(kRayKinds); ++k)
        stats.walks[k] = {s[k], s[kRayKinds + k], s[2 * kRayKinds + k]};
    stats.loop_bound_reached = s[3 * kRayKinds];
    stats.gpu_cpu_syncs = syncs_;
    return stats;
}

std::vector<std::uint32_t> GpuGrid::cell_ranges() const {
    ++syncs_;
    return grid_.download<std::uint32_t>(std::size_t(params_.cell_count) * 2, kHeaderBytes / 4);
}

std::vector<std::uint32_t> GpuGrid::triangles() const {
    ++syncs_;
    return grid_.download<std::uint32_t>(pairs_, kHeaderBytes / 4 + std::size_t(params_.cell_count) * 2);
}

}  // namespace rt
