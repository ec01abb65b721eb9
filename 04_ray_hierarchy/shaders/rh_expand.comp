#version 450 core
// Expansion of the surviving pairs of a chunk: pair i writes its n pairs to outputs [o, o + n), where o is its work
// group's first place among the chunk's children plus its place in the group (n and both places from rh_cull.comp). The
// side rh_cull.comp chose is split (rh_children.glsl). Only outputs inside the window [rh_window_first, +
// rh_window_count) are written: windows keep each output within one buffer, so any number of survivors is expanded (in
// several windows) and no pair is ever dropped. A thread writes at most B (16) children, or one mesh object's triangles
// (at most 4096: the loop limit of docs/gpu.md).
#include "rh_common.glsl"
#include "rh_pairs.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_ORDER) readonly buffer Order { uint rh_order[]; };
layout(std430, binding = RH_BINDING_OBJECTS) readonly buffer Objects { RhObject rh_objects[]; };
layout(std430, binding = RH_BINDING_PAIRS_OUT) writeonly buffer PairsOut { uvec2 rh_pairs_out[]; };
layout(std430, binding = RH_BINDING_COUNTS) readonly buffer Counts { uint rh_counts[]; };
layout(std430, binding = RH_BINDING_OFFSETS) readonly buffer Offsets { uint rh_group_offsets[]; };

uniform uint rh_window_first, rh_window_count;
uniform uint rh_branching;
uniform uint rh_identity_order;  // 1: level-1 objects hold triangles first + k (meshes), 0: rh_order[first + k]

#include "rh_children.glsl"

void main() {
    const uint i = rt_global_index();
    if (i >= rh_chunk_count()) return;
    const uint word = rh_counts[i];
    const uint n = word & 0x1fffu;
    if (n == 0u) return;
    const uint base = rh_group_offsets[rt_group_index()] + ((word >> 13) & 0x3ffffu);
    const uint first = max(base, rh_window_first), last = min(base + n, rh_window_first + rh_window_count);
    if (first >= last) return;
    rh_write_children(rh_pair(i), (word >> 31) == 1u, base, first, last, rh_window_first);
}
