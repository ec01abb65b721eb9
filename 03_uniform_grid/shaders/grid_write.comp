#version 450 core
// Build pass 2: each triangle writes its (cell, triangle) pairs from its scanned offset on, in cell order. Pairs
// are then sorted by cell (stable radix sort: triangles stay in increasing id within a cell).
#include "grid_build.glsl"

layout(std430, binding = GRID_BINDING_OFFSETS) readonly buffer GridOffsets { uint grid_offsets[]; };
layout(std430, binding = GRID_BINDING_KEYS) writeonly buffer GridKeys { uint grid_keys[]; };
layout(std430, binding = GRID_BINDING_VALUES) writeonly buffer GridValues { uint grid_values[]; };

void grid_visit_cell(uint triangle, uint cell, uint k) {
    const uint i = grid_offsets[triangle] + k;
    grid_keys[i] = cell;
    grid_values[i] = triangle;
}

void main() {
    const uint t = rt_global_index();
    if (t >= grid_triangle_count) return;
    grid_for_each_cell(t);
}
