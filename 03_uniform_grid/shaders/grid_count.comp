#version 450 core
// Build pass 2: one thread per chunk: how many of its cells its triangle overlaps (grid_chunk_pairs[w]); an
// exclusive scan of them gives where each chunk's (cell, triangle) pairs start, and the number of pairs.
#include "grid_build.glsl"

layout(std430, binding = GRID_BINDING_OFFSETS) readonly buffer GridChunkFirst { uint grid_chunk_firsts[]; };
layout(std430, binding = GRID_BINDING_CHUNKS) writeonly buffer GridChunkPairs { uint grid_chunk_pairs[]; };

uniform uint grid_chunk_count;

uint grid_chunk_first(uint t) { return grid_chunk_firsts[t]; }
void grid_visit_cell(uint triangle, uint chunk, uint cell, uint k) {}

void main() {
    const uint w = rt_global_index();
    if (w >= grid_chunk_count) return;
    grid_chunk_pairs[w] = grid_for_each_cell_of_chunk(w, grid_triangle_count);
}
