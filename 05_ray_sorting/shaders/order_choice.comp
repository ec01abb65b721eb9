#version 450 core
// --sort auto: keep the sorted order only where it makes level 1 tighter (order_cost.comp's sums: sorted below
// queue by more than the margin of order_choice.glsl);
// otherwise overwrite it with queue order (order[i] = first + i), so the gather and scatter passes after it, and the
// hierarchy, see the batch as stage 04 does. Decided on the GPU: no read-back. Thread 0 tallies a kept sort
// (oc_tally: batches and rays per batch kind, 64-bit), which the stats read once per frame.
#include "04_ray_hierarchy/shaders/rh_common.glsl"
#include "order_choice.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = OC_BINDING_ORDER) buffer Order { uint oc_order[]; };
layout(std430, binding = OC_BINDING_COST) readonly buffer Cost { uint oc_cost[]; };
layout(std430, binding = OC_BINDING_TALLY) buffer Tally { uint oc_tally[]; };

uniform uint oc_count;
uniform uint oc_first;
uniform uint oc_kind;   // 0: trace batch, 1: shadow batch

void oc_add64(uint at, uint value) {
    const uint old = atomicAdd(oc_tally[at], value);
    if (old + value < old) atomicAdd(oc_tally[at + 1u], 1u);
}

double oc_sum(uint at) { return double(oc_cost[at + 1u]) * 4294967296.0 + double(oc_cost[at]); }   // exact below 2^53

// order_choice.h: keep_sorted_order. The sort must be tighter by more than OC_MARGIN of the queue's width.
bool oc_sorted_is_tighter() {
    const double queue = oc_sum(0u), sorted = oc_sum(2u);
    return sorted * OC_MARGIN_DENOMINATOR < queue * (OC_MARGIN_DENOMINATOR - 1.0lf);
}

void main() {
    const uint i = rt_global_index();
    if (i >= oc_count) return;
    const bool sorted = oc_sorted_is_tighter();
    if (!sorted) oc_order[i] = oc_first + i;
    if (i == 0u && sorted) {
        oc_add64(4u * oc_kind, 1u);
        oc_add64(4u * oc_kind + 2u, oc_count);
    }
}
