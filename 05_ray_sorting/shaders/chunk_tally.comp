#version 450 core
// Compression's bookkeeping: one thread adds the chunk count of this sort (the total of the compression's scan) to a
// 64-bit sum per tally slot, on the GPU, so that the frame's statistics read the sums once instead of each sort
// reading its count back (ray_sort.h).
#include "ray_sort.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = RS_BINDING_0) readonly buffer ChunkCount { uint rs_chunk_count; };
layout(std430, binding = RS_BINDING_1) buffer Tally { uvec2 rs_tally[]; };   // (low, high) words per slot

uniform uint rs_slot;

void main() {
    const uvec2 sum = rs_tally[rs_slot];
    uint carry;
    const uint low = uaddCarry(sum.x, rs_chunk_count, carry);
    rs_tally[rs_slot] = uvec2(low, sum.y + carry);
}
