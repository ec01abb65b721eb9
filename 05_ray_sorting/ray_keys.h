// Ray keys and the CPU reference of the sorting pipeline (Garanzha & Loop 2010, "Fast Ray Sorting and
// Breadth-First Packet Traversal for GPU Ray Tracing", section 3; Reis's thesis, "Ray Indexing" to "Ray
// Decompression"). The GPU does the same in shaders/ (ray_sort.h); ray_sort_test.cpp checks that both agree bit for
// bit, so this file is also the readable specification of the GPU passes.
//
// The key of a ray, 32 bits, from the most significant bit down:
//
//   [ group : G bits ][ origin cell, Morton order : O bits ][ direction cell, Morton order : D bits ]
//
// or, with direction_major, the direction cell above the origin cell. Origin first suits shadow rays (towards a
// point light the direction follows from the origin); direction first suits reflection and refraction rays, whose
// neighbours on one surface may come from very different paths (in builtin:mirror_box, origin-major sorting puts
// rays of unrelated directions side by side and the hierarchy's cones open: 10x the local tests of queue order).
//
//  - group: primary 0, reflection 1, refraction 2, shadow ray towards light l: 3 + l. G = the bits 3 + lights
//    values need. Rays of different groups never share a key, and groups sort in this order, so the sorted rays of
//    a group stay in one range (the queues of the wavefront pipeline hold the groups in the same order).
//  - origin: the scene box split into a virtual grid of 2^ox x 2^oy x 2^oz cells (O = ox + oy + oz, split as evenly as
//    possible, x first); a coordinate maps to floor((o - box_min) * 2^bits / extent), clamped to the grid.
//  - direction: octahedral mapping (Meyer et al. 2010): d / (|dx| + |dy| + |dz|) lies on the diamond |u| + |v| +
//    |w| = 1; the upper half (dz >= 0) projects to (u, v), the lower half folds over the diamond's edges to
//    ((1 - |v|) sign(u), (1 - |u|) sign(v)). Both coordinates are quantized to 2^du and 2^dv cells (D = du + dv).
//    dx and dy move (u, v) directly, dz moves both through the sum and picks the half: every component reaches the
//    key (Reis's published code computes an azimuth from atan2(d.x, d.x), so its key never sees d.y).
//  - key_bits = O + D; when G + key_bits > 32, the hash's lowest bits give way (a coarser direction first).
//
// Every step uses only additions, multiplications and comparisons (no division, no sqrt, no atan), which IEEE 754
// rounds the same way in C++ and GLSL: keys are equal on both, bit for bit.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "common/gpu/wavefront.h"

namespace rt {

struct RayKeyLayout {
    glm::vec3 box_min{0.0f};
    glm::vec3 origin_scale{0.0f};    // cells per unit along each axis (0 for a flat axis)
    glm::uvec3 origin_bits{0u};
    glm::uvec2 direction_bits{0u};   // u, v
    unsigned hash_drop = 0;          // low hash bits given up for the group
    unsigned hash_bits = 0;          // hash bits kept
    unsigned group_count = 1;        // 3 + lights
    unsigned key_bits = 0;           // origin + direction bits
    bool direction_major = false;    // the direction cell above the origin cell (set per batch kind)
    unsigned sort_bits = 0;          // group bits + hash_bits: the bits the radix sort looks at
};

// key_bits (1..32): origin + direction bits; direction_bits (0..key_bits). Throws std::invalid_argument otherwise.
RayKeyLayout make_key_layout(glm::vec3 box_min, glm::vec3 box_max, unsigned key_bits, unsigned direction_bits,
                             unsigned lights);

std::uint32_t ray_group(const gpu::WavefrontRay& ray, const RayKeyLayout& layout);
std::uint32_t ray_key(const gpu::WavefrontRay& ray, const RayKeyLayout& layout);

// The pieces of the key, for tests.
std::uint32_t quantize_axis(float o, float box_min, float scale, unsigned bits);
std::uint32_t octahedral_cell(float n, float s, unsigned bits);

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
