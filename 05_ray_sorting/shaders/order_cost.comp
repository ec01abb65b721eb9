#version 450 core
// --sort auto (sort_auto.h): how tight stage 04's lowest nodes would be over the batch in one order (the
// queue's, or a sorted one). Thread g builds node g of level 1 exactly as rh_build.comp does (rh_leaf, rh_union over
// the B rays the order puts at [gB, gB + B)) and measures its beam width where it meets the scene: radius
// + L sin(spread), the width rh_split_rays compares with an object node, at L = the longest ray of the node (tmax |d|)
// cut to an eighth of the scene's diagonal (order_choice.glsl: OC_REACH). Level 1 carries the traversal's cost: its
// width decides how many (ray, triangle) pairs reach the leaves.
// Each width is capped by the leaves' mean diameter (order_choice.glsl: oc_width_cap), which oc_mode 1 measures once
// per frame: the same pass sums the leaves' radii (thread g: leaves [16 g, 16 g + 16), OC_LEAVES_PER_THREAD) into
// oc_cost[6], [7].
// Widths are summed in fixed point (1/4096 of the diagonal per unit) as a 64-bit counter, first per work group in
// shared memory, then one atomic add per group, so the sum (and the choice) does not depend on the order threads run.
#include "04_ray_hierarchy/shaders/rh_common.glsl"
#include "order_choice.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = OC_BINDING_ORDER) readonly buffer Order { uint oc_order[]; };
layout(std430, binding = OC_BINDING_COST) buffer Cost { uint oc_cost[]; };
layout(std430, binding = OC_BINDING_LEAVES) readonly buffer Leaves { vec4 oc_leaves[]; };

uniform uint oc_count;       // rays of the batch
uniform uint oc_first;       // the batch's first ray in wf_rays_in (queue order)
uniform uint oc_branching;   // B: rays per level-1 node
uniform float oc_diagonal;   // the scene box's diagonal (> 0)
uniform uint oc_sorted;      // 0: queue order (oc_order unread), 1: the order in oc_order
uniform uint oc_slot;        // the sum goes to oc_cost[2 slot], [2 slot + 1] (order_choice.glsl)
uniform uint oc_mode;        // 0: the widths of an order's level-1 nodes; 1: the leaves' radii (slot 3)
uniform uint oc_leaf_count;  // the leaves' count (0: none, no cap)
uniform uint oc_leaf_stride; // vec4s from one leaf's sphere to the next

shared uint oc_lo[64], oc_hi[64];

#define OC_LEAVES_PER_THREAD 16u   // order_choice.h: kOrderLeavesPerThread (16 x the largest unit fit a uint)

// The fixed-point width of level-1 node g.
uint oc_width(uint g) {
    const uint first = g * oc_branching;
    const uint count = min(oc_branching, oc_count - first);
    RhNode kids[16];
    float longest = 0.0;
    for (uint k = 0u; k < count; ++k) {
        const uint i = oc_sorted == 1u ? oc_order[first + k] : oc_first + first + k;
        const WavefrontRay r = wf_rays_in[i];
        kids[k] = rh_leaf(r.origin, r.direction);
        longest = max(longest, r.tmax * length(r.direction));
    }
    return oc_fixed_width(rh_union(kids, count), longest, oc_diagonal);
}

void main() {
    const uint g = rt_global_index(), t = gl_LocalInvocationIndex;
    if (oc_mode == 1u) {
        uint sum = 0u;
        for (uint k = 0u; k < OC_LEAVES_PER_THREAD; ++k) {
            const uint leaf = g * OC_LEAVES_PER_THREAD + k;
            if (leaf < oc_leaf_count) sum += oc_radius_units(oc_leaves[leaf * oc_leaf_stride].w, oc_diagonal);
        }
        oc_lo[t] = sum;
    } else {
        const uint nodes = (oc_count + oc_branching - 1u) / oc_branching;
        oc_lo[t] = g < nodes ? min(oc_width(g), oc_width_cap(oc_cost[6], oc_cost[7], oc_leaf_count)) : 0u;
    }
    oc_hi[t] = 0u;
    barrier();
    // Tree reduction of 64-bit sums held as (lo, hi) pairs.
    for (uint stride = 32u; stride > 0u; stride >>= 1u) {
        if (t < stride) {
            const uint lo = oc_lo[t], add = oc_lo[t + stride];
            oc_lo[t] = lo + add;
            oc_hi[t] += oc_hi[t + stride] + (lo + add < lo ? 1u : 0u);
        }
        barrier();
    }
    if (t == 0u) {
        const uint old = atomicAdd(oc_cost[2u * oc_slot], oc_lo[0]);
        atomicAdd(oc_cost[2u * oc_slot + 1u], oc_hi[0] + (old + oc_lo[0] < old ? 1u : 0u));
    }
}
