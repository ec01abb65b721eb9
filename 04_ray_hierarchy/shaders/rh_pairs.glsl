// Candidate pairs (ray side, object side) of one traversal step (rh_common.glsl: the encoding). A chunk of pairs is
// either explicit (rh_pairs[rh_pair_first + i]) or, at the top, implicit: every node of the top ray level from
// rh_node_first with every item of [rh_item_first, + rh_item_count) (triangles, objects, or the object tree's top
// level; rh_item_flag marks triangles), node-major.
#include "rh_info.glsl"

layout(std430, binding = RH_BINDING_PAIRS) readonly buffer Pairs { uvec2 rh_pairs[]; };

// The chunk's length: rh_count, or, when the CPU has not read it back (rh_count_slot > 0), what the previous step's
// rh_cull.comp counted in rh_info[rh_count_slot] (the pass is then dispatched indirectly, from the arguments that
// pass's last work group wrote), at most rh_count, the window's room (a speculative batch may count more children
// than its window holds: those past it were not written, and the group is traced again).
uniform uint rh_count;
uniform uint rh_count_slot;
uint rh_chunk_count() { return rh_count_slot == 0u ? rh_count : min(rh_info[rh_count_slot], rh_count); }

uniform uint rh_implicit;
uniform uint rh_pair_first;
uniform uint rh_top_level;
uniform uint rh_node_first, rh_item_first, rh_item_count, rh_item_flag;

uvec2 rh_pair(uint i) {
    if (rh_implicit == 1u)
        return uvec2(rh_ray_side(rh_top_level, rh_node_first + i / rh_item_count),
                     rh_item_flag | (rh_item_first + i % rh_item_count));
    return rh_pairs[rh_pair_first + i];
}
