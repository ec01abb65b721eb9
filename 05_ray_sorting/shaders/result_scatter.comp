#version 450 core
// After tracing the sorted rays: puts each result back where the pipeline expects it, the slot of the ray's queue
// position (results[order[i] - first] = sorted_results[i]); a result is rs_stride uints (4 for a closest hit, 1 for
// occlusion).
#include "ray_sort.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RS_STAGE_BINDING_0) readonly buffer Order { uint rs_order[]; };
layout(std430, binding = RS_STAGE_BINDING_1) readonly buffer SortedResults { uint rs_sorted_results[]; };
layout(std430, binding = RS_STAGE_BINDING_2) writeonly buffer Results { uint rs_results[]; };

uniform uint rs_count;
uniform uint rs_first;
uniform uint rs_stride;

void main() {
    const uint i = rt_global_index();
    if (i >= rs_count) return;
    const uint slot = rs_order[i] - rs_first;
    for (uint k = 0u; k < rs_stride; ++k) rs_results[slot * rs_stride + k] = rs_sorted_results[i * rs_stride + k];
}
