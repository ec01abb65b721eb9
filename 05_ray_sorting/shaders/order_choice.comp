#version 450 core
// --sort auto: of the batch's sorted orders (one, or two for reflection and refraction batches: the coarse and the
// fine direction cell), keep the tightest if its level-1 width sum (order_cost.comp) is below the queue's by more
// than the margin (order_choice.glsl); otherwise queue order (order[i] = first + i), so the gather and scatter passes
// after it, and the hierarchy, see the batch as stage 04 does. The result is written into oc_order. Decided on the
// GPU: no read-back. Thread 0 tallies the choice (oc_tally, per batch kind) and records it (oc_record), which the
// renderer reads once per frame, with its statistics.
#include "04_ray_hierarchy/shaders/rh_common.glsl"
#include "order_choice.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = OC_BINDING_ORDER) buffer Order { uint oc_order[]; };
layout(std430, binding = OC_BINDING_COST) readonly buffer Cost { uint oc_cost[]; };
layout(std430, binding = OC_BINDING_TALLY) buffer Tally { uint oc_tally[]; };
layout(std430, binding = OC_BINDING_ORDER_FINE) readonly buffer OrderFine { uint oc_order_fine[]; };

uniform uint oc_count;
uniform uint oc_first;
uniform uint oc_kind;         // 0: trace batch, 1: shadow batch
uniform uint oc_candidates;   // sorted orders: 1 (oc_order) or 2 (oc_order, then oc_order_fine)
uniform uint oc_record;       // where the choice is recorded: a word of the records (OC_RECORDS per kind), or
                              // OC_NO_RECORD

void oc_add64(uint at, uint value) {
    const uint old = atomicAdd(oc_tally[at], value);
    if (old + value < old) atomicAdd(oc_tally[at + 1u], 1u);
}

double oc_sum(uint slot) {   // exact below 2^53
    return double(oc_cost[2u * slot + 1u]) * 4294967296.0 + double(oc_cost[2u * slot]);
}

// order_choice.h: choose_order. 0 = the queue's order, 1 = oc_order, 2 = oc_order_fine.
uint oc_choice() {
    uint best = 1u;
    double width = oc_sum(1u);
    if (oc_candidates > 1u && oc_sum(2u) < width) {
        best = 2u;
        width = oc_sum(2u);
    }
    return width * OC_MARGIN_DENOMINATOR < oc_sum(0u) * (OC_MARGIN_DENOMINATOR - 1.0lf) ? best : 0u;
}

void main() {
    const uint i = rt_global_index();
    if (i >= oc_count) return;
    const uint choice = oc_choice();
    if (choice == 0u) oc_order[i] = oc_first + i;
    if (choice == 2u) oc_order[i] = oc_order_fine[i];
    if (i == 0u && oc_record < 2u * OC_RECORDS) oc_tally[2u * OC_TALLY_SIZE + oc_record] = choice;
    if (i == 0u && choice != 0u) {
        oc_add64(OC_TALLY_SIZE * oc_kind, 1u);
        oc_add64(OC_TALLY_SIZE * oc_kind + 2u, oc_count);
        if (choice == 2u) oc_add64(OC_TALLY_SIZE * oc_kind + 4u, 1u);
    }
}
