#version 450 core
// Build pass 3: after the sort, each cell's pairs are one run of equal keys. The first pair of a run writes the
// cell's begin, the last its end; cells no pair names keep [0, 0) (cleared before).
#include "grid_common.glsl"
#include "common/shaders/compute.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = GRID_BINDING_KEYS) readonly buffer GridKeys { uint grid_keys[]; };

uniform uint grid_pair_count;

void main() {
    const uint i = rt_global_index();
    if (i >= grid_pair_count) return;
    const uint cell = grid_keys[i];
    if (i == 0u || grid_keys[i - 1u] != cell) grid_data[2u * cell] = i;
    if (i + 1u == grid_pair_count || grid_keys[i + 1u] != cell) grid_data[2u * cell + 1u] = i + 1u;
}
