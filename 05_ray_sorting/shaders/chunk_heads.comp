#version 450 core
// Compression, step 1: head flag 1 where a run of equal keys (a chunk) starts.
#include "ray_sort.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RS_BINDING_0) readonly buffer Keys { uint rs_keys[]; };
layout(std430, binding = RS_BINDING_1) writeonly buffer Heads { uint rs_heads[]; };

uniform uint rs_count;

void main() {
    const uint i = rt_global_index();
    if (i >= rs_count) return;
    rs_heads[i] = i == 0u || rs_keys[i] != rs_keys[i - 1u] ? 1u : 0u;
}
