#version 450 core
// Expansion of the surviving pairs of a chunk: output g of the window [rh_window_first, + rh_window_count) belongs
// to the pair i whose range [offsets[i], offsets[i] + counts[i]) holds g (a binary search over the exclusive scan:
// the last i with offsets[i] <= g), as its child number g - offsets[i]. Windows keep each output within one buffer,
// so any number of survivors is expanded (in several windows) and no pair is ever dropped.
#include "rh_common.glsl"
#include "rh_pairs.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_OBJECTS) readonly buffer Objects { RhObject rh_objects[]; };
layout(std430, binding = RH_BINDING_PAIRS_OUT) writeonly buffer PairsOut { uvec2 rh_pairs_out[]; };
layout(std430, binding = RH_BINDING_OFFSETS) readonly buffer Offsets { uint rh_offsets[]; };

uniform uint rh_count;           // pairs tested in the chunk (the length of rh_offsets)
uniform uint rh_window_first, rh_window_count;
uniform uint rh_branching;
uniform uint rh_objects_mode;

void main() {
    const uint k = rt_global_index();
    if (k >= rh_window_count) return;
    const uint g = rh_window_first + k;
    uint lo = 0u, hi = rh_count;   // the first index with offset > g lies in [lo, hi]
    while (lo < hi) {
        const uint mid = (lo + hi) / 2u;
        if (rh_offsets[mid] <= g) lo = mid + 1u; else hi = mid;
    }
    const uint i = lo - 1u;
    const uint local = g - rh_offsets[i];
    const uvec2 p = rh_pair(i);
    rh_pairs_out[k] = rh_objects_mode == 1u ? uvec2(p.x, rh_objects[p.y].first + local)
                                            : uvec2(p.x * rh_branching + local, p.y);
}
