// Sizes of the radix sort's passes (radix_count.comp, radix_scatter.comp). Must match
// common/gpu/primitives/radix_sort.h.
#define RADIX_BITS 4u                                // bits of the key sorted per pass
#define RADIX (1u << RADIX_BITS)                     // buckets (digit values) per pass
#define SORT_THREADS 256u
#define SORT_ITEMS 16u                               // consecutive elements per thread
#define SORT_TILE (SORT_THREADS * SORT_ITEMS)        // elements per work group

// Per dispatch: n elements of this window (bound from its first element), the window's first tile among all
// `tiles`, and the digit: (key >> shift) & mask.
uniform uint n;
uniform uint tile_base;
uniform uint tiles;
uniform uint shift;
uniform uint mask;

// counts[digit * tiles + tile]: digit-major, so that the exclusive scan of the whole array gives each (digit, tile)
// its first output position, tiles in order within a digit: that order is what makes the sort stable.
uint count_index(uint digit, uint tile) { return digit * tiles + tile_base + tile; }
