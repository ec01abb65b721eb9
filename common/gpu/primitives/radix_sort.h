// Stable key-value radix sort of uint32 keys and values on the GPU (least significant digit first; Satish, Harris
// and Garland 2009 in its simplest form). Each pass sorts by RADIX_BITS = 6 bits of the key:
//   1. count  (radix_count.comp):   per tile of kSortTile keys, how many keys have each of the 64 digits;
//   2. scan   (Scan::exclusive):    of those counts, digit-major: where each (digit, tile) starts in the output;
//   3. scatter (radix_scatter.comp): each key and its value to that start plus its rank among the tile's keys of
//                                    the same digit, so keys with equal digits keep their order (stable).
// ceil(key_bits / 6) passes ping-pong between the caller's buffers and two kept scratch buffers. Arrays of at most
// kScatterScanTiles tiles skip step 2: each scatter work group sums the counts it needs (at most 64 x 64), which
// saves a dispatch per pass (stage 05 sorts ~16 short arrays a frame, 6 passes each). Arrays of at most one tile
// (kSortTile keys) take one dispatch for all passes: one work group counts, scans and scatters each pass itself
// (radix_tile.comp), the same order.
//
// Why 6 bits and 64 threads of 64 keys: the scatter's rank table (digits x threads) must fit shared memory (32 KiB on
// llvmpipe: 64 x 64 uints is 16 KiB), and a tile's threads share its barriers; on llvmpipe a work group runs on one
// core, so fewer threads each with more keys cost fewer barrier rounds, and 6-bit digits take a 32-bit key in 6
// passes instead of 8 (docs/benchmarks.md, "GPU radix sort", compares it with 4-bit digits, 256 threads of 16 keys
// and other tile sizes). Chosen on llvmpipe, where CI and most machines here run; a hardware GPU, where 64-thread
// groups hide less memory latency, may want another shape.
//
// Used by stage 03 (sorting (cell, triangle) pairs), stage 04 (the object tree's Morton codes) and stage 05 (ray
// chunks). Needs a current context when constructed; calls only enqueue GPU work and end with a memory barrier, like
// Scan.
//
// Any n up to 2^32 - 1: arrays larger than one shader storage block (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, llvmpipe
// 128 MiB = 2^25 uints) are bound in windows of at most that size, so nothing is bound past the limit.
#pragma once

#include <cstddef>

#include "common/gpu/gl/buffer.h"
#include "scan.h"
#include "common/gpu/gl/shader.h"

namespace rt::gpu {

constexpr std::size_t kSortTile = 4096;   // keys per work group (radix_common.glsl: SORT_TILE)
constexpr unsigned kRadixBits = 6;        // radix_common.glsl: RADIX_BITS
constexpr std::size_t kScatterScanTiles = 64;   // radix_common.glsl: SCATTER_SCAN_TILES

class RadixSort {
public:
    RadixSort();
    // Sorts keys[0..n) in place by their low key_bits bits (1..32; 0 leaves everything as it is), moving
    // values[0..n) along; elements with equal low bits keep their order, and the other bits of a key ride along
    // unchanged. Both buffers must hold n uints and be different buffers.
    void sort(Buffer& keys, Buffer& values, std::size_t n, unsigned key_bits = 32);
    // The same when only the GPU knows how many elements there are: the first uint of `count` (written by an earlier
    // pass, at most n) is the count, and n only a bound that sizes the passes. Nothing is read back. Elements from
    // the count on take no part (their values afterwards are unspecified).
    void sort(Buffer& keys, Buffer& values, std::size_t n, const Buffer& count, unsigned key_bits = 32);
    // Elements per window (bound range) for arrays beyond one storage block: for tests; 0 = from the GL limit.
    void set_window_for_testing(std::size_t elements) { window_override_ = elements; }

private:
    void run(Buffer& keys, Buffer& values, std::size_t n, const Buffer* gpu_count, unsigned key_bits);
    void sort_tile(Buffer& keys, Buffer& values, std::size_t n, const Buffer* gpu_count, unsigned key_bits);
    void pass(const Buffer& keys_in, const Buffer& values_in, Buffer& keys_out, Buffer& values_out, std::size_t n,
              unsigned shift, unsigned bits, std::size_t window, const Buffer* gpu_count);
    Scan scan_;
    Program count_, scatter_, tile_;
    Buffer keys_tmp_, values_tmp_, counts_;
    std::size_t window_override_ = 0;
};

}  // namespace rt::gpu
