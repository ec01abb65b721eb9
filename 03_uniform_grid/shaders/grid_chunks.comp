#version 450 core
// Build pass 1: how many chunks of GRID_CHUNK_CELLS cells each triangle's bounding box has (grid_counts[t]), and
// the boxes' cells in all as a 64-bit sum (the bound the C++ side checks before any 32-bit offset can wrap).
#include "grid_build.glsl"

layout(std430, binding = GRID_BINDING_OFFSETS) writeonly buffer GridCounts { uint grid_counts[]; };
layout(std430, binding = GRID_BINDING_CHUNKS) buffer GridBoxCells { uint grid_box_cells[2]; };   // low, high word

uint grid_chunk_first(uint t) { return 0u; }   // not used by this pass
void grid_visit_cell(uint triangle, uint chunk, uint cell, uint k) {}

void main() {
    const uint t = rt_global_index();
    if (t >= grid_triangle_count) return;
    vec3 a, b, c;
    ivec3 first, last;
    const uint cells = grid_triangle_box(t, a, b, c, first, last);
    grid_counts[t] = grid_chunks_of(cells);
    // 64-bit add from two 32-bit atomics: the low word's old value tells whether this add carried.
    const uint old = atomicAdd(grid_box_cells[0], cells);
    if (old > 0xFFFFFFFFu - cells) atomicAdd(grid_box_cells[1], 1u);
}
