#include "scan.h"

#include <stdexcept>

#include "bindings.h"

namespace rt::gpu {

namespace {
constexpr GLbitfield kAllBarriers = GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT;

std::size_t block_count(std::size_t n) { return (n + kScanBlock - 1) / kScanBlock; }

void dispatch_blocks(const Program& p, std::size_t blocks) {
    if (blocks <= kMaxGroupsX) p.dispatch(unsigned(blocks));
    else p.dispatch(kMaxGroupsX, unsigned((blocks + kMaxGroupsX - 1) / kMaxGroupsX));
}
}  // namespace

Scan::Scan()
    : block_(Program::compute("common/scan_block.comp")),
      block_flags_(Program::compute("common/scan_block.comp", {{"SCAN_FLAGS", "1"}})),
      add_(Program::compute("common/scan_add.comp")) {}

void Scan::scan_level(const Program& block, const Buffer& in, Buffer& out, std::size_t n, std::size_t level) {
    const std::size_t blocks = block_count(n);
    sums_[level].reserve(blocks * sizeof(std::uint32_t));
    in.bind(kBindingScanIn);
    out.bind(kBindingScanOut);
    sums_[level].bind(kBindingScanSums);
    block.set("n", unsigned(n));
    dispatch_blocks(block, blocks);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (blocks > 1) {
        // Scan the block totals in place, then add them to every element of their block.
        scan_level(block_, sums_[level], sums_[level], blocks, level + 1);
        out.bind(kBindingScanOut);
        sums_[level].bind(kBindingScanSums);
        add_.set("n", unsigned(n));
        dispatch_blocks(add_, blocks);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

void Scan::run(const Program& first, const Buffer& in, Buffer& out, std::size_t n, Buffer* total,
               std::size_t total_offset) {
    if (n > 0xffffffffu) throw std::length_error("Scan: more than 2^32 - 1 elements");
    if (in.size() < n * 4 || out.size() < n * 4) throw std::out_of_range("Scan: buffers smaller than n uints");
    if (n == 0) {
        if (total) {
            const std::uint32_t zero = 0;
            total->upload(&zero, sizeof zero, total_offset);
        }
        return;
    }
    // One sums buffer per level, allocated before recursing (scan_level holds references into sums_).
    std::size_t top = 0;
    for (std::size_t m = n; block_count(m) > 1; m = block_count(m)) ++top;
    if (sums_.size() < top + 1) sums_.resize(top + 1);
    scan_level(first, in, out, n, 0);
    if (total) {
        // The top level is a single block whose total is the total of everything; it sits in that level's sums[0].
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        sums_[top].copy_to(*total, sizeof(std::uint32_t), 0, total_offset);
    }
    glMemoryBarrier(kAllBarriers);
    check_gl("Scan::exclusive");
}

void Scan::exclusive(const Buffer& in, Buffer& out, std::size_t n, Buffer* total, std::size_t total_offset) {
    run(block_, in, out, n, total, total_offset);
}

void Scan::exclusive_flags(const Buffer& flags, Buffer& out, std::size_t n, Buffer* total, std::size_t total_offset) {
    run(block_flags_, flags, out, n, total, total_offset);
}

// ---------------------------------------------------------------------------------------------------------------

Compaction::Compaction()
    : scatter_indices_(Program::compute("common/compact_scatter.comp")),
      scatter_values_(Program::compute("common/compact_scatter.comp", {{"COMPACT_VALUES", "1"}})) {}

void Compaction::run(const Program& scatter, const Buffer* values, const Buffer& flags, std::size_t n, Buffer& out,
                     Buffer& count, std::size_t count_offset) {
    if (out.size() < n * 4) throw std::out_of_range("Compaction: output smaller than n uints");
    offsets_.reserve(n * sizeof(std::uint32_t));
    scan_.exclusive_flags(flags, offsets_, n, &count, count_offset);
    if (n == 0) return;
    flags.bind(kBindingCompactFlags);
    offsets_.bind(kBindingCompactOffsets);
    if (values) values->bind(kBindingCompactValues);
    out.bind(kBindingCompactOut);
    scatter.set("n", unsigned(n));
    scatter.dispatch_threads(n);
    glMemoryBarrier(kAllBarriers);
    check_gl("Compaction");
}

void Compaction::compact_indices(const Buffer& flags, std::size_t n, Buffer& out, Buffer& count,
                                 std::size_t count_offset) {
    run(scatter_indices_, nullptr, flags, n, out, count, count_offset);
}

void Compaction::compact_values(const Buffer& values, const Buffer& flags, std::size_t n, Buffer& out, Buffer& count,
                                std::size_t count_offset) {
    if (values.size() < n * 4) throw std::out_of_range("Compaction: values smaller than n uints");
    run(scatter_values_, &values, flags, n, out, count, count_offset);
}

}  // namespace rt::gpu
