#version 450 core
// One level of the hierarchy, bottom-up (one dispatch per level): parent j bounds children
// [j * B, min((j + 1) * B, child_count)). Level 1's children are the group's rays (leaves, made here with rh_leaf),
// higher levels' children the nodes of the level below. rh_common.glsl: the union.
#include "rh_common.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_NODES) buffer Nodes { RhNode rh_nodes[]; };

uniform uint rh_from_rays;     // 1: children are rays wf_rays_in[rh_child_first + k]
uniform uint rh_child_first;   // first child (ray index, or node index in rh_nodes)
uniform uint rh_child_count;
uniform uint rh_parent_first;  // where parent 0 goes in rh_nodes
uniform uint rh_parent_count;
uniform uint rh_branching;

void main() {
    const uint j = rt_global_index();
    if (j >= rh_parent_count) return;
    const uint first = j * rh_branching;
    const uint count = min(rh_branching, rh_child_count - first);
    RhNode kids[16];
    for (uint k = 0u; k < count; ++k) {
        if (rh_from_rays == 1u) {
            const WavefrontRay r = wf_rays_in[rh_child_first + first + k];
            kids[k] = rh_leaf(r.origin, r.direction);
        } else {
            kids[k] = rh_nodes[rh_child_first + first + k];
        }
    }
    rh_nodes[rh_parent_first + j] = rh_union(kids, count);
}
