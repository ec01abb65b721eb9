#version 450 core
// Compression, step 3 (after the exclusive scan of the head flags, which numbers the chunks): the chunk arrays.
// A chunk's first key writes its key, its id (the value the radix sort carries) and its base; its last key writes
// its end, so size = end - base.
#include "ray_sort.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RS_BINDING_0) readonly buffer Keys { uint rs_keys[]; };
layout(std430, binding = RS_BINDING_1) readonly buffer Heads { uint rs_heads[]; };
layout(std430, binding = RS_BINDING_2) readonly buffer Offsets { uint rs_chunk_of[]; };   // exclusive scan of heads
layout(std430, binding = RS_BINDING_3) writeonly buffer ChunkKeys { uint rs_chunk_keys[]; };
layout(std430, binding = RS_BINDING_4) writeonly buffer ChunkIds { uint rs_chunk_ids[]; };
layout(std430, binding = RS_BINDING_5) writeonly buffer ChunkBases { uint rs_chunk_bases[]; };
layout(std430, binding = RS_BINDING_6) writeonly buffer ChunkEnds { uint rs_chunk_ends[]; };

uniform uint rs_count;

void main() {
    const uint i = rt_global_index();
    if (i >= rs_count) return;
    const uint chunk = rs_chunk_of[i] + rs_heads[i] - 1u;   // the chunk key i belongs to
    if (rs_heads[i] != 0u) {
        rs_chunk_keys[chunk] = rs_keys[i];
        rs_chunk_ids[chunk] = chunk;
        rs_chunk_bases[chunk] = i;
    }
    if (i + 1u == rs_count || rs_heads[i + 1u] != 0u) rs_chunk_ends[chunk] = i + 1u;
}
