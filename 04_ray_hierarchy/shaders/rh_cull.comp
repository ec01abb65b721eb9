#version 450 core
// The conservative test of one chunk of candidate pairs (ray side, object side) (rh_pairs.glsl), each on its own
// levels: a ray node against an object node or a triangle (rh_may_hit, then with --box-test its box: rh_node_box_test),
// a single ray against an object node (rh_ray_may_hit, then with --box-test its box: rh_ray_box_test). A survivor
// splits one side (object_tree.h): the ray node into its children, or the object node into its children (nodes, or a
// leaf's triangles); a triangle is never split, a single ray neither. (ray, triangle) pairs are not tested here:
// rh_leaf.comp gives them the sphere and box tests and the exact test. Every split takes one side one level down, so
// the pairs of one step are equally deep and the (ray, triangle) pairs are all in the last step, which only
// rh_leaf.comp sees.
//
// Writes for each pair how many pairs it expands to (0 when rejected), for rh_expand.comp; or, compiled with
// RH_CULL_WRITES_CHILDREN for a step whose children all fit one window, writes those children itself
// (rh_children.glsl). A pair's place inside its work group of 64 comes from the shared-memory atomic that sums the
// group, and the group's first place among the chunk's children from one atomic on the children's count
// (rh_info[rh_children_slot]), which thereby ends as their number: no scan, no pass between this one and
// rh_expand.comp (a scan of the groups' sums would cost up to three more dispatches per step).
// Both atomics hand out places in whatever order the threads and groups run: the order of the pairs changes nothing
// the traversal computes, the hits, the occlusion or the counts. With RH_CULL_WRITES_CHILDREN the last group to finish
// also writes the next step's indirect dispatch from the children's final count (the "last block" of a reduction:
// every group counts itself done after its add, so the group that counts last has seen every add): no rh_args.comp
// pass, one dispatch less per step.
// In a speculative batch (gpu_ray_hierarchy.cpp, trace) every step writes its children this way, into one
// window of rh_window_room pairs: children past it are not written, the group is marked (rh_mark_overflow) and the
// pass leaves the next step at most the window (rh_chunk_count), and the passes after the mark test nothing more.
// rh_counts[i] packs the count (bits 0-12, at most 4096), that place (bits 13-30, at most 63 x 4096) and the side
// split (bit 31: the object side).
#include "rh_common.glsl"
#include "rh_triangles.glsl"
#include "rh_pairs.glsl"
#include "rh_info.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_NODES) readonly buffer Nodes { RhNode rh_nodes[]; };
layout(std430, binding = RH_BINDING_OBJECTS) readonly buffer Objects { RhObject rh_objects[]; };
#ifdef RH_CULL_WRITES_CHILDREN
// The step's children all fit one window (gpu_ray_traversal.cpp, test_chunk: `chain`): each survivor writes its
// children itself once its group's place is known, and the step needs no rh_expand.comp.
layout(std430, binding = RH_BINDING_PAIRS_OUT) writeonly buffer PairsOut { uvec2 rh_pairs_out[]; };
layout(std430, binding = RH_BINDING_CULL_ORDER) readonly buffer Order { uint rh_order[]; };
layout(std430, binding = RH_BINDING_OFFSETS) writeonly buffer Args { uint rh_args[]; };   // as rh_args.comp's
uniform uint rh_identity_order;  // as rh_expand.comp's
uniform uint rh_args_first;      // where the next step's 3 dispatch arguments go
uniform uint rh_window_room;     // pairs the next step's window holds
shared uint rh_group_base;
#else
layout(std430, binding = RH_BINDING_COUNTS) writeonly buffer Counts { uint rh_counts[]; };
layout(std430, binding = RH_BINDING_GROUP_OFFSETS) writeonly buffer GroupOffsets { uint rh_group_offsets[]; };
#endif

uniform uint rh_level_first[32];   // ray level l >= 1: its node 0 in rh_nodes
uniform uint rh_level_nodes[32];   // nodes on ray level l (level 0: the group's rays)
uniform uint rh_group_first;       // wf_rays_in index of the group's ray 0
uniform uint rh_branching;
uniform uint rh_split_by_width;    // 1 (--objects tree): the side rh_split_rays picks; 0: the object side first
uniform uint rh_box_test;          // 1 (--box-test on): a single ray against an object node's box too
uniform uint rh_children_slot;     // RH_INFO_STEP_COUNT + step + 1: the children's count (0 before the pass)

#ifdef RH_CULL_WRITES_CHILDREN
#include "rh_children.glsl"
#endif

shared uint rh_group_sum;
// The group's counts per ray level, four 8-bit fields in one word so that a pair adds them with one shared atomic
// (a work group has 64 pairs, so no field passes 255): pairs tested, those kept, and of them the ones whose object
// side is an object node (not a triangle); fewer atomics, a faster pass (04's README, "The traversal").
shared uint rh_level_counts[32];
#define RH_COUNT_IN 1u
#define RH_COUNT_OUT (1u << 8)
#define RH_COUNT_OBJECT_IN (1u << 16)
#define RH_COUNT_OBJECT_OUT (1u << 24)

