#version 450 core
// Build pass 3: each chunk writes its (cell, triangle) pairs from its scanned offset on, in cell order. Pairs are
// then sorted by cell (stable radix sort: triangles stay in increasing id within a cell).
#include "grid_build.glsl"

layout(std430, binding = GRID_BINDING_OFFSETS) readonly buffer GridChunkFirst { uint grid_chunk_firsts[]; };
layout(std430, binding = GRID_BINDING_CHUNKS) readonly buffer GridPairFirst { uint grid_pair_first[]; };
layout(std430, binding = GRID_BINDING_KEYS) writeonly buffer GridKeys { uint grid_keys[]; };
layout(std430, binding = GRID_BINDING_VALUES) writeonly buffer GridValues { uint grid_values[]; };

uniform uint grid_chunk_count;
uint grid_chunk_first(uint t) { return grid_chunk_firsts[t]; }

void grid_visit_cell(uint triangle, uint chunk, uint cell, uint k) {
    const uint i = grid_pair_first[chunk] + k;
    grid_keys[i] = cell;
    grid_values[i] = triangle;
}

void main() {
    const uint w = rt_global_index();
    if (w >= grid_chunk_count) return;
    grid_for_each_cell_of_chunk(w, grid_triangle_count);
}
