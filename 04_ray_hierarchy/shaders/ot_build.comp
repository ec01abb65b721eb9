#version 450 core
// The object tree, rebuilt every frame (object_tree.h; C++ twin: build_object_tree in object_tree.cpp), one mode per
// dispatch after rh_spheres.comp has written the triangles' spheres:
//   0 codes     per triangle: the 30-bit Morton code of its sphere's centre (cubic cells over the scene box) and
//               its id, for the shared radix sort (common/gpu/primitives/radix_sort.h), which sorts ids by code,
//               stably;
//   1 clusters  per node of level 1: the sphere of triangles rh_order[first, first + kClusterSize), and the box of
//               their vertices;
//   2 level     per node of an upper level: the sphere and the box of nodes [first, first + kObjectBranching) of the
//               level below.
#include "rh_common.glsl"
#include "rh_triangles.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_SPHERES) readonly buffer Spheres { vec4 rh_spheres[]; };
layout(std430, binding = RH_BINDING_OBJECTS) buffer Objects { RhObject rh_objects[]; };
layout(std430, binding = RH_BINDING_KEYS) buffer Keys { uint ot_keys[]; };
layout(std430, binding = RH_BINDING_ORDER) buffer Order { uint rh_order[]; };

uniform uint ot_mode;
uniform uint ot_count;          // threads: triangles (0) or nodes of the level (1, 2)
uniform uint ot_triangles;      // mode 1: triangles in all
uniform uint ot_child_first;    // mode 2: the level below's node 0
uniform uint ot_child_count;    // mode 2: nodes on the level below
uniform uint ot_node_first;     // modes 1, 2: where this level's node 0 goes
uniform uint ot_level;          // modes 1, 2: this level (1 = clusters)
uniform uint ot_fanout;         // modes 1, 2: kClusterSize or kObjectBranching
uniform vec3 ot_box_min;
uniform float ot_scale;         // cells per unit (object_tree.cpp: morton_scale)

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
// as rh_triangle_sphere (object_tree.cpp: sphere_union).
vec4 ot_union(vec4 kids[16], uint count) {
    vec3 lo = vec3(RT_INFINITY), hi = vec3(-RT_INFINITY);
    for (uint k = 0u; k < count; ++k) {
        lo = min(lo, kids[k].xyz - kids[k].w);
        hi = max(hi, kids[k].xyz + kids[k].w);
    }
    const vec3 m = 0.5 * lo + 0.5 * hi;
    float r = 0.0;
    for (uint k = 0u; k < count; ++k) r = max(r, length(kids[k].xyz - m) + kids[k].w);
    return vec4(m, r * (1.0 + RH_PAD) + RH_PAD * max(rh_max_abs(m), rh_max_abs(hi - lo)) + 1e-30);
}

void main() {
    const uint i = rt_global_index();
    if (i >= ot_count) return;
    if (ot_mode == 0u) {
        const vec3 c = rh_spheres[i].xyz;
        ot_keys[i] = ot_spread_bits(ot_cell(c.x, ot_box_min.x)) << 2 | ot_spread_bits(ot_cell(c.y, ot_box_min.y)) << 1 |
                     ot_spread_bits(ot_cell(c.z, ot_box_min.z));
        rh_order[i] = i;
        return;
    }
    RhObject o;
    o.level = ot_level;
    o.pad = 0u;
    vec4 kids[16];
    vec3 lo = vec3(RT_INFINITY), hi = vec3(-RT_INFINITY);
    if (ot_mode == 1u) {
        o.first = i * ot_fanout;
        o.count = min(ot_fanout, ot_triangles - o.first);
        for (uint k = 0u; k < o.count; ++k) {
            const uint t = rh_order[o.first + k];
            kids[k] = rh_spheres[t];
            vec3 a, b, c;
            rh_load_triangle(t, a, b, c);
            lo = min(lo, min(a, min(b, c)));
            hi = max(hi, max(a, max(b, c)));
        }
    } else {
        o.first = ot_child_first + i * ot_fanout;
        o.count = min(ot_fanout, ot_child_count - i * ot_fanout);
        for (uint k = 0u; k < o.count; ++k) {
            const RhObject child = rh_objects[o.first + k];
            kids[k] = child.sphere;
            lo = min(lo, child.box_lo.xyz);
            hi = max(hi, child.box_hi.xyz);
        }
    }
    o.box_lo = vec4(lo, 0.0);
    o.box_hi = vec4(hi, 0.0);
    o.sphere = ot_union(kids, o.count);
    rh_objects[ot_node_first + i] = o;
}
