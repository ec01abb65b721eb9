#version 450 core
// Build pass 1: how many cells each triangle overlaps (grid_counts[t]); an exclusive scan of them gives where each
// triangle's (cell, triangle) pairs start.
#include "grid_build.glsl"

layout(std430, binding = GRID_BINDING_OFFSETS) writeonly buffer GridCounts { uint grid_counts[]; };

void grid_visit_cell(uint triangle, uint cell, uint k) {}

void main() {
    const uint t = rt_global_index();
    if (t >= grid_triangle_count) return;
    grid_counts[t] = grid_for_each_cell(t);
}
