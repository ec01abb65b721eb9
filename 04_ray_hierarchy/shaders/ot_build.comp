#version 450 core
// The object tree, rebuilt every frame (object_tree.h; C++ twin: build_object_tree in object_tree.cpp), one mode per
// dispatch (each mode its own program: OT_MODE) after rh_spheres.comp has written the triangles' spheres:
//   0 codes     per triangle: the 30-bit Morton code of its sphere's centre (cubic cells over the scene box) and
//               its id, for the shared radix sort (common/gpu/primitives/radix_sort.h), which sorts ids by code,
//               stably;
// then per level (ot_level 1 = the clusters over the sorted triangles, then each level over the one below), its
// groups (object_tree.cpp: group_heads) in three modes and a scan, nothing read back:
//   3 cuts      per node of the level below (per triangle for level 1): 1 where a group starts (node 0, and after
//               a boundary whose subtree of the codes' Cartesian tree holds more than 4 nodes), else 0; the host
//               scans these flags in place (exclusive, the total to level word 0 of ot_codes); neither runs
//               with ot_every_4;
//   4 heads     per node below: the group it starts (the scan's value), or with the fallback (a level the rule would
//               not halve) every 4th node; writes each group's first node and the level's size and first node,
//               and the dispatch of modes 1/2 over the level's groups (the next level's mode 4 runs over them too);
//   1 clusters  per group of level 1: the sphere of triangles rh_order[first, first + count), and the box of their
//               vertices;
//   2 level     per group of an upper level: the sphere and the box of nodes [first, first + count) below.
// Modes 1 and 2 also write the codes each group spans, for the next level's cuts. The host dispatches every level a
// tree of n triangles can have (each at most halves): modes 3 and the scan over a bound of the nodes below, modes 4
// (above level 1) and 1/2 over the GPU's counts; a level whose nodes below are fewer than two is empty (size 0).
//   5 all       a tree of at most kOneGroupTreeTriangles (gpu_ray_hierarchy.h): every level's modes 3, the scan, 4
//               and 1/2 in one work group, a barrier between them (ot_build_all): one dispatch for the whole tree.
#include "rh_common.glsl"
#include "rh_triangles.glsl"

#define OT_THREADS 64u
layout(local_size_x = OT_THREADS) in;

layout(std430, binding = RH_BINDING_SPHERES) readonly buffer Spheres { vec4 rh_spheres[]; };
layout(std430, binding = RH_BINDING_OBJECTS) buffer Objects { RhObject rh_objects[]; };
layout(std430, binding = RH_BINDING_KEYS) buffer Keys { uint ot_keys[]; };   // mode 0; after the sort, sorted
layout(std430, binding = RH_BINDING_ORDER) buffer Order { uint rh_order[]; };
// Modes 3 and 4: per node below, its cut flag and then (scanned in place) the number of groups starting before it.
layout(std430, binding = RH_BINDING_PAIRS_OUT) buffer Groups { uint ot_groups[]; };
// One buffer (a compute shader sees at most 16 storage blocks, and the scene's take most): first the levels' words,
// 4 a vec4 (ot_level_word: [0] the scan's total, the groups the rule makes; per level l >= 1, [2l] its nodes and
// [2l + 1] its node 0; from ot_args_word, 3 words a level: the dispatch of its modes 1/2, which
// glDispatchComputeIndirect reads from this buffer); then two halves of codes, the level below's from ot_codes_in
// and this level's from ot_codes_out: per node, x and y the codes it spans (first, last), and for this level's
// groups z their first node below (mode 4).
layout(std430, binding = RH_BINDING_COUNTS) buffer Codes { uvec4 ot_codes[]; };

// One program per mode (gpu_object_tree.cpp compiles this file with OT_MODE 0 to 5), so each holds only its own code
// (faster on llvmpipe than a mode uniform: the comment above compile_tree's twin, compile_spheres).
const uint ot_mode = OT_MODE;
#if OT_MODE == 5
// Mode 5 sets per level what the host sets for modes 1-4 (ot_build_all).
uint ot_level, ot_codes_in, ot_codes_out;
uniform uint ot_levels;         // the levels a tree of ot_triangles can have (the host's loop's)
uniform uint ot_codes_first;    // the first half of codes in ot_codes (the second follows ot_half later)
uniform uint ot_half;
#else
uniform uint ot_count;          // triangles (0), a bound of the nodes below (3, 4) or of the level's groups (1, 2)
uniform uint ot_level;          // modes 1-4: this level (1 = clusters)
uniform uint ot_codes_in;       // modes 1-4: the level below's codes in ot_codes (upper levels)
uniform uint ot_codes_out;      // modes 1, 2, 4: this level's
#endif
uniform uint ot_triangles;      // triangles in all
uniform uint ot_every_4;        // mode 4: 1 groups every 4 nodes whatever the codes (group_heads' every_4)
uniform uint ot_args_word;      // mode 4: level l's dispatch goes to level words ot_args_word + 3 (l - 1) + 0..2
uniform vec3 ot_box_min;
uniform float ot_scale;         // cells per unit (object_tree.cpp: morton_scale)

