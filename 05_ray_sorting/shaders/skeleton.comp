#version 450 core
// Decompression, step 2: on a skeleton of 1s and head flags of 0s (cleared before), each sorted chunk writes its
// first ray's index where the chunk starts in the sorted order, and a head flag there. The inclusive segmented scan
// of the skeleton then counts up from each chunk's first ray: the sorted order.
#include "ray_sort.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RS_BINDING_0) readonly buffer ChunkIds { uint rs_chunk_ids[]; };   // sorted
layout(std430, binding = RS_BINDING_1) readonly buffer ChunkBases { uint rs_chunk_bases[]; };
layout(std430, binding = RS_BINDING_2) readonly buffer Starts { uint rs_starts[]; };   // exclusive scan of sizes
layout(std430, binding = RS_BINDING_3) buffer Skeleton { uint rs_skeleton[]; };
layout(std430, binding = RS_BINDING_4) buffer Heads { uint rs_heads[]; };

// The chunk count: the total of the compression's scan, on the GPU only (ray_sort.h: nothing is read back).
layout(std430, binding = RS_BINDING_5) readonly buffer ChunkCount { uint rs_chunk_count; };
uniform uint rs_first;   // added to every index: the queue position of key 0

void main() {
    const uint j = rt_global_index();
    if (j >= rs_chunk_count) return;
    // BEGIN EXERCISE 05.decompression: sorted chunk j starts at rs_starts[j] in the sorted order; write there its
    // first ray's queue index (rs_first + the base of chunk rs_chunk_ids[j]) and a head flag, so that the segmented
    // scan counts up from it over the chunk's rays.
    rs_skeleton[rs_starts[j]] = rs_first + rs_chunk_bases[rs_chunk_ids[j]];
    rs_heads[rs_starts[j]] = 1u;
    // STUB: rs_skeleton[rs_starts[j]] = rs_first + rs_starts[j];
    // STUB: rs_heads[rs_starts[j]] = 1u;
    // END EXERCISE
}
