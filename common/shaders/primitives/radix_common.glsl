// Sizes of the radix sort's passes (radix_count.comp, radix_scatter.comp). Must match
// common/gpu/primitives/radix_sort.h.
#define RADIX_BITS 6u                                // bits of the key sorted per pass
#define RADIX (1u << RADIX_BITS)                     // buckets (digit values) per pass
#define SORT_THREADS 64u                             // at least RADIX: thread d < RADIX handles digit d
#define SORT_ITEMS 64u                               // consecutive elements per thread
#define SORT_TILE (SORT_THREADS * SORT_ITEMS)        // elements per work group
#define SCATTER_SCAN_TILES 64u   // up to this many tiles, radix_scatter.comp scans the counts it needs itself

// Per dispatch: n elements of this window (bound from its first element), the window's first tile among all
// `tiles`, and the digit: (key >> shift) & mask.
uniform uint n;
uniform uint tile_base;
uniform uint tiles;
uniform uint shift;
uniform uint mask;

// count_from_buffer = 1: the host knows only a bound of the element count (n, tiles and total are sized for it);
// the count is sort_count, written by an earlier pass, so that nothing is read back to the CPU. The elements from
// the count on are left out: their tiles count nothing and scatter nothing.
uniform uint count_from_buffer;
layout(std430, binding = RT_BINDING_SORT_COUNT) readonly buffer SortCount { uint sort_count; };

// Elements of this window to sort: n, or those of the window below the GPU's count.
uint window_count() {
    if (count_from_buffer == 0u) return n;
    const uint begin = tile_base * SORT_TILE;
    return sort_count > begin ? min(n, sort_count - begin) : 0u;
}

// counts[digit * tiles + tile]: digit-major, so that the exclusive scan of the whole array gives each (digit, tile)
// its first output position, tiles in order within a digit: that order is what makes the sort stable.
uint count_index(uint digit, uint tile) { return digit * tiles + tile_base + tile; }