#define OT_BRANCHING 4u         // object_tree.h: kObjectBranching (= kClusterSize)

uint ot_level_word(uint w) { return ot_codes[w / 4u][w % 4u]; }
void ot_set_level_word(uint w, uint v) { ot_codes[w / 4u][w % 4u] = v; }

// Nodes on the level below this one (the triangles below level 1); 0 when that level is empty.
uint ot_below() { return ot_level == 1u ? ot_triangles : ot_level_word(2u * (ot_level - 1u)); }
// Does this level group its m nodes below? Not when one node below is the root: no level above it.
bool ot_grouped(uint m) { return ot_level == 1u || m > 1u; }
uint ot_first_code(uint k) { return ot_level == 1u ? ot_keys[k] : ot_codes[ot_codes_in + k].x; }
uint ot_last_code(uint k) { return ot_level == 1u ? ot_keys[k] : ot_codes[ot_codes_in + k].y; }

// object_tree.cpp: boundary_strength, between nodes k and k + 1 below.
uint ot_strength(uint k) {
    const uint x = ot_last_code(k) ^ ot_first_code(k + 1u);
    if (x != 0u) return 33u + uint(findMSB(x));
    return 1u + uint(findMSB(k ^ (k + 1u)));
}

// object_tree.cpp: group_heads' rule for boundary k of m nodes: does its subtree hold more than OT_BRANCHING?
bool ot_cut(uint k, uint m) {
    const uint s = ot_strength(k);
    uint left = 1u, right = 1u;
    while (left <= OT_BRANCHING && k >= left && ot_strength(k - left) < s) ++left;
    while (right <= OT_BRANCHING && k + right + 1u < m && ot_strength(k + right) <= s) ++right;
    return left + right > OT_BRANCHING;
}