void main() {
    const uint lane = gl_LocalInvocationIndex;
    if (lane < 32u) rh_level_counts[lane] = 0u;
    if (lane == 0u) rh_group_sum = 0u;
    barrier();
    const uint i = rt_global_index();
    uvec2 p = uvec2(0u);
    uint n = 0u, place = 0u, split_objects = 0u;
    if (i < rh_chunk_count() && !rh_overflowed()) {
        p = rh_pair(i);
        const uint level = rh_ray_level(p.x), index = rh_ray_index(p.x);
        const bool triangle = rh_is_triangle(p.y);
        if (!(level == 0u && triangle)) {   // (ray, triangle) pairs are rh_leaf.comp's (only the last step has them)
            // The object side's bounds: an object node's sphere and box, or a triangle's, from its vertices (as in
            // rh_leaf.comp; a buffer of the triangles' spheres would be a 17th storage block with --heatmap).
            vec4 s;
            vec3 lo, hi;
            if (triangle) {
                vec3 a, b, c;
                rh_load_triangle(p.y & ~RH_TRIANGLE_FLAG, a, b, c);
                s = rh_triangle_sphere(a, b, c);
                lo = min(a, min(b, c));
                hi = max(a, max(b, c));
            } else {
                const RhObject o = rh_objects[p.y];
                s = o.sphere;
                lo = o.box_lo.xyz;
                hi = o.box_hi.xyz;
            }
            bool may_hit, split_rays = false;
            if (level == 0u) {   // a single ray, against an object node
                const WavefrontRay r = wf_rays_in[rh_group_first + index];
                may_hit = rh_ray_may_hit(r.origin, r.direction, r.tmax, s);
                if (may_hit && rh_box_test == 1u) may_hit = rh_ray_box_test(r.origin, r.direction, r.tmax, lo, hi);
            } else {
                const RhNode node = rh_nodes[rh_level_first[level] + index];
                may_hit = rh_may_hit(node, s);
                if (may_hit && rh_box_test == 1u) may_hit = rh_node_box_test(node, lo, hi);   // --box-test
                split_rays = triangle || (rh_split_by_width == 1u && rh_split_rays(node, s));
            }
            uint counts = RH_COUNT_IN + (triangle ? 0u : RH_COUNT_OBJECT_IN);
            if (may_hit) counts += RH_COUNT_OUT + (triangle ? 0u : RH_COUNT_OBJECT_OUT);
            atomicAdd(rh_level_counts[level], counts);
            if (may_hit) {
                if (split_rays) {
                    n = min(rh_branching, rh_level_nodes[level - 1u] - index * rh_branching);
                } else {
                    n = rh_objects[p.y].count;
                    split_objects = 1u;
                }
            }
        }
        if (n > 0u) place = atomicAdd(rh_group_sum, n);
#ifndef RH_CULL_WRITES_CHILDREN
        rh_counts[i] = n | place << 13 | split_objects << 31;
#endif
    }
    barrier();
    if (lane == 0u) {
        const uint group_first = atomicAdd(rh_info[rh_children_slot], rh_group_sum);
#ifdef RH_CULL_WRITES_CHILDREN
        rh_group_base = group_first;
        // The next step's dispatch, by the last group done: its add came before its done count (the barrier), and
        // so did every other group's, so the atomic read sees the children's final count.
        memoryBarrierBuffer();
        const uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumWorkGroups.z;
        if (atomicAdd(rh_info[RH_INFO_GROUPS_DONE], 1u) == groups - 1u) {
            const uint children = atomicAdd(rh_info[rh_children_slot], 0u);
            if (children > rh_window_room) rh_mark_overflow();
            const uvec3 grid = rt_dispatch_size(min(children, rh_window_room), 64u);
            rh_args[rh_args_first] = grid.x;
            rh_args[rh_args_first + 1u] = grid.y;
            rh_args[rh_args_first + 2u] = grid.z;
            atomicExchange(rh_info[RH_INFO_GROUPS_DONE], 0u);   // for the next step's pass
        }
#else
        rh_group_offsets[rt_group_index()] = group_first;
#endif
    }
    if (lane < 32u) {   // rh_add64 adds nothing for a level no pair was on
        const uint c = rh_level_counts[lane];
        rh_add64(RH_INFO_LEVEL_IN + 2u * lane, c & 0xffu);
        rh_add64(RH_INFO_LEVEL_OUT + 2u * lane, (c >> 8) & 0xffu);
        rh_add64(RH_INFO_OBJECT_IN, (c >> 16) & 0xffu);
        rh_add64(RH_INFO_OBJECT_OUT, c >> 24);
    }
#ifdef RH_CULL_WRITES_CHILDREN
    barrier();
    const uint base = rh_group_base + place;
    if (n > 0u) rh_write_children(p, split_objects == 1u, base, base, min(base + n, rh_window_room), 0u);
#endif
}
