#include "radix_sort.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/gpu/gl/bindings.h"
#include "common/gpu/gl/storage_limit.h"

namespace rt::gpu {

namespace {
constexpr std::size_t kRadix = std::size_t(1) << kRadixBits;

std::size_t tiles_for(std::size_t n) { return (n + kSortTile - 1) / kSortTile; }

void dispatch_tiles(const Program& p, std::size_t tiles) {
    const glm::uvec3 grid = Program::grid_for(tiles, 1);   // one group a tile, 2D beyond kMaxGroupsX
    p.dispatch(grid.x, grid.y, grid.z);
}

// Binds elements [begin, begin + count) of a uint buffer.
void bind_window(const Buffer& b, GLuint binding, std::size_t begin, std::size_t count) {
    b.bind_range(binding, begin * 4, std::max<std::size_t>(count, 1) * 4);
}
}  // namespace

RadixSort::RadixSort()
    : count_(Program::compute("common/shaders/primitives/radix_count.comp")),
      scatter_(Program::compute("common/shaders/primitives/radix_scatter.comp")),
      tile_(Program::compute("common/shaders/primitives/radix_tile.comp")) {}

void RadixSort::sort(Buffer& keys, Buffer& values, std::size_t n, unsigned key_bits) {
    run(keys, values, n, nullptr, key_bits);
}

void RadixSort::sort(Buffer& keys, Buffer& values, std::size_t n, const Buffer& count, unsigned key_bits) {
    if (count.size() < 4) throw std::out_of_range("RadixSort: the count buffer holds no uint");
    run(keys, values, n, &count, key_bits);
}

void RadixSort::run(Buffer& keys, Buffer& values, std::size_t n, const Buffer* gpu_count, unsigned key_bits) {
    if (key_bits > 32) throw std::invalid_argument("RadixSort: key_bits " + std::to_string(key_bits) + " > 32");
    if (n > 0xffffffffu) throw std::length_error("RadixSort: more than 2^32 - 1 elements");
    if (keys.size() < n * 4 || values.size() < n * 4)
        throw std::out_of_range("RadixSort: buffers smaller than n uints");
    if (&keys == &values) throw std::invalid_argument("RadixSort: keys and values must be different buffers");
    if (n <= 1 || key_bits == 0) return;

    // Windows: whole tiles, at most one storage block, starting at offsets the binding alignment allows.
    GLint align = 0;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    std::size_t window = window_override_ ? window_override_ : max_storage_block_bytes() / 4 / kSortTile * kSortTile;
    if (window == 0 || window % kSortTile != 0 || (window * 4) % std::size_t(std::max(align, 1)) != 0)
        throw std::logic_error("RadixSort: window of " + std::to_string(window) + " elements is not whole tiles");
    // The digit counts are one array read by the scan, so they must fit one block: kRadix (64) uints per tile.
    check_storage_block("RadixSort counts", kRadix * tiles_for(n));

    keys_tmp_.reserve(n * 4);
    if (n <= kSortTile) {   // one tile: one work group, every pass (radix_tile.comp)
        sort_tile(keys, values, n, gpu_count, key_bits);
        return;
    }
    values_tmp_.reserve(n * 4);
    counts_.reserve(kRadix * tiles_for(n) * 4);
    Buffer* src_keys = &keys;
    Buffer* src_values = &values;
    Buffer* dst_keys = &keys_tmp_;
    Buffer* dst_values = &values_tmp_;
    for (unsigned shift = 0; shift < key_bits; shift += kRadixBits) {
        pass(*src_keys, *src_values, *dst_keys, *dst_values, n, shift, std::min(kRadixBits, key_bits - shift), window,
             gpu_count);
        std::swap(src_keys, dst_keys);
        std::swap(src_values, dst_values);
    }
    if (src_keys != &keys) {   // an odd number of passes ended in the scratch buffers
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        keys_tmp_.copy_to(keys, n * 4);
        values_tmp_.copy_to(values, n * 4);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    check_gl("RadixSort");
}

void RadixSort::sort_tile(Buffer& keys, Buffer& values, std::size_t n, const Buffer* gpu_count, unsigned key_bits) {
    values_tmp_.reserve(n * 4);
    counts_.reserve(4);
    bind_window(keys, kBindingSortKeysIn, 0, n);
    bind_window(values, kBindingSortValuesIn, 0, n);
    bind_window(keys_tmp_, kBindingSortKeysOut, 0, n);
    bind_window(values_tmp_, kBindingSortValuesOut, 0, n);
    (gpu_count ? *gpu_count : counts_).bind_range(kBindingSortCount, 0, 4);   // read only with a GPU count
    tile_.set("n", unsigned(n));
    tile_.set("tile_base", 0u);
    tile_.set("tiles", 1u);
    tile_.set("count_from_buffer", gpu_count ? 1u : 0u);
    tile_.set("key_bits", key_bits);
    tile_.dispatch(1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    check_gl("RadixSort (one tile)");
}

void RadixSort::pass(const Buffer& keys_in, const Buffer& values_in, Buffer& keys_out, Buffer& values_out,
                     std::size_t n, unsigned shift, unsigned bits, std::size_t window, const Buffer* gpu_count) {
    const std::size_t tiles = tiles_for(n);
    for (const Program* p : {&count_, &scatter_}) {
        p->set("tiles", unsigned(tiles));
        p->set("shift", shift);
        p->set("mask", (1u << bits) - 1u);
        p->set("count_from_buffer", gpu_count ? 1u : 0u);
    }
    // The count's binding holds a buffer even without a GPU count: the shaders do not read it then, but a compiler
    // may load it ahead of the branch.
    const Buffer& count_binding = gpu_count ? *gpu_count : counts_;
    scatter_.set("total", unsigned(n));
    const bool scan_here = tiles <= kScatterScanTiles && window >= n;   // radix_scatter.comp sums the counts itself
    // 1. Count the digits of every tile, window by window.
    bind_window(counts_, kBindingSortCounts, 0, kRadix * tiles);
    count_binding.bind_range(kBindingSortCount, 0, 4);
    for (std::size_t begin = 0; begin < n; begin += window) {
        const std::size_t count = std::min(window, n - begin);
        bind_window(keys_in, kBindingSortKeysIn, begin, count);
        count_.set("n", unsigned(count));
        count_.set("tile_base", unsigned(begin / kSortTile));
        dispatch_tiles(count_, tiles_for(count));
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    // 2. Where each (digit, tile) starts in the output (with few tiles, in the scatter).
    scatter_.set("scan_here", scan_here ? 1u : 0u);
    if (!scan_here) {
        scan_.exclusive(counts_, counts_, kRadix * tiles);
        count_binding.bind_range(kBindingSortCount, 0, 4);   // the scan used that point
    }
    // 3. Scatter every input window into every output window (one of each when the arrays fit one block).
    bind_window(counts_, kBindingSortCounts, 0, kRadix * tiles);
    for (std::size_t begin = 0; begin < n; begin += window) {
        const std::size_t count = std::min(window, n - begin);
        bind_window(keys_in, kBindingSortKeysIn, begin, count);
        bind_window(values_in, kBindingSortValuesIn, begin, count);
        scatter_.set("n", unsigned(count));
        scatter_.set("tile_base", unsigned(begin / kSortTile));
        for (std::size_t out = 0; out < n; out += window) {
            const std::size_t out_count = std::min(window, n - out);
            bind_window(keys_out, kBindingSortKeysOut, out, out_count);
            bind_window(values_out, kBindingSortValuesOut, out, out_count);
            scatter_.set("out_begin", unsigned(out));
            scatter_.set("out_end", unsigned(out + out_count));
            dispatch_tiles(scatter_, tiles_for(count));
        }
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace rt::gpu