// Bits 0..9 of v to every third bit.
uint ot_spread_bits(uint v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

uint ot_cell(float x, float lo) {
    precise float f = (x - lo) * ot_scale;
    if (!(f >= 0.0)) return 0u;
    if (f >= 1024.0) return 1023u;
    return uint(f);
}

// The sphere of spheres kids[0, count): the box of the spheres, its middle, the largest reach from there, padded
// as rh_triangle_sphere (object_tree.cpp: sphere_union). Loops of a constant OT_BRANCHING, so that the array stays
// in registers (a dynamically indexed one is private memory for every invocation: on llvmpipe, most of the pass).
vec4 ot_union(vec4 kids[OT_BRANCHING], uint count) {
    vec3 lo = vec3(RT_INFINITY), hi = vec3(-RT_INFINITY);
    for (uint k = 0u; k < OT_BRANCHING; ++k)
        if (k < count) {
            lo = min(lo, kids[k].xyz - kids[k].w);
            hi = max(hi, kids[k].xyz + kids[k].w);
        }
    const vec3 m = 0.5 * lo + 0.5 * hi;
    float r = 0.0;
    for (uint k = 0u; k < OT_BRANCHING; ++k)
        if (k < count) r = max(r, length(kids[k].xyz - m) + kids[k].w);
    return vec4(m, r * (1.0 + RH_PAD) + RH_PAD * max(rh_max_abs(m), rh_max_abs(hi - lo)) + 1e-30);
}

// Mode 0 for triangle i.
void ot_code_at(uint i) {
    const vec3 c = rh_spheres[i].xyz;
    ot_keys[i] = ot_spread_bits(ot_cell(c.x, ot_box_min.x)) << 2 | ot_spread_bits(ot_cell(c.y, ot_box_min.y)) << 1 |
                 ot_spread_bits(ot_cell(c.z, ot_box_min.z));
    rh_order[i] = i;
}

// Mode 3 for node i below.
void ot_cut_at(uint i) {
    const uint m = ot_below();
    const bool grouped = ot_grouped(m);
    ot_groups[i] = grouped && i < m && (i == 0u || ot_cut(i - 1u, m)) ? 1u : 0u;
}

// Mode 4 for node i below.
void ot_head_at(uint i) {
    const uint m = ot_below();
    const bool grouped = ot_grouped(m);
    const uint made = ot_level_word(0u);
    const bool fallback = ot_every_4 == 1u || 2u * made > m;   // group_heads: a level is at least halved
    const uint groups = !grouped ? 0u : fallback ? (m + OT_BRANCHING - 1u) / OT_BRANCHING : made;
    if (i == 0u) {
        const uvec3 grid = rt_dispatch_size(groups, OT_THREADS);
        const uint args = ot_args_word + 3u * (ot_level - 1u);
        ot_set_level_word(args, grid.x);
        ot_set_level_word(args + 1u, grid.y);
        ot_set_level_word(args + 2u, grid.z);
        ot_set_level_word(2u * ot_level, groups);
        ot_set_level_word(2u * ot_level + 1u, ot_level == 1u ? 0u
                                                             : ot_level_word(2u * ot_level - 1u) +
                                                                   ot_level_word(2u * ot_level - 2u));
    }
    if (!grouped || i >= m) return;
    if (fallback) {   // with ot_every_4 the host ran neither mode 3 nor the scan: the flags are not this level's
        if (i % OT_BRANCHING == 0u) ot_codes[ot_codes_out + i / OT_BRANCHING].z = i;
        return;
    }
    const uint before = ot_groups[i];
    if (i + 1u < m ? ot_groups[i + 1u] > before : made > before) ot_codes[ot_codes_out + before].z = i;
}

// Modes 1 and 2: group i of this level.
void ot_group_at(uint i) {
    const uint m = ot_below();
    const uint groups = ot_level_word(2u * ot_level);
    if (i >= groups) return;
    const uint b = ot_codes[ot_codes_out + i].z, e = i + 1u < groups ? ot_codes[ot_codes_out + i + 1u].z : m;
    RhObject o;
    o.level = ot_level;
    o.pad = 0u;
    o.count = e - b;
    vec4 kids[OT_BRANCHING];
    vec3 lo = vec3(RT_INFINITY), hi = vec3(-RT_INFINITY);
    if (ot_mode == 1u || (ot_mode == 5u && ot_level == 1u)) {
        o.first = b;
        for (uint k = 0u; k < OT_BRANCHING; ++k) {
            if (k >= o.count) break;
            const uint t = rh_order[o.first + k];
            kids[k] = rh_spheres[t];
            vec3 a, bb, c;
            rh_load_triangle(t, a, bb, c);
            lo = min(lo, min(a, min(bb, c)));
            hi = max(hi, max(a, max(bb, c)));
        }
    } else {
        o.first = ot_level_word(2u * ot_level - 1u) + b;
        for (uint k = 0u; k < OT_BRANCHING; ++k) {
            if (k >= o.count) break;
            const RhObject child = rh_objects[o.first + k];
            kids[k] = child.sphere;
            lo = min(lo, child.box_lo.xyz);
            hi = max(hi, child.box_hi.xyz);
        }
    }
    o.box_lo = vec4(lo, 0.0);
    o.box_hi = vec4(hi, 0.0);
    o.sphere = ot_union(kids, o.count);
    rh_objects[ot_level_word(2u * ot_level + 1u) + i] = o;
    ot_codes[ot_codes_out + i].xy = uvec2(ot_first_code(b), ot_last_code(e - 1u));
}

#if OT_MODE == 5
shared uint ot_sums[OT_THREADS];

// Each pass's writes seen by the whole group before the next pass reads them.
void ot_sync() {
    memoryBarrierBuffer();
    barrier();
}

// Mode 3's flags of this level's m nodes below, scanned in place (exclusive, the total to level word 0) by the
// group: each thread sums a run of them, thread 0 scans the runs' sums, each thread writes its run's prefixes.
void ot_scan_flags(uint lane, uint m) {
    const uint per = (m + OT_THREADS - 1u) / OT_THREADS, b = lane * per, e = min(b + per, m);
    uint sum = 0u;
    for (uint k = b; k < e; ++k) sum += ot_groups[k];
    ot_sums[lane] = sum;
    barrier();
    if (lane == 0u) {
        uint run = 0u;
        for (uint t = 0u; t < OT_THREADS; ++t) {
            const uint v = ot_sums[t];
            ot_sums[t] = run;
            run += v;
        }
        ot_set_level_word(0u, run);
    }
    barrier();
    uint run = ot_sums[lane];
    for (uint k = b; k < e; ++k) {
        const uint v = ot_groups[k];
        ot_groups[k] = run;
        run += v;
    }
    ot_sync();
}

// Mode 5: every level of a small tree in one work group, the same passes as the host's loop over modes 3, the scan,
// 4 and 1/2 (gpu_object_tree.cpp, build_tree), each over the GPU's own counts: one dispatch instead of four or five a
// level. A level's nodes below are the level word the last level's mode 4 wrote, read after the group's barrier.
void ot_build_all() {
    const uint lane = gl_LocalInvocationIndex;
    for (uint l = 1u; l <= ot_levels; ++l) {
        ot_level = l;
        ot_codes_in = ot_codes_first + (l % 2u) * ot_half;
        ot_codes_out = ot_codes_first + ((l - 1u) % 2u) * ot_half;
        const uint m = ot_below();
        if (ot_every_4 == 0u) {
            for (uint i = lane; i < m; i += OT_THREADS) ot_cut_at(i);
            ot_sync();
            ot_scan_flags(lane, m);
        }
        for (uint i = lane; i < m; i += OT_THREADS) ot_head_at(i);
        ot_sync();
        const uint groups = ot_level_word(2u * l);
        for (uint i = lane; i < groups; i += OT_THREADS) ot_group_at(i);
        ot_sync();
    }
}
#endif

void main() {
#if OT_MODE == 5
    ot_build_all();
#else
    const uint i = rt_global_index();
    if (i >= ot_count) return;
    if (ot_mode == 0u)
        ot_code_at(i);
    else if (ot_mode == 3u)
        ot_cut_at(i);
    else if (ot_mode == 4u)
        ot_head_at(i);
    else
        ot_group_at(i);
#endif
}
