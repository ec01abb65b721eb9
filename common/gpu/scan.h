// Work-efficient exclusive prefix sum (Blelloch scan) over uint arrays of any length, and stream compaction built on
// it (flag -> scan -> scatter). Multi-level: blocks of kScanBlock elements are scanned in shared memory
// (scan_block.comp), their totals are scanned recursively, and added back (scan_add.comp). Radix sorts (stages
// 04/05) use Scan::exclusive on their digit histograms.
//
// Both classes need a current context when constructed (they compile their programs) and keep their temporary
// buffers between calls (grow-only). Calls only enqueue GPU work; they end with a memory barrier (shader storage,
// buffer update and command bits), so later passes, read-backs and indirect dispatches see the results.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "buffer.h"
#include "shader.h"

namespace rt::gpu {

constexpr std::size_t kScanBlock = 512;   // elements per work group (scan_common.glsl: SCAN_BLOCK)

class Scan {
public:
    Scan();
    // out[i] = in[0] + ... + in[i-1] for i < n (uint arithmetic, wrapping). `in` and `out` may be the same buffer
    // (in-place). When `total` is given, the sum of all n values is written there as a uint at total_offset bytes
    // (on the GPU, no read-back). n = 0 writes only the total (0).
    void exclusive(const Buffer& in, Buffer& out, std::size_t n, Buffer* total = nullptr, std::size_t total_offset = 0);
    // The same, scanning (in[i] != 0 ? 1 : 0): the offsets of a stream compaction.
    void exclusive_flags(const Buffer& flags, Buffer& out, std::size_t n, Buffer* total = nullptr,
                         std::size_t total_offset = 0);

private:
    void run(const Program& first, const Buffer& in, Buffer& out, std::size_t n, Buffer* total, std::size_t offset);
    void scan_level(const Program& block, const Buffer& in, Buffer& out, std::size_t n, std::size_t level);
    Program block_, block_flags_, add_;
    std::vector<Buffer> sums_;   // block totals per level
};

class Compaction {
public:
    Compaction();
    // Writes the indices i < n with flags[i] != 0, in increasing order, to out[0..count), and count (a uint) to
    // `count` at count_offset bytes. `out` must hold n uints.
    void compact_indices(const Buffer& flags, std::size_t n, Buffer& out, Buffer& count, std::size_t count_offset = 0);
    // The same, writing values[i] instead of i.
    void compact_values(const Buffer& values, const Buffer& flags, std::size_t n, Buffer& out, Buffer& count,
                        std::size_t count_offset = 0);
    Scan& scan() { return scan_; }

private:
    void run(const Program& scatter, const Buffer* values, const Buffer& flags, std::size_t n, Buffer& out,
             Buffer& count, std::size_t count_offset);
    Scan scan_;
    Program scatter_indices_, scatter_values_;
    Buffer offsets_;
};

}  // namespace rt::gpu
