// Stage 05's ray sorting on the GPU (Garanzha & Loop 2010, section 3; Reis's pipeline): the rays of one batch of
// the wavefront queue, in an order that puts rays with the same key (origin cell, direction cell: ray_keys.h) next
// to each other, so the ray-space hierarchy built over them has tight nodes.
//
//   hashing        ray_keys.comp      key[i] of rays[first + i]
//   compression    chunk_heads.comp   head[i] = 1 where the key changes
//                  Scan::exclusive    chunk number of each head
//                  chunks.comp        chunk arrays: key, id, base (first ray), end
//                  chunk_tally.comp   the chunk count added to the frame's sums (statistics)
//   sorting        RadixSort          the chunks by key (stable; ids ride along), over the key's used bits only
//   decompression  chunk_sizes.comp   size of each sorted chunk; Scan::exclusive: where it starts in the output
//                  skeleton.comp      a skeleton of 1s gets each chunk's base at its start, with a head flag
//                  Scan::segmented_inclusive   the sorted order: base, base + 1, ... within each chunk
//
// The result is a permutation buffer: order[i] = the queue index (first + k) of the i-th ray in sorted order. Equal
// keys keep their queue order, so the order equals a stable sort of the rays by key (ray_keys.h: sorted_order), and
// each group (ray kind, light) keeps the range it has in the queue. Every buffer holds one uint per ray or chunk, so a
// batch whose rays fit a storage block fits too.
//
// Nothing is read back to the CPU: the chunk count (the sort's length) stays on the GPU, where the radix sort and
// the decompression read it; the passes are sized for n, its bound, so no batch waits for the GPU.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "common/gpu/gl/buffer.h"
#include "common/gpu/primitives/radix_sort.h"
#include "common/gpu/primitives/scan.h"
#include "common/gpu/gl/shader.h"
#include "ray_keys.h"

namespace rt {

class RaySorter {
public:
    RaySorter();   // needs a current context (compiles the passes)

    // The key layout rays are hashed with (the renderer sets it per batch kind: the scene box, the lights, the order).
    RayKeyLayout layout;

    // Keys of rays[first, first + count) (WavefrontRay) into keys()[0, count), then their sorted order into
    // `order` (count uints, grown as needed).
    void sort(const gpu::Buffer& rays, std::size_t first, std::size_t count, gpu::Buffer& order);
    // Hashing only.
    void compute_keys(const gpu::Buffer& rays, std::size_t first, std::size_t count);
    // Compression, sorting and decompression of keys[0, n) by their low sort_bits bits: order[i] = first + the index
    // of the i-th key in sorted order. `keys` is left as it is.
    void sort_keys(const gpu::Buffer& keys, std::size_t n, unsigned sort_bits, std::uint32_t first,
                   gpu::Buffer& order);

    const gpu::Buffer& keys() const { return keys_; }
    // Chunks of the last sort_keys (rays / chunks is the compression ratio), read back: one sync, for tests and tools.
    std::size_t chunk_count();

    // The chunk counts of every sort_keys are summed on the GPU in the tally slot set here (the renderer uses one
    // per batch kind); chunk_tally() reads the sums back (one sync), reset_tally() clears them and `syncs` (the
    // renderer calls it when a frame begins).
    static constexpr std::size_t kTallySlots = 3;
    std::size_t tally_slot = 0;
    std::array<std::uint64_t, kTallySlots> chunk_tally();
    void reset_tally();

    // Read-backs (each a wait for the GPU) since the last reset_tally(): chunk_count() and chunk_tally() only.
    std::uint64_t syncs = 0;

private:
    gpu::Program keys_pass_, heads_pass_, chunks_pass_, tally_pass_, sizes_pass_, skeleton_pass_;
    gpu::Scan scan_;
    gpu::RadixSort radix_;
    gpu::Buffer keys_, heads_, chunk_of_, chunk_keys_, chunk_ids_, chunk_bases_, chunk_ends_, sizes_, total_, tally_;
};

}  // namespace rt
