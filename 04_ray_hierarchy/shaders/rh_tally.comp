#version 450 core
// The traversal's counts summed on the GPU, read by the CPU once per frame (GpuRayHierarchy::stats()) instead of once
// per group: rh_tally holds, per ray kind, RH_TALLY_WORDS words of 64-bit sums.
//   mode 0, after a group: rh_info's group counts (RH_INFO_EXACT .. RH_INFO_BOX_TESTS, 64-bit each) are added to the
//          group's kind, the sphere tests too (the leaf pairs, with --sphere-test on), and the exact tests to the
//          pipeline's test counters (the total and the kind's), as the stage's other tests are;
//          A group marked in a speculative batch (rh_info.glsl: RH_INFO_OVERFLOW), or one after it, adds nothing:
//          it is traced again and adds its counts then;
//   mode 1, after a batch's fold: its re-tests per ray kind (rh_info[RH_INFO_FOLD_TESTS + kind]).
// One thread per 64-bit word pair, and the passes run one after another, so plain adds with a carry suffice.
#include "rh_common.glsl"
#include "rh_info.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_OFFSETS) buffer Tally { uint rh_tally[]; };

// Per kind: [0, 138) the words RH_INFO_EXACT .. RH_INFO_BOX_TESTS + 1, then the sphere tests and the fold tests.
#define RH_TALLY_WORDS 144u
#define RH_TALLY_GROUP_PAIRS 69u     // (RH_INFO_BOX_TESTS + 2 - RH_INFO_EXACT) / 2
#define RH_TALLY_SPHERE 138u
#define RH_TALLY_FOLD 140u
#define RH_TALLY_KINDS 5u            // ray kinds (WF_KIND_*; kRayKinds)

uniform uint rh_mode;
uniform uint rh_kind;          // mode 0: the group's ray kind
uniform uint rh_sphere_test;   // mode 0: 1 when the leaf pairs got the sphere test

void rh_tally_add(uint at, uint lo, uint hi) {
    const uint sum = rh_tally[at] + lo;
    rh_tally[at + 1u] += hi + (sum < lo ? 1u : 0u);
    rh_tally[at] = sum;
}

void main() {
    const uint i = rt_global_index();
    if (rh_mode == 0u && rh_overflowed()) return;   // the group is traced again: its counts then
    if (rh_mode == 0u) {
        const uint base = rh_kind * RH_TALLY_WORDS;
        if (i < RH_TALLY_GROUP_PAIRS) {
            const uint w = RH_INFO_EXACT + 2u * i;
            rh_tally_add(base + 2u * i, rh_info[w], rh_info[w + 1u]);
        } else if (i == RH_TALLY_GROUP_PAIRS && rh_sphere_test == 1u) {
            rh_tally_add(base + RH_TALLY_SPHERE, rh_info[RH_INFO_LEAF_PAIRS], rh_info[RH_INFO_LEAF_PAIRS + 1u]);
        } else if (i == RH_TALLY_GROUP_PAIRS + 1u) {
#ifdef COUNT_TESTS
            const uint lo = rh_info[RH_INFO_EXACT], hi = rh_info[RH_INFO_EXACT + 1u];
            for (uint c = 0u; c < 2u; ++c) {
                const uint counter = c == 0u ? RT_COUNTER_INTERSECTION_TESTS : RT_COUNTER_TESTS_FIRST + rh_kind;
                rt_counter_add(counter, lo);
                if (hi != 0u) atomicAdd(rt_counters[2u * counter + 1u], hi);
            }
#endif
        }
    } else if (i < RH_TALLY_KINDS) {
        rh_tally_add(i * RH_TALLY_WORDS + RH_TALLY_FOLD, rh_info[RH_INFO_FOLD_TESTS + i], 0u);
    }
}
