// Work-efficient exclusive prefix sum over uint arrays of any length, and stream compaction built on it (flag -> scan
// -> scatter). Multi-level: blocks of kScanBlock elements are scanned in shared memory by raking (scan_block.comp: each
// thread a run of 8 in registers, one thread the runs' totals), their totals are scanned recursively, and added back
// (scan_add.comp). The radix sort (radix_sort.h) uses Scan::exclusive on its digit counts; stage 05's decompression the
// inclusive and segmented scans.
//
// Exclusive and inclusive scans take any n up to 2^32 - 1: arrays beyond GL_MAX_SHADER_STORAGE_BLOCK_SIZE (llvmpipe:
// 128 MiB = 2^25 uints) are bound in windows of at most that size. The segmented scan and the compaction read or
// write anywhere in their arrays, so their n is limited to one storage block: beyond it they throw
// std::length_error naming the size and the limit. Only the elements used are bound, so buffers may be larger.
//
// Both classes need a current context when constructed (they compile their programs) and keep their temporary
// buffers between calls (grow-only). Calls only enqueue GPU work; they end with a memory barrier (shader storage,
// buffer update and command bits), so later passes, read-backs and indirect dispatches see the results.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/gpu/gl/buffer.h"
#include "common/gpu/gl/shader.h"

namespace rt::gpu {

constexpr std::size_t kScanBlock = 512;   // elements per work group (scan_common.glsl: SCAN_BLOCK)
// Up to this many elements, one work group scans them all, block after block (scan_block.comp: `whole`): one dispatch
// instead of three (block, sums, add). On llvmpipe each dispatch costs tens of microseconds whatever it holds, and a
// frame of stage 05 scans about 90 short arrays; 8 blocks keep the one group's serial walk short on a real GPU too.
constexpr std::size_t kScanWhole = 8 * kScanBlock;

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
    // out[i] = in[0] + ... + in[i]. In place allowed; `total` as above.
    void inclusive(const Buffer& in, Buffer& out, std::size_t n, Buffer* total = nullptr, std::size_t total_offset = 0);
    // Segmented inclusive scan: out[i] = in[h] + ... + in[i], where h is the last index <= i with heads[h] != 0
    // (0 when there is none): a new sum starts at every head flag. In place allowed (`out` may be `in`, not `heads`).
    void segmented_inclusive(const Buffer& in, const Buffer& heads, Buffer& out, std::size_t n);
    // Elements per window (bound range) for arrays beyond one storage block: for tests; 0 = from the GL limit.
    void set_window_for_testing(std::size_t elements) { window_override_ = elements; }

private:
    // The programs of one scan: `first` for the input level, `block` and `add` for the levels of block totals.
    struct Passes {
        const Program& first;
        const Program& block;
        const Program& add;
    };
    std::size_t window() const;
    bool scanned_whole(std::size_t n) const;   // n <= kScanWhole, in one window
    void run(const Passes& passes, const Buffer& in, Buffer& out, std::size_t n, Buffer* total, std::size_t offset);
    void scan_level(const Passes& passes, const Program& block, const Buffer& in, Buffer& out, std::size_t n,
                    std::size_t level);
    Program block_, block_flags_, block_inclusive_, add_;
    Program block_max_, block_heads_max_, add_max_, segments_;   // the segmented scan
    std::vector<Buffer> sums_;   // block totals per level
    Buffer segment_sums_, segment_heads_;
    std::size_t window_override_ = 0;
};

// Throws std::length_error("<what>: ... beyond this GPU's limit ...") when n uints exceed one shader storage block.
void check_storage_block(const char* what, std::size_t n);

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
