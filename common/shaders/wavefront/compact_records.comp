#version 450 core
// Queue compaction, last step (flags -> exclusive scan -> this): the used slots of a pass' output (flags[i] != 0)
// move to out[offsets[i]], keeping their order. Records are `stride` uints long (rays 16, hits 20); one thread per
// uint of the output slots, so the copy is coalesced.
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RT_BINDING_COMPACT_FLAGS) readonly buffer Flags { uint flags[]; };
layout(std430, binding = RT_BINDING_COMPACT_OFFSETS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = RT_BINDING_COMPACT_VALUES) readonly buffer Slots { uint slots[]; };
layout(std430, binding = RT_BINDING_COMPACT_OUT) writeonly buffer Out { uint compact_out[]; };

uniform uint n;        // slots
uniform uint stride;   // uints per record

void main() {
    const uint i = rt_global_index();
    const uint slot = i / stride, word = i % stride;
    if (slot >= n || flags[slot] == 0u) return;
    compact_out[offsets[slot] * stride + word] = slots[i];
}
