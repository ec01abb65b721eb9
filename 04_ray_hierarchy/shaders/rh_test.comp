#version 450 core
// The conservative test of one chunk of candidate pairs (node, item) at one level (rh_may_hit, rh_common.glsl):
// writes for each pair how many pairs it expands to (0 when rejected): the node's children with the same triangle,
// or, for an object, the object's triangles with the same node. Each work group of 64 pairs also writes its total:
// the shared scan (common/gpu/scan.h) runs over these totals only, 64 times fewer values than pairs. A pair's place
// inside its group comes from the shared-memory atomic that sums the group (in whatever order the threads run: the
// order of pairs inside a group changes nothing the traversal computes, the hits, the occlusion or the counts).
// rh_counts[i] packs the count (bits 0-12, at most 4096) and that place (bits 13-31, at most 63 x 4096).
#include "rh_common.glsl"
#include "rh_pairs.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_NODES) readonly buffer Nodes { RhNode rh_nodes[]; };
layout(std430, binding = RH_BINDING_SPHERES) readonly buffer Spheres { vec4 rh_spheres[]; };
layout(std430, binding = RH_BINDING_OBJECTS) readonly buffer Objects { RhObject rh_objects[]; };
layout(std430, binding = RH_BINDING_COUNTS) writeonly buffer Counts { uint rh_counts[]; };
layout(std430, binding = RH_BINDING_INFO) buffer Info { uint rh_info[]; };
layout(std430, binding = RH_BINDING_GROUP_SUMS) writeonly buffer GroupSums { uint rh_group_sums[]; };

uniform uint rh_count;           // pairs in the chunk
uniform uint rh_level_first;     // this level's node 0 in rh_nodes
uniform uint rh_children;        // nodes (or rays) on the level below
uniform uint rh_branching;
uniform uint rh_objects_mode;    // 1: items are objects

shared uint rh_group_survivors;   // summed in shared memory: one global atomic per work group, not per survivor
shared uint rh_group_sum;

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        rh_group_survivors = 0u;
        rh_group_sum = 0u;
    }
    barrier();
    const uint i = rt_global_index();
    if (i < rh_count) {
        const uvec2 p = rh_pair(i);
        const RhNode node = rh_nodes[rh_level_first + p.x];
        uint n = 0u;
        if (rh_objects_mode == 1u) {
            const RhObject o = rh_objects[p.y];
            if (rh_may_hit(node, o.sphere)) n = o.count;
        } else if (rh_may_hit(node, rh_spheres[p.y])) {
            n = min(rh_branching, rh_children - p.x * rh_branching);
        }
        uint place = 0u;
        if (n > 0u) {
            atomicAdd(rh_group_survivors, 1u);
            place = atomicAdd(rh_group_sum, n);
        }
        rh_counts[i] = n | place << 13;
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        rh_group_sums[rt_group_index()] = rh_group_sum;
        if (rh_group_survivors > 0u) atomicAdd(rh_info[0], rh_group_survivors);
    }
}
