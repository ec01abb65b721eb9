// Shared by the build passes. A triangle's cells are the cells of its bounding box it overlaps; a large triangle's
// box can hold hundreds of thousands of cells (the floor of a big scene), too many for one invocation: Mesa's
// llvmpipe ends a shader invocation's loops silently after 65,535 iterations in all (docs/gpu.md, "Known limit"),
// and on any GPU one thread doing a whole floor serializes the build. So the box is cut into chunks of
// GRID_CHUNK_CELLS consecutive cells (x fastest, then y, then z) and each chunk is one invocation:
//
//   grid_chunks.comp  one thread per triangle: how many chunks its box has
//   (exclusive scan)  -> where each triangle's chunks start; their total is the number of chunk invocations
//   grid_count.comp   one thread per chunk: how many of its cells the triangle overlaps
//   (exclusive scan)  -> where each chunk's (cell, triangle) pairs start
//   grid_write.comp   one thread per chunk: writes its pairs
//
// A triangle's chunks are consecutive and each walks its cells in order, so the pairs come out exactly as one thread
// per triangle would write them: by triangle, then cell order within it.
#include "grid_common.glsl"
#include "common/shaders/compute.glsl"

layout(local_size_x = 64) in;

// At most ~12 loop iterations per cell (the cell loop and the overlap test's axis loops): a chunk stays far below
// llvmpipe's 65,535.
const uint GRID_CHUNK_CELLS = 512u;

// The cells of triangle t's bounding box (first..last, inclusive) and their number (0 if the box is empty).
uint grid_triangle_box(uint t, out vec3 a, out vec3 b, out vec3 c, out ivec3 first, out ivec3 last) {
    grid_load_triangle(t, a, b, c);
    grid_triangle_cell_range(a, b, c, first, last);
    if (any(lessThan(last, first))) return 0u;
    const uvec3 size = uvec3(last - first) + 1u;
    return size.x * size.y * size.z;   // <= kMaxGridResPerAxis^3 = 2^30
}

uint grid_chunks_of(uint cells) { return (cells + GRID_CHUNK_CELLS - 1u) / GRID_CHUNK_CELLS; }

// Supplied by each pass: where triangle t's chunks start (the scan of grid_chunks.comp's counts), and what to do
// with the k-th cell a chunk's triangle overlaps.
uint grid_chunk_first(uint t);
void grid_visit_cell(uint triangle, uint chunk, uint cell, uint k);

// The triangle whose chunks include chunk w: the last t with chunk_first[t] <= w (a binary search over the scanned
// chunk counts; triangles without chunks share their start with the next one and are skipped by "last").
uint grid_chunk_triangle(uint w, uint triangle_count) {
    uint lo = 0u, hi = triangle_count;   // chunk_first[lo] <= w < chunk_first[hi] (hi = n: past the end)
    while (hi - lo > 1u) {
        const uint mid = (lo + hi) / 2u;
        if (grid_chunk_first(mid) <= w) lo = mid; else hi = mid;
    }
    return lo;
}

// Walks chunk w's cells and calls grid_visit_cell(t, w, cell index, k) for the k-th one its triangle overlaps; returns
// how many it overlaps.
uint grid_for_each_cell_of_chunk(uint w, uint triangle_count) {
    const uint t = grid_chunk_triangle(w, triangle_count);
    vec3 a, b, c;
    ivec3 first, last;
    const uint cells = grid_triangle_box(t, a, b, c, first, last);
    const uint begin = (w - grid_chunk_first(t)) * GRID_CHUNK_CELLS, end = min(begin + GRID_CHUNK_CELLS, cells);
    // The chunk's first cell from its linear index in the box; then step x, carrying into y and z.
    const uint nx = uint(last.x - first.x) + 1u, ny = uint(last.y - first.y) + 1u;
    ivec3 cell = first + ivec3(begin % nx, (begin / nx) % ny, begin / (nx * ny));
    // BEGIN EXERCISE 03.grid_cells: walk the chunk's cells (x fastest, then y, then z) and, for each one the
    // triangle overlaps (grid_triangle_overlaps_cell), call grid_visit_cell(t, w, cell index, k) with k counting
    // them; return how many.
    uint k = 0u;
    for (uint i = begin; i < end; ++i) {
        if (grid_triangle_overlaps_cell(cell, a, b, c)) grid_visit_cell(t, w, grid_cell_index(cell), k++);
        if (++cell.x > last.x) {
            cell.x = first.x;
            if (++cell.y > last.y) { cell.y = first.y; ++cell.z; }
        }
    }
    return k;
    // STUB: return 0u;
    // END EXERCISE
}
