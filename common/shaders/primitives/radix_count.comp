#version 450 core
// Radix sort, step 1 of a pass: how many keys of each tile have each digit. One work group per tile of SORT_TILE keys.
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"
#include "radix_common.glsl"

layout(local_size_x = SORT_THREADS) in;

layout(std430, binding = RT_BINDING_SORT_KEYS_IN) readonly buffer KeysIn { uint keys_in[]; };
layout(std430, binding = RT_BINDING_SORT_COUNTS) writeonly buffer Counts { uint counts[]; };

shared uint histogram[RADIX];

void main() {
    const uint tile = rt_group_index();
    const uint t = gl_LocalInvocationID.x;
    const uint count = window_count();
    if (t < RADIX) histogram[t] = 0u;
    barrier();
    // Order does not matter for counting: neighbouring threads read neighbouring keys.
    for (uint k = 0u; k < SORT_ITEMS; ++k) {
        const uint i = tile * SORT_TILE + k * SORT_THREADS + t;
        if (i < count) atomicAdd(histogram[(keys_in[i] >> shift) & mask], 1u);
    }
    barrier();
    if (t < RADIX) counts[count_index(t, tile)] = histogram[t];
}
