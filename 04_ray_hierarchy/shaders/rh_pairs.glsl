// Candidate pairs (node, item) of one traversal step: item is a triangle, or an object (a run of triangles) at the
// first level with object culling. A chunk of pairs is either explicit (rh_pairs[rh_pair_first + i]) or, at the top
// level, implicit: every node of [rh_node_first, ...) with every item of [rh_item_first, + rh_item_count), node-major.
layout(std430, binding = RH_BINDING_PAIRS) readonly buffer Pairs { uvec2 rh_pairs[]; };

uniform uint rh_implicit;
uniform uint rh_pair_first;
uniform uint rh_node_first, rh_item_first, rh_item_count;

uvec2 rh_pair(uint i) {
    if (rh_implicit == 1u) return uvec2(rh_node_first + i / rh_item_count, rh_item_first + i % rh_item_count);
    return rh_pairs[rh_pair_first + i];
}
