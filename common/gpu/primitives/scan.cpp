#include "scan.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "common/gpu/gl/bindings.h"
#include "common/gpu/gl/storage_limit.h"

namespace rt::gpu {

namespace {
constexpr GLbitfield kAllBarriers = GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT;

std::size_t block_count(std::size_t n) { return (n + kScanBlock - 1) / kScanBlock; }

void dispatch_blocks(const Program& p, std::size_t blocks) {
    const glm::uvec3 grid = Program::grid_for(blocks, 1);   // one group a block, 2D beyond kMaxGroupsX
    p.dispatch(grid.x, grid.y, grid.z);
}

// Binds uints [begin, begin + n) of a buffer (never more than the shader may see).
void bind_uints(const Buffer& b, GLuint binding, std::size_t n, std::size_t begin = 0) {
    b.bind_range(binding, begin * 4, std::max<std::size_t>(n, 1) * 4);
}
}  // namespace

void check_storage_block(const char* what, std::size_t n) {
    const std::size_t limit = max_storage_block_bytes();
    if (n > limit / 4)
        throw std::length_error(std::string(what) + ": " + std::to_string(n) + " elements need " +
                                describe_bytes(n * 4) + " in one shader storage block, beyond this GPU's limit "
                                "(GL_MAX_SHADER_STORAGE_BLOCK_SIZE) of " + describe_bytes(limit));
}

Scan::Scan()
    : block_(Program::compute("common/shaders/primitives/scan_block.comp")),
      block_flags_(Program::compute("common/shaders/primitives/scan_block.comp", {{"SCAN_FLAGS", "1"}})),
      block_inclusive_(Program::compute("common/shaders/primitives/scan_block.comp", {{"SCAN_INCLUSIVE", "1"}})),
      add_(Program::compute("common/shaders/primitives/scan_add.comp")),
      block_max_(Program::compute("common/shaders/primitives/scan_block.comp", {{"SCAN_MAX", "1"}})),
      block_heads_max_(Program::compute("common/shaders/primitives/scan_block.comp",
                                        {{"SCAN_HEADS", "1"}, {"SCAN_MAX", "1"}, {"SCAN_INCLUSIVE", "1"}})),
      add_max_(Program::compute("common/shaders/primitives/scan_add.comp", {{"SCAN_MAX", "1"}})),
      segments_(Program::compute("common/shaders/primitives/scan_segments.comp")) {}

std::size_t Scan::window() const {
    GLint align = 0;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    const std::size_t w = window_override_ ? window_override_ : max_storage_block_bytes() / 4 / kScanBlock * kScanBlock;
    if (w == 0 || w % kScanBlock != 0 || (w * 4) % std::size_t(std::max(align, 1)) != 0)
        throw std::logic_error("Scan: window of " + std::to_string(w) + " elements is not whole blocks");
    return w;
}

bool Scan::scanned_whole(std::size_t n) const { return n <= kScanWhole && n <= window(); }

// The arrays are bound window by window (whole blocks, at most one storage block each); the block sums of all
// windows go to one array (block_base: the window's first block), which is much smaller and bound whole.
void Scan::scan_level(const Passes& passes, const Program& block, const Buffer& in, Buffer& out, std::size_t n,
                      std::size_t level) {
    const std::size_t blocks = block_count(n), w = window();
    sums_[level].reserve(blocks * sizeof(std::uint32_t));
    bind_uints(sums_[level], kBindingScanSums, blocks);
    if (scanned_whole(n)) {   // one work group, block after block: the total in sums_[level][0]
        bind_uints(in, kBindingScanIn, n);
        bind_uints(out, kBindingScanOut, n);
        block.set("n", unsigned(n));
        block.set("block_base", 0u);
        block.set("whole", 1u);
        block.dispatch(1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        return;
    }
    block.set("whole", 0u);
    for (std::size_t begin = 0; begin < n; begin += w) {
        const std::size_t count = std::min(w, n - begin);
        bind_uints(in, kBindingScanIn, count, begin);
        bind_uints(out, kBindingScanOut, count, begin);
        block.set("n", unsigned(count));
        block.set("block_base", unsigned(begin / kScanBlock));
        dispatch_blocks(block, block_count(count));
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (blocks > 1) {
        // Scan the block totals in place, then add them to every element of their block.
        scan_level(passes, passes.block, sums_[level], sums_[level], blocks, level + 1);
        bind_uints(sums_[level], kBindingScanSums, blocks);
        for (std::size_t begin = 0; begin < n; begin += w) {
            const std::size_t count = std::min(w, n - begin);
            bind_uints(out, kBindingScanOut, count, begin);
            passes.add.set("n", unsigned(count));
            passes.add.set("block_base", unsigned(begin / kScanBlock));
            dispatch_blocks(passes.add, block_count(count));
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

void Scan::run(const Passes& passes, const Buffer& in, Buffer& out, std::size_t n, Buffer* total,
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
    for (std::size_t m = n; !scanned_whole(m); m = block_count(m)) ++top;
    if (sums_.size() < top + 1) sums_.resize(top + 1);
    scan_level(passes, passes.first, in, out, n, 0);
    if (total) {
        // The top level is scanned by one work group, whose total is the total of everything: that level's sums[0].
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        sums_[top].copy_to(*total, sizeof(std::uint32_t), 0, total_offset);
    }
    glMemoryBarrier(kAllBarriers);
    check_gl("Scan::exclusive");
}

void Scan::exclusive(const Buffer& in, Buffer& out, std::size_t n, Buffer* total, std::size_t total_offset) {
    run({block_, block_, add_}, in, out, n, total, total_offset);
}

void Scan::exclusive_flags(const Buffer& flags, Buffer& out, std::size_t n, Buffer* total, std::size_t total_offset) {
    run({block_flags_, block_, add_}, flags, out, n, total, total_offset);
}

void Scan::inclusive(const Buffer& in, Buffer& out, std::size_t n, Buffer* total, std::size_t total_offset) {
    run({block_inclusive_, block_, add_}, in, out, n, total, total_offset);
}

void Scan::segmented_inclusive(const Buffer& in, const Buffer& heads, Buffer& out, std::size_t n) {
    // Two whole-array scans and a difference: sums = inclusive scan of in; last_head = inclusive max-scan of
    // (heads[i] != 0 ? i : 0); out[i] = sums[i] - sums[last_head[i] - 1] (scan_segments.comp). That difference
    // reads sums anywhere, so the arrays must fit one storage block.
    check_storage_block("Scan::segmented_inclusive", n);
    if (heads.size() < n * 4) throw std::out_of_range("Scan: head flags smaller than n uints");
    if (n == 0) return;
    segment_sums_.reserve(n * 4);
    segment_heads_.reserve(n * 4);
    inclusive(in, segment_sums_, n);
    run({block_heads_max_, block_max_, add_max_}, heads, segment_heads_, n, nullptr, 0);
    bind_uints(segment_sums_, kBindingScanIn, n);
    bind_uints(segment_heads_, kBindingScanSums, n);
    bind_uints(out, kBindingScanOut, n);
    segments_.set("n", unsigned(n));
    segments_.dispatch_threads(n);
    glMemoryBarrier(kAllBarriers);
    check_gl("Scan::segmented_inclusive");
}

// ---------------------------------------------------------------------------------------------------------------

Compaction::Compaction()
    : scatter_indices_(Program::compute("common/shaders/primitives/compact_scatter.comp")),
      scatter_values_(Program::compute("common/shaders/primitives/compact_scatter.comp", {{"COMPACT_VALUES", "1"}})) {}

void Compaction::run(const Program& scatter, const Buffer* values, const Buffer& flags, std::size_t n, Buffer& out,
                     Buffer& count, std::size_t count_offset) {
    // The scatter writes anywhere in `out`, so the arrays must fit one storage block.
    check_storage_block("Compaction", n);
    if (out.size() < n * 4) throw std::out_of_range("Compaction: output smaller than n uints");
    offsets_.reserve(n * sizeof(std::uint32_t));
    scan_.exclusive_flags(flags, offsets_, n, &count, count_offset);
    if (n == 0) return;
    bind_uints(flags, kBindingCompactFlags, n);
    bind_uints(offsets_, kBindingCompactOffsets, n);
    if (values) bind_uints(*values, kBindingCompactValues, n);
    bind_uints(out, kBindingCompactOut, n);
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
