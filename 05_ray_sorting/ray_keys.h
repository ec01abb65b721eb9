// Ray keys and the CPU reference of the sorting pipeline (Garanzha & Loop 2010, "Fast Ray Sorting and
// Breadth-First Packet Traversal for GPU Ray Tracing", section 3; Reis's thesis, "Ray Indexing" to "Ray
// Decompression"). The GPU does the same in shaders/ (ray_sort.h); ray_sort_test.cpp checks that both agree bit for
// bit, so this file is also the readable specification of the GPU passes.
//
// The key of a ray, 32 bits, from the most significant bit down, in one of two orders (KeyOrder, chosen per batch
// kind by the renderer):
//
//   origin first (shadow rays):                  [ group : G ][ origin cell : O ][ direction cell : D ]
//   direction first (reflection, refraction):    [ group : G ][ coarse direction cell : D ][ origin cell : O ]
//
//  - group: primary 0, reflection 1, refraction 2, transparency 3, shadow ray towards light l: 3 + l (a batch holds
//    trace rays or shadow rays, never both). G = the bits max(4, 3 + lights) values need. Rays of different groups
//    never share a key, and groups sort in this order, so the sorted rays of a group stay in one range (the queues
//    of the wavefront pipeline hold the groups in the same order).
//  - origin: a virtual grid of CUBIC cells over the scene box: one cell size c on every axis, and per axis as many
//    bits as its extent needs, b_a = the least b >= 0 with extent_a <= c 2^b (a flat or thin axis gets few bits or
//    none). c is the least size with b_x + b_y + b_z <= O (and b_a <= 24): the finest cubic grid the budget allows.
//    A coordinate maps to floor((o - box_min) * s), s = 1 / c rounded to a float once (the same on every axis),
//    clamped to the grid; the cells are interleaved in Morton order (axes with fewer bits drop out of the top
//    levels), so nearby cells get nearby codes. O = key_bits - direction_bits; where cubic cells cannot use all of
//    O (at most 2 bits are lost to rounding each axis' count up to a power of two), the key is shorter.
//  - direction: octahedral mapping (Meyer et al. 2010): d / (|dx| + |dy| + |dz|) lies on the diamond |u| + |v| +
//    |w| = 1; the upper half (dz >= 0) projects to (u, v), the lower half folds over the diamond's edges to
//    ((1 - |v|) sign(u), (1 - |u|) sign(v)). Both coordinates are quantized to 2^du and 2^dv cells (D = du + dv).
//    dx and dy move (u, v) directly, dz moves both through the sum and picks the half: every component reaches the
//    key (Reis's published code computes an azimuth from atan2(d.x, d.x), so its key never sees d.y).
//  - when G + O + D > 32, the hash's lowest bits give way.
//
// Why this layout (05's README, "Measured: the cubic key against the first key and stage 04", has the figures):
//  - Cubic cells: a grid scaled per axis to the box gives a flat scene flat cells, and the Morton order then hops
//    between neighbouring objects.
//  - Reflection and refraction rays: a fine direction cell above the origin makes rays of one direction from
//    different surfaces neighbours; a COARSE direction cell (2 + 2 bits: 16 cells of the octahedron) above a fine
//    cubic origin code keeps the rays of one surface together within each of a few broad direction classes (rays
//    bouncing between mirrors, as in mirror_box, want more: --direction-bits 8, or --sort auto's fine key).
//  - Shadow rays towards a point light: the direction follows from the origin, so the origin goes first.
//
// Every step of a key uses only additions, multiplications and comparisons (no division, no sqrt, no atan), which
// IEEE 754 rounds the same way in C++ and GLSL: keys are equal on both, bit for bit. The layout (make_key_layout)
// keeps every shift below 32 and the scale a normal float in [2^-100, 2^100] (with box_min's subnormals flushed to
// zero), so a GPU that flushes subnormals still gets the CPU's cells.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/gpu/pipeline/wavefront.h"

namespace rt {

enum class KeyOrder { origin_first, direction_first };
const char* key_order_name(KeyOrder order);   // "origin first", "direction first"

struct RayKeyLayout {
    glm::vec3 box_min{0.0f};
    float origin_scale = 0.0f;       // cells per unit, the same on every axis (1 / cell size as a float; 0: none)
    double cell_size = 0.0;          // the cubic cell's edge, 1 / origin_scale (0 when no axis has bits)
    glm::uvec3 origin_bits{0u};      // bits per axis, from each axis' extent
    glm::uvec2 direction_bits{0u};   // u, v
    unsigned origin_total = 0;       // origin_bits.x + .y + .z
    unsigned direction_total = 0;    // direction_bits.x + .y
    unsigned hash_drop = 0;          // low hash bits given up for the group
    unsigned hash_bits = 0;          // hash bits kept
    unsigned group_count = 1;        // max(4, 3 + lights)
    unsigned key_bits = 0;           // origin_total + direction_total: the hash's length before the drop
    bool direction_major = false;    // the direction cell above the origin cell (KeyOrder::direction_first)
    unsigned sort_bits = 0;          // group bits + hash_bits: the bits the radix sort looks at
};

// key_bits (1..32): origin + direction bits; direction_bits (0..key_bits). Throws std::invalid_argument otherwise.
// Any box works: a flat axis gets no bits, a point-like, non-finite or absurdly large box none at all (every ray
// then has origin cell 0).
RayKeyLayout make_key_layout(glm::vec3 box_min, glm::vec3 box_max, unsigned key_bits, unsigned direction_bits,
                             unsigned lights, KeyOrder order = KeyOrder::origin_first);

std::uint32_t ray_group(const gpu::WavefrontRay& ray, const RayKeyLayout& layout);
std::uint32_t ray_key(const gpu::WavefrontRay& ray, const RayKeyLayout& layout);

// The pieces of the key, for tests.
std::uint32_t quantize_axis(float o, float box_min, float scale, unsigned bits);
std::uint32_t octahedral_cell(float n, float s, unsigned bits);
std::uint32_t origin_code(glm::vec3 origin, const RayKeyLayout& layout);   // the Morton code of the origin cell

// Compression: one chunk per run of equal keys.
struct RayChunks {
    std::vector<std::uint32_t> keys, bases, sizes;
};
RayChunks compress(const std::vector<std::uint32_t>& keys);
// Chunks sorted by key (stable: equal keys keep their order).
RayChunks sort_chunks(const RayChunks& chunks);
// Decompression: the rays of each chunk in chunk order, as indices (first + position in the key array).
std::vector<std::uint32_t> decompress(const RayChunks& sorted, std::uint32_t first = 0);
// The three steps: the sorted order of the rays with these keys (= a stable sort of the indices by key).
std::vector<std::uint32_t> sorted_order(const std::vector<std::uint32_t>& keys, std::uint32_t first = 0);

}  // namespace rt
