#version 450 core
// Decompression, step 1: the size of each chunk in sorted order (then an exclusive scan gives where it starts).
#include "ray_sort.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RS_BINDING_0) readonly buffer ChunkIds { uint rs_chunk_ids[]; };   // sorted
layout(std430, binding = RS_BINDING_1) readonly buffer ChunkBases { uint rs_chunk_bases[]; };
layout(std430, binding = RS_BINDING_2) readonly buffer ChunkEnds { uint rs_chunk_ends[]; };
layout(std430, binding = RS_BINDING_3) writeonly buffer Sizes { uint rs_sizes[]; };

// The chunk count: the total of the compression's scan, on the GPU only (ray_sort.h: nothing is read back).
layout(std430, binding = RS_BINDING_5) readonly buffer ChunkCount { uint rs_chunk_count; };

void main() {
    const uint j = rt_global_index();
    if (j >= rs_chunk_count) return;
    const uint c = rs_chunk_ids[j];
    rs_sizes[j] = rs_chunk_ends[c] - rs_chunk_bases[c];
}
